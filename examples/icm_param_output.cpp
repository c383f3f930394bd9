// icm_param's output paths and pictures (icm_param_output.h).

#include "icm_param_output.h"

#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace icm_param {

namespace fs = std::filesystem;

/// Why the outputs cannot be written, found before hours of work rather than after: two
/// outputs on one file, an output over an input, a read-only target, a missing directory.
std::string check_output_paths(const Arguments& args)
{
  std::vector<std::pair<std::string, std::string>> outputs = {{"-o", args.output}};
  for(const auto& [option, path] :
      {std::pair<std::string, std::string>{"--svg", args.svg}, {"--png", args.png}, {"--preview", args.preview}})
    if(!path.empty())
      outputs.push_back({option, path});
  for(std::size_t i = 0; i < outputs.size(); ++i)
    for(std::size_t j = 0; j < i; ++j)
      if(ICM::internal::same_file(outputs[i].second, outputs[j].second))
        return outputs[j].first + " and " + outputs[i].first + " name the same file '" + outputs[i].second + "'";
  for(const auto& [option, path] : outputs)
  {
    if(ICM::internal::same_file(path, args.input))
      return option + " names the input file '" + path + "'";
    if(!args.seams.empty() && ICM::internal::same_file(path, args.seams))
      return option + " names the seam file '" + path + "'";
    const std::string refusal = ICM::internal::replace_refusal(path);
    if(!refusal.empty())
      return "cannot write '" + path + "': " + refusal;
    const fs::path directory = fs::path(path).parent_path();
    std::error_code ec;
    if(!directory.empty() && !fs::is_directory(directory, ec))
      return "cannot write '" + path + "': the directory '" + directory.string() + "' does not exist";
  }
  return {};
}

/// The pictures asked for, with the SVG's title.
ICM::IO::Uv_pictures pictures_of(const Arguments& args)
{
  ICM::IO::Uv_pictures pictures;
  pictures.svg = args.svg;
  pictures.png = args.png;
  pictures.preview = args.preview;
  pictures.svg_options.title = fs::path(args.input).filename().string() + " — ICM" +
                               (optimizes_energy(args) ? " (" + args.energy + ")" : std::string()) +
                               (prescribes_border(args) ? " (" + args.boundary + ")" : std::string());
#ifdef ICM_HAS_STB_IMAGE_WRITE
  pictures.png_options.size = args.picture_size;
  pictures.preview_options.size = args.picture_size;
#endif
  return pictures;
}

} // namespace icm_param
