// icm_param's command line, parsed with CLI11: the options and their help, each option's
// value checked as it is parsed, then what they mean together (the mode, one mesh or a batch,
// and the options that cannot go together), all before any file is read. A wrong command line
// gets the reason and the usage on stderr and exit code 2.

#include "icm_param_arguments.h"

#include <ICM/IO/write_uv_files.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/metrics/Inversive_distance_metric.h>
#include <ICM/metrics/Vertex_scaling_metric.h>

#include <CGAL/version.h>

#include <CLI/CLI.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#ifndef ICM_VERSION
#define ICM_VERSION "unknown"
#endif

namespace icm_param {

namespace {

namespace fs = std::filesystem;

const char* const usage =
  "usage: icm_param INPUT -o OUTPUT.obj|.ply|.gltf|.glb [--ply-binary] [--svg FILE] [--png FILE]\n"
  "         [--preview FILE] [--picture-size PIXELS] [--json] [--triangulate] [--quiet]\n"
  "         [--metric intrinsic-delaunay|vertex-scaling|inversive-distance|circle-packing]\n"
  "         [--energy entropy|u-square|area|angle|log-area] [--boundary free|circle|square|circle-domain]\n"
  "         [--cones auto|N] [--cone-target T] [--cone-placement linearized|exact]\n"
  "         [--cone-angles auto|entropy|least-log-area] [--no-cone-sweeps] [--cone VERTEX:DEGREES]...\n"
  "         [--seams FILE.selection.txt] [--keep-overlaps]\n"
  "         [--atlas SIZE [--padding TEXELS] [--atlas-packer skyline|shelf]]\n"
  "       icm_param INPUT... [--list FILE] -O OUTDIR [-j JOBS] [--format obj|ply|gltf|glb] [--resume]\n"
  "         [--timeout SECONDS] [--max-memory MB] [options above but -o and the pictures]\n"
  "       icm_param --help | --version\n";

/// The end of --help: what a script needs besides the options (doc/cli.md says the same).
const char* const help_footer =
  "Exit status:\n"
  "  0  the outputs are written (and after --help or --version)\n"
  "  1  the run failed, nothing is written: the input (or the --seams file, or a --cone vertex) cannot be\n"
  "     read or is not a mesh the options can take, the parameterization failed, an output cannot be\n"
  "     written, or memory ran out; in a batch (-O), some mesh failed (OUTDIR/summary.jsonl says why)\n"
  "  2  the command line is wrong, nothing is read or written (the reason and the usage go to stderr)\n"
  "\n"
  "Units: the UVs are in the mesh's units, each chart at its 3D scale (its UV area equals its 3D area),\n"
  "the charts side by side; with --atlas SIZE they are in [0,1]^2 instead, all charts at one scale.\n"
  "\n"
  "Example:\n"
  "  icm_param examples/data/three_peaks.off -o three_peaks_uv.obj --png three_peaks_uv.png \\\n"
  "    --preview three_peaks_preview.png --json\n";

std::string version_text()
{
  return std::string("icm_param ") + ICM_VERSION + " (CGAL " + CGAL_VERSION_STR + ", Eigen " +
         std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
         std::to_string(EIGEN_MINOR_VERSION) +
#ifdef ICM_HAS_CHOLMOD
         ", CHOLMOD"
#else
         ", without CHOLMOD"
#endif
         + ")";
}

// --- each option's value, checked as it is parsed -------------------------------------

/// `--cones auto|N`: -1 for auto, else the count.
CLI::Validator cone_count_validator()
{
  return CLI::Validator(
    [](std::string& v) -> std::string {
      if(v == "auto")
        return {};
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if(v.empty() || *end != '\0' || n < 0 || n > 100000)
        return "takes 'auto' or a count from 0 to 100000, not '" + v + "'";
      return {};
    },
    "");
}

/// `--cone VERTEX:DEGREES`, parsed into `cone`.
bool parse_cone(const std::string& v, std::pair<int, double>& cone)
{
  const std::size_t colon = v.find(':');
  if(colon == std::string::npos)
    return false;
  char *end_vertex = nullptr, *end_angle = nullptr;
  const long vertex = std::strtol(v.c_str(), &end_vertex, 10);
  const double degrees = std::strtod(v.c_str() + colon + 1, &end_angle);
  if(end_vertex != v.c_str() + colon || colon == 0 || vertex < 0 || vertex > 2147483647L || *end_angle != '\0' ||
     !(degrees > 0) || !std::isfinite(degrees))
    return false;
  cone = {static_cast<int>(vertex), degrees};
  return true;
}

CLI::Validator cone_validator()
{
  return CLI::Validator(
    [](std::string& v) -> std::string {
      std::pair<int, double> cone;
      return parse_cone(v, cone) ? std::string()
                                 : "takes VERTEX:DEGREES with a vertex index >= 0 and an angle > 0, not '" + v + "'";
    },
    "");
}

/// A whole number from `low` to `high` (a texel count), as `--atlas` and `--padding` take:
/// parsed into `value`, or false.
bool parse_texels(const std::string& v, long low, long high, int& value)
{
  char* end = nullptr;
  errno = 0;
  const long n = std::strtol(v.c_str(), &end, 10);
  if(v.empty() || *end != '\0' || errno != 0 || n < low || n > high)
    return false;
  value = static_cast<int>(n);
  return true;
}

CLI::Validator texel_validator(const std::string& what, long low, long high)
{
  return CLI::Validator(
    [what, low, high](std::string& v) -> std::string {
      int value = 0;
      return parse_texels(v, low, high, value)
               ? std::string()
               : "takes " + what + ", a whole number of texels from " + std::to_string(low) + " to " +
                   std::to_string(high) + ", not '" + v + "'";
    },
    "");
}

/// A wrong command line: the reason, then the usage; exit code 2.
int usage_error(const std::string& reason, const Failure_report& fail)
{
  const int code = fail(reason, 2);
  std::cerr << usage;
  return code;
}

/// What --energy takes: the entropy, then the energies minimised from it (icm_param_energy.h).
std::vector<std::string> energy_names()
{
  return {ICM::Curvature_entropy::name, ICM::U_square::name, ICM::Area_distortion::name, ICM::Angle_distortion::name,
          ICM::Log_area_distortion::name};
}

/// What --boundary takes: the free border (default), a CGAL border parameterizer's circle or
/// square, the circle domain of a surface with several border loops (doc/border_conditions.md).
std::vector<std::string> boundary_names()
{
  return {"free", "circle", "square", "circle-domain"};
}

// --- the options together --------------------------------------------------------------

/// Why the options cannot go with the energy or the border condition, or empty: a prescribed
/// border leaves no choice to an energy, and is solved on a disk without cones or seams.
std::string energy_conflict(const Arguments& args)
{
  if(!prescribes_border(args))
    return {};
  if(optimizes_energy(args))
    return "--energy " + args.energy + " cannot go with --boundary " + args.boundary +
           ": a prescribed border leaves one conformal map, nothing for an energy to choose";
  const char* option = !args.cones.empty()   ? "--cone"
                       : !args.seams.empty() ? "--seams"
                       : args.cones_asked    ? "--cones"
                                             : nullptr;
  if(option == nullptr)
    return {};
  return std::string(option) + " cannot go with --boundary " + args.boundary +
         ": a prescribed border is solved on the mesh as it is, without cones or seams";
}

/// The atlas options of `--atlas`, `--padding` and `--atlas-packer` (already checked one by
/// one) into `args.atlas`; why they do not go together, or empty.
std::string parse_atlas(const std::string& atlas_text, const std::string& padding_text, const std::string& packer_text,
                        Arguments& args)
{
  if(atlas_text.empty())
    return !padding_text.empty()  ? "--padding " + padding_text + " needs --atlas SIZE"
           : !packer_text.empty() ? "--atlas-packer " + packer_text + " needs --atlas SIZE"
                                  : std::string();
  if(prescribes_border(args))
    return "--atlas cannot go with --boundary " + args.boundary +
           ": a prescribed border is laid out by the disk parameterizer, which packs no charts";
  ICM::Atlas_options atlas;
  parse_texels(atlas_text, 1, 65536, atlas.size);
  if(!padding_text.empty())
    parse_texels(padding_text, 0, 32767, atlas.padding);
  if(!packer_text.empty())
    atlas.packer = packer_text == "shelf" ? ICM::Atlas_packer::Shelf : ICM::Atlas_packer::Skyline;
  if(const ICM::Status checked = ICM::check_options(atlas); !checked.ok())
  {
    if(atlas.padding > (atlas.size - 1) / 2)
      return "--padding " + std::to_string(atlas.padding) + " leaves no texel for the charts in a " +
             std::to_string(atlas.size) + " x " + std::to_string(atlas.size) + " atlas (" +
             std::to_string(atlas.padding) + " on each side of " + std::to_string(atlas.size) +
             "): it must be at most " + std::to_string((atlas.size - 1) / 2);
    return checked.message;
  }
  args.atlas = atlas;
  return {};
}

/// Why -o names no format written (a `.off` would otherwise be OBJ text under a name that
/// promises OFF), or --ply-binary goes with an output that is not PLY, or empty.
std::string output_format_conflict(const Arguments& args)
{
  const std::string refused = ICM::IO::why_uv_mesh_path_is_refused(args.output);
  if(!refused.empty())
    return "-o: " + refused;
  if(args.ply_binary && ICM::IO::uv_mesh_format(args.output) != ICM::IO::Uv_mesh_format::Ply)
    return "--ply-binary needs a .ply output, not '" + args.output + "'";
  for(const auto& [option, path] :
      {std::pair<std::string, std::string>{"--png", args.png}, {"--preview", args.preview}})
  {
    if(path.empty())
      continue;
#ifndef ICM_HAS_STB_IMAGE_WRITE
    return option + " needs stb_image_write (Debian: libstb-dev), which icm_param was built without";
#endif
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if(extension != ".png")
      return option + " writes PNG: name a .png file, not '" + path + "'";
  }
  return {};
}

/// -O, -j, --list, --format, --resume, --timeout, --max-memory, and the hidden --batch-item
/// by which a batch runs each mesh (icm_param_batch.h).
void add_batch_options(CLI::App& app, Arguments& args)
{
  Batch_options& batch = args.batch;
  app
    .add_option("-O,--output-dir", batch.output_dir,
                "a batch: write each INPUT's output to OUTDIR/NAME.FORMAT (NAME its file name without the extension) "
                "and a row per input to OUTDIR/summary.jsonl; each mesh runs in a process of its own")
    ->type_name("OUTDIR");
  app.add_option("--list", batch.list, "with -O: also the inputs named in FILE, one path a line ('#' comments)")
    ->type_name("FILE");
  app.add_option("-j,--jobs", batch.jobs, "with -O: meshes run at once (default 1)")
    ->check(CLI::Range(1, 1024))
    ->type_name("JOBS");
  app.add_option("--format", batch.format, "with -O: the outputs' format (default obj)")
    ->check(CLI::IsMember({"obj", "ply", "gltf", "glb"}))
    ->type_name("obj|ply|gltf|glb");
  app.add_flag("--resume", batch.resume,
               "with -O: skip the inputs whose row in OUTDIR/summary.jsonl says ok and whose output exists");
  app.add_option("--timeout", batch.timeout, "with -O: a mesh still running after SECONDS is stopped and fails")
    ->check(CLI::PositiveNumber)
    ->type_name("SECONDS");
  app
    .add_option("--max-memory", batch.max_memory_mb,
                "with -O: a mesh may use at most MB megabytes of address space, or it fails")
    ->check(CLI::PositiveNumber)
    ->type_name("MB");
  app.add_option("--batch-item", args.batch_item)->group(""); // hidden: set by the batch for each child
}

/// One mesh (INPUT -o OUTPUT), a batch (-O), or a batch's child (--batch-item): checks that
/// the options go with the mode and fills `args.input`, `args.output`. The reason they do
/// not, or empty.
std::string choose_mode(Arguments& args)
{
  Batch_options& batch = args.batch;
  if(!args.batch_item.empty()) // a child: its parent checked everything else
  {
    args.input = args.batch_item;
    args.output = batch_output_path(batch.output_dir, args.input, batch.format);
    args.json = args.quiet = true;
    return {};
  }
  if(batch.output_dir.empty())
  {
    for(const auto& [option, given] : {std::pair<const char*, bool>{"--list", !batch.list.empty()},
                                       {"-j", batch.jobs != 1},
                                       {"--format", batch.format != "obj"},
                                       {"--resume", batch.resume},
                                       {"--timeout", batch.timeout > 0},
                                       {"--max-memory", batch.max_memory_mb > 0}})
      if(given)
        return std::string(option) + " needs a batch: -O OUTDIR";
    if(batch.inputs.empty())
      return "no input file";
    if(batch.inputs.size() > 1)
      return "more than one input file ('" + batch.inputs[1] + "'): -O OUTDIR parameterizes several";
    if(args.output.empty())
      return "no output file (-o OUTPUT.obj|.ply|.gltf|.glb)";
    args.input = batch.inputs.front();
    return {};
  }
  for(const auto& [option, given] : {std::pair<const char*, bool>{"-o", !args.output.empty()},
                                     {"--svg", !args.svg.empty()},
                                     {"--png", !args.png.empty()},
                                     {"--preview", !args.preview.empty()}})
    if(given)
      return std::string(option) + " names one file: with -O OUTDIR each input's output is OUTDIR/NAME." +
             batch.format + " and there are no pictures";
  std::string error;
  if(!batch.list.empty() && !read_input_list(batch.list, batch.inputs, error))
    return error;
  args.output = batch_output_path(batch.output_dir, "NAME", batch.format); // for the format checks
  batch.quiet = args.quiet;
  batch.json = args.json;
  return {};
}

// --- the options -----------------------------------------------------------------------

/// The options checked one by one as they are parsed, and read together after.
struct Option_texts
{
  std::string cones, atlas, padding, packer;
  std::vector<std::string> cone;
};

/// INPUT, -o, the batch's options, the pictures and the JSON line: what is read and written.
void add_file_options(CLI::App& app, Arguments& args)
{
  app.add_option("input", args.batch.inputs, "mesh file: .off (and COFF, NOFF, STOFF, 4OFF), .obj, .ply, .stl")
    ->type_name("INPUT");
  app
    .add_option("-o,--output", args.output,
                "the UV'd mesh to write, in the format its extension names: .obj (v, vt, f), .ply (ASCII, or "
                "--ply-binary; per-corner texcoord), .gltf or .glb (glTF 2.0, vertices split at seams)")
    ->type_name("OUTPUT.obj|.ply|.gltf|.glb");
  add_batch_options(app, args);
  app.add_flag("--ply-binary", args.ply_binary, "write the .ply output in binary little-endian rather than ASCII");
  app.add_option("--svg", args.svg, "also write an SVG of the layout, faces coloured by log area ratio")
    ->type_name("FILE");
  app
    .add_option("--png", args.png,
                "also write a PNG of the layout: faces coloured by log area ratio, chart borders, "
                "flipped faces in black and green, a colour bar")
    ->type_name("FILE");
  app
    .add_option("--preview", args.preview,
                "also write a PNG of the surface textured with a checkerboard through the UVs, from a fixed camera")
    ->type_name("FILE");
  app.add_option("--picture-size", args.picture_size, "side of the PNG pictures in pixels (default 1024)")
    ->check(CLI::Range(16, 8192))
    ->type_name("PIXELS");
  app.add_flag("--json", args.json, "print the figures as one JSON line on stdout (a JSON error object on failure)");
}

/// --metric to --keep-overlaps: how the map is made.
void add_map_options(CLI::App& app, Arguments& args, Option_texts& texts)
{
  app.add_option("--metric", args.metric, "the discrete conformal metric (default " + args.metric + ")")
    ->check(CLI::IsMember({ICM::Intrinsic_delaunay_metric::name, ICM::Vertex_scaling_metric::name,
                           ICM::Inversive_distance_metric::name, ICM::Circle_packing_metric::name}))
    ->type_name("NAME");
  app
    .add_option("--energy", args.energy,
                "the energy minimised (default " + args.energy +
                  "); any other is minimised from it over the same border and cones")
    ->check(CLI::IsMember(energy_names()))
    ->type_name("NAME");
  app
    .add_option("--boundary", args.boundary,
                "the border condition (default free): circle or square (a disk's border on CGAL's "
                "arc-length circle or square), circle-domain (every border loop a circle, no cut; genus 0)")
    ->check(CLI::IsMember(boundary_names()))
    ->type_name("NAME");
  app
    .add_option("--cones", texts.cones,
                "automatic interior cones: 'auto' (default: until the linearized max |u - u0| <= 0.6, at most 32), "
                "exactly N (also on a disk whose free border is not extreme), 0 for none")
    ->check(cone_count_validator())
    ->type_name("auto|N");
  app
    .add_option("--cone-target", args.cone_target,
                "add cones until the linearized optimum's max |u - u0| is at most T (at most --cones N, default 32)")
    ->check(CLI::PositiveNumber)
    ->type_name("T");
  app
    .add_option("--cone-placement", args.cone_placement,
                "greedy cones on the linearized optimum (default) or on the exact one, from Algorithm 3's minima")
    ->check(CLI::IsMember({"linearized", "exact"}))
    ->type_name("NAME");
  app
    .add_option("--cone-angles", args.cone_angles,
                "the automatic cones' angles: the entropy's, the least linearized log^2 area's, or (auto) at --cones N "
                "on a closed surface whichever of the two measures better on the exact map")
    ->check(CLI::IsMember({"auto", "entropy", "least-log-area"}))
    ->type_name("NAME");
  app.add_flag("--no-cone-sweeps", args.no_cone_sweeps,
               "at --cones N on a closed surface, keep the greedy's cones where they are (by default a cone moves "
               "where the exact optimum then has less area distortion)");
  app.add_option("--cone", texts.cone, "a cone of DEGREES at the input's VERTEX (repeatable)")
    ->check(cone_validator())
    ->type_name("VERTEX:DEGREES");
  app
    .add_option("--seams", args.seams,
                "a CGAL selection file: cut along its edges (vertex index pairs, third line on), cones at the vertices "
                "of its first line (CGAL's orbifold cone files), their angles chosen by the optimum")
    ->type_name("FILE");
  app.add_flag("--keep-overlaps", args.keep_overlaps,
               "keep a chart that folds over itself (only count the overlaps); with a prescribed --boundary, whose one "
               "chart is not cut, write a map that does rather than fail");
}

/// --atlas, --padding and --atlas-packer: the charts packed for a texture.
void add_atlas_options(CLI::App& app, Option_texts& texts)
{
  app
    .add_option("--atlas", texts.atlas,
                "texture-ready UVs: every chart into the unit square for a SIZE x SIZE texture, all at one texel "
                "density, charts turned by a quarter turn where that packs them larger")
    ->check(texel_validator("the texture size", 1, 65536))
    ->type_name("SIZE");
  app
    .add_option("--padding", texts.padding,
                "with --atlas: texels kept free between charts and from the square's border (default 4: a texel "
                "apart down to the mipmap level of a quarter of the size)")
    ->check(texel_validator("the padding", 0, 32767))
    ->type_name("TEXELS");
  app
    .add_option(
      "--atlas-packer", texts.packer,
      std::string("with --atlas: how the charts' boxes are packed, stb_rect_pack's skyline or shelves (default ") +
        ICM::atlas_packer_name(ICM::default_atlas_packer()) + ")")
    ->check(CLI::IsMember({"skyline", "shelf"}))
    ->type_name("NAME");
}

/// What the options parsed into `args` and `texts` mean together: the mode, the cones, the
/// atlas, and the options that cannot go together. Returns -1 to go on, else 2 after a usage
/// error, which `fail` has reported.
int check_arguments(Arguments& args, const Option_texts& texts, const Failure_report& fail)
{
  if(const std::string mode = choose_mode(args); !mode.empty())
    return usage_error(mode, fail);
  if(!texts.cones.empty() && texts.cones != "auto")
    args.max_cones = std::atoi(texts.cones.c_str());
  args.cones_asked = (!texts.cones.empty() && args.max_cones != 0) || args.cone_target > 0;
  for(const std::string& text : texts.cone)
  {
    std::pair<int, double> cone;
    parse_cone(text, cone);
    args.cones.push_back(cone);
  }
  const std::string conflict = energy_conflict(args);
  if(!conflict.empty())
    return usage_error(conflict, fail);
  if(const std::string atlas = parse_atlas(texts.atlas, texts.padding, texts.packer, args); !atlas.empty())
    return usage_error(atlas, fail);
  const std::string format = output_format_conflict(args);
  if(!format.empty())
    return usage_error(format, fail);
  if(!args.batch.output_dir.empty() && args.batch_item.empty()) // last: it creates OUTDIR
    if(const std::string batch = check_batch(args.batch); !batch.empty())
      return usage_error(batch, fail);
  return -1;
}

} // namespace

/// Parses the command line into `args`. Returns -1 to go on, else the exit code (0 after
/// --help or --version, 2 on a usage error, which `fail` has reported).
int parse_arguments(int argc, char** argv, Arguments& args, const Failure_report& fail)
{
  CLI::App app("Conformal parameterization with least area distortion by the inverse curvature map:\n"
               "reads a mesh (OFF, OBJ, PLY or STL), writes it with UVs as OBJ (one vt per corner side of\n"
               "every seam), PLY (per-corner texcoord) or glTF (vertices split at seams). Output vertices\n"
               "are the input's in file order, without isolated ones, then one copy per extra fan of each\n"
               "split non-manifold vertex.",
               "icm_param");
  app.set_version_flag("--version", version_text());
  app.footer(help_footer);
  app.allow_extras(); // unknown options are reported below, by name
  Option_texts texts;
  add_file_options(app, args);
  add_map_options(app, args, texts);
  add_atlas_options(app, texts);
  app.add_flag("--triangulate", args.triangulate, "triangulate polygons (otherwise they are refused)");
  app.add_flag("-q,--quiet", args.quiet, "no progress line on stderr for large meshes");
  try
  {
    app.parse(argc, argv);
  }
  catch(const CLI::CallForHelp& e)
  {
    return app.exit(e);
  }
  catch(const CLI::CallForAllHelp& e)
  {
    return app.exit(e);
  }
  catch(const CLI::CallForVersion& e)
  {
    return app.exit(e);
  }
  catch(const CLI::ParseError& e)
  {
    return usage_error(e.what(), fail);
  }
  for(const std::string& extra : app.remaining())
    return usage_error("unknown option " + extra, fail);
  return check_arguments(args, texts, fail);
}

} // namespace icm_param
