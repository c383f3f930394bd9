// icm_param: parameterize any triangle mesh file with the inverse curvature map (cones and
// seams where its topology needs them, one chart per connected component) and write the UV'd
// mesh (OBJ with a vt per corner side of every seam, PLY with per-corner texcoords, or glTF
// split at the seams, by the extension of -o), optionally pictures (the layout as SVG or PNG,
// the surface with a checkerboard as PNG) and a JSON line.
//
//   icm_param INPUT -o OUTPUT.obj|.ply|.gltf|.glb [--ply-binary] [--svg FILE] [--png FILE] [--preview FILE]
//             [--picture-size PIXELS] [--json] [--triangulate] [--quiet]
//             [--metric intrinsic-delaunay|vertex-scaling|inversive-distance|circle-packing]
//             [--energy entropy|u-square|area|angle|log-area]
//             [--cones auto|N] [--cone VERTEX:DEGREES]... [--seams FILE.selection.txt]
//             [--keep-overlaps] [--atlas SIZE [--padding TEXELS]]   (icm_param --help for all)
//
// Every energy goes through ICM::parameterize (every surface, cones and seams where its
// topology needs them): the curvature entropy (the default) directly, another energy
// minimised over the border and the cones from there (icm_param_energy.h). A prescribed
// border (--boundary) goes through Inverse_curvature_map_parameterizer_3, on a disk.
//
// The input is untrusted: it is read by ICM's own checked readers (IO/read_polygon_soup.h),
// repaired only as users expect (isolated vertices dropped, non-manifold vertices split,
// polygons triangulated with --triangulate), and everything else refused with the reason.
// On any failure it prints one line on stderr naming the reason (and with --json a JSON error
// object on stdout), exits non-zero and changes no file: the mesh and the pictures are written to
// temporary files and renamed into place together, only when all were written. An output
// name whose extension names no format written is refused before any work.

#include <ICM/IO/read_seam_selection.h>
#include <ICM/IO/read_triangle_mesh.h>
#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_files.h>
#include <ICM/measures/Distortion.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/metrics/Inversive_distance_metric.h>
#include <ICM/metrics/Vertex_scaling_metric.h>
#include <ICM/parameterize.h>

#include "icm_param_batch.h"
#include "icm_param_energy.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/version.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <new>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#ifndef _WIN32
#include <unistd.h>
#endif

#ifndef ICM_VERSION
#define ICM_VERSION "unknown"
#endif

namespace {

using Kernel = icm_param::Kernel;
using Mesh = icm_param::Mesh;
namespace SMP = CGAL::Surface_mesh_parameterization;
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

/// Meshes from this size get a progress line on stderr (a run takes seconds from there).
constexpr std::size_t progress_min_faces = 100000;

struct Arguments
{
  std::string input, output, svg, png, preview, seams;
  int picture_size = 1024; // --picture-size: the PNG pictures' side
  bool json = false, keep_overlaps = false, triangulate = false, quiet = false, ply_binary = false;
  std::string metric = ICM::Default_metric::name;
  std::string energy = ICM::Curvature_entropy::name;
  std::string boundary = ICM::Free_border().name();
  int max_cones = -1;     // -1: automatic
  double cone_target = 0; // --cone-target: 0 unless given
  std::string cone_placement = "linearized";
  bool cones_asked = false;                  // --cones auto or N > 0, or --cone-target given
  std::vector<std::pair<int, double>> cones; // vertex index, cone angle in degrees
  /// --atlas SIZE [--padding TEXELS] [--atlas-packer NAME]: unset, UVs in the mesh's units.
  std::optional<ICM::Atlas_options> atlas;
  /// -O OUTDIR and the other batch options: many inputs, each in a process of its own.
  icm_param::Batch_options batch;
  /// --batch-item INPUT (hidden): this process is one mesh of a batch, run by its parent.
  std::string batch_item;
};

const char* const usage =
  "usage: icm_param INPUT -o OUTPUT.obj|.ply|.gltf|.glb [--ply-binary] [--svg FILE] [--png FILE]\n"
  "         [--preview FILE] [--picture-size PIXELS] [--json] [--triangulate] [--quiet]\n"
  "         [--metric intrinsic-delaunay|vertex-scaling|inversive-distance|circle-packing]\n"
  "         [--energy entropy|u-square|area|angle|log-area] [--boundary free|circle|square|circle-domain]\n"
  "         [--cones auto|N] [--cone-target T] [--cone-placement linearized|exact] [--cone VERTEX:DEGREES]...\n"
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

/// How a failure is told: one line on stderr, and with --json a JSON object on stdout.
class Failure_report
{
public:
  bool json = false;
  std::string input, output;

  int operator()(const std::string& reason, int exit_code = 1) const
  {
    std::cerr << "icm_param: " << reason << "\n";
    if(json)
    {
      Json error;
      error["error"] = reason;
      error["exit_code"] = exit_code;
      error["input"] = input;
      error["output"] = output;
      std::cout << error.dump(-1, ' ', false, Json::error_handler_t::replace) << "\n";
    }
    return exit_code;
  }
};

// --- the command line ------------------------------------------------------------------

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

bool optimizes_energy(const Arguments& args)
{
  return args.energy != ICM::Curvature_entropy::name;
}

/// What --boundary takes: the free border (default), a CGAL border parameterizer's circle or
/// square, the circle domain of a surface with several border loops (doc/border_conditions.md).
std::vector<std::string> boundary_names()
{
  return {"free", "circle", "square", "circle-domain"};
}

bool prescribes_border(const Arguments& args)
{
  return args.boundary != "free";
}

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
  icm_param::Batch_options& batch = args.batch;
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
  icm_param::Batch_options& batch = args.batch;
  if(!args.batch_item.empty()) // a child: its parent checked everything else
  {
    args.input = args.batch_item;
    args.output = icm_param::batch_output_path(batch.output_dir, args.input, batch.format);
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
  if(!batch.list.empty() && !icm_param::read_input_list(batch.list, batch.inputs, error))
    return error;
  args.output = icm_param::batch_output_path(batch.output_dir, "NAME", batch.format); // for the format checks
  batch.quiet = args.quiet;
  batch.json = args.json;
  return {};
}

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
  std::string cones_text, atlas_text, padding_text, packer_text;
  std::vector<std::string> cone_texts;
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
    .add_option("--cones", cones_text,
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
  app.add_option("--cone", cone_texts, "a cone of DEGREES at the input's VERTEX (repeatable)")
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
  app
    .add_option("--atlas", atlas_text,
                "texture-ready UVs: every chart into the unit square for a SIZE x SIZE texture, all at one texel "
                "density, charts turned by a quarter turn where that packs them larger")
    ->check(texel_validator("the texture size", 1, 65536))
    ->type_name("SIZE");
  app
    .add_option("--padding", padding_text,
                "with --atlas: texels kept free between charts and from the square's border (default 4: a texel "
                "apart down to the mipmap level of a quarter of the size)")
    ->check(texel_validator("the padding", 0, 32767))
    ->type_name("TEXELS");
  app
    .add_option(
      "--atlas-packer", packer_text,
      std::string("with --atlas: how the charts' boxes are packed, stb_rect_pack's skyline or shelves (default ") +
        ICM::atlas_packer_name(ICM::default_atlas_packer()) + ")")
    ->check(CLI::IsMember({"skyline", "shelf"}))
    ->type_name("NAME");
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
  if(const std::string mode = choose_mode(args); !mode.empty())
    return usage_error(mode, fail);
  if(!cones_text.empty() && cones_text != "auto")
    args.max_cones = std::atoi(cones_text.c_str());
  args.cones_asked = (!cones_text.empty() && args.max_cones != 0) || args.cone_target > 0;
  for(const std::string& text : cone_texts)
  {
    std::pair<int, double> cone;
    parse_cone(text, cone);
    args.cones.push_back(cone);
  }
  const std::string conflict = energy_conflict(args);
  if(!conflict.empty())
    return usage_error(conflict, fail);
  if(const std::string atlas = parse_atlas(atlas_text, padding_text, packer_text, args); !atlas.empty())
    return usage_error(atlas, fail);
  const std::string format = output_format_conflict(args);
  if(!format.empty())
    return usage_error(format, fail);
  if(!args.batch.output_dir.empty() && args.batch_item.empty()) // last: it creates OUTDIR
    if(const std::string batch = icm_param::check_batch(args.batch); !batch.empty())
      return usage_error(batch, fail);
  return -1;
}

// --- checks before any work ------------------------------------------------------------

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

// --- input -----------------------------------------------------------------------------

/// The vertices of `mesh` that each of the input file's vertex indices names (none for a
/// dropped isolated vertex, several for a split non-manifold one).
std::vector<std::vector<Mesh::Vertex_index>> vertices_by_file_index(const Mesh& mesh,
                                                                    const ICM::IO::Mesh_reading_report& read)
{
  std::vector<std::vector<Mesh::Vertex_index>> by_index(read.file_vertices);
  std::size_t i = 0;
  for(Mesh::Vertex_index v : vertices(mesh))
    by_index[read.file_vertex[i++]].push_back(v);
  return by_index;
}

/// The user's cones as curvatures at vertices of the mesh; empty `error` on success.
std::map<Mesh::Vertex_index, double>
user_cones(const Arguments& args, const std::vector<std::vector<Mesh::Vertex_index>>& by_index, std::string& error)
{
  std::map<Mesh::Vertex_index, double> cones;
  for(const auto& [vertex, degrees] : args.cones)
  {
    const std::string option = "--cone " + std::to_string(vertex) + ": ";
    if(static_cast<std::size_t>(vertex) >= by_index.size())
      error = option + "the mesh has " + std::to_string(by_index.size()) + " vertices";
    else if(by_index[vertex].empty())
      error = option + "vertex " + std::to_string(vertex) + " is in no face (it was dropped)";
    else if(by_index[vertex].size() > 1)
      error = option + "vertex " + std::to_string(vertex) + " is non-manifold and was split into " +
              std::to_string(by_index[vertex].size()) + " vertices";
    if(!error.empty())
      return {};
    cones[by_index[vertex].front()] = 2 * M_PI - degrees * M_PI / 180;
  }
  return cones;
}

/// The cones (first line) and seams (third line on) of the --seams file, as CGAL's orbifold
/// and seam examples write them: the cones join `cones` with the angle the optimum chooses (a
/// --cone at the same vertex keeps its angle); empty `error` on success.
bool read_selection_cones_and_seams(const Arguments& args, const Mesh& mesh,
                                    const std::vector<std::vector<Mesh::Vertex_index>>& by_index,
                                    std::map<Mesh::Vertex_index, double>& cones, std::vector<Mesh::Edge_index>& seams,
                                    std::string& error)
{
  std::vector<Mesh::Vertex_index> selected;
  if(!ICM::IO::read_selection(args.seams, mesh, by_index, selected, seams, error))
    return false;
  for(Mesh::Vertex_index v : selected)
    cones.emplace(v, std::nan(""));
  return true;
}

// --- progress --------------------------------------------------------------------------

/// "icm_param: cones 12%, 9 s, about 70 s left" on stderr, rewritten in place on a terminal:
/// the stage, the share of the run done, the seconds since it began and, once enough of it
/// is done to extrapolate from, the time left at the pace so far (a rough guess: the shares
/// are fixed per stage, not measured). Shown whenever the stage changes, otherwise at most
/// four times a second on a terminal and every few seconds in a log, whatever the rate of
/// the library's callbacks (one per greedy cone round).
class Progress_line
{
public:
  explicit Progress_line(bool shown) : shown_(shown), start_(Clock::now())
  {
#ifndef _WIN32
    terminal_ = ::isatty(2) != 0;
#endif
  }
  void operator()(const std::string& stage, double fraction)
  {
    if(!shown_)
      return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if(stage == stage_ && elapsed - shown_at_ < (terminal_ ? 0.25 : 5.0))
      return;
    stage_ = stage;
    shown_at_ = elapsed;
    fraction = std::clamp(fraction, 0.0, 1.0);
    std::cerr << (terminal_ ? "\r" : "") << "icm_param: " << stage << " "
              << static_cast<int>(std::floor(100 * fraction)) << "%, " << duration_text(elapsed);
    if(fraction >= least_fraction_for_an_estimate && fraction < 1)
      std::cerr << ", about " << duration_text(elapsed * (1 - fraction) / fraction) << " left";
    std::cerr << (terminal_ ? "\x1b[K" : "\n") << std::flush;
    open_ = terminal_;
  }
  /// Ends the line on a terminal, so that what follows starts on its own.
  void finish()
  {
    if(open_)
      std::cerr << "\n";
    open_ = false;
  }

private:
  using Clock = std::chrono::steady_clock;
  /// Below this share done, the pace so far says too little of the rest.
  static constexpr double least_fraction_for_an_estimate = 0.03;

  static std::string duration_text(double seconds)
  {
    return seconds < 120 ? std::to_string(static_cast<long>(seconds)) + " s"
                         : std::to_string(static_cast<long>(std::lround(seconds / 60))) + " min";
  }

  bool shown_, terminal_ = false, open_ = false;
  Clock::time_point start_;
  std::string stage_;
  double shown_at_ = 0;
};

// --- output ----------------------------------------------------------------------------

/// What the JSON line and the summary line tell of a run, from either parameterizer's report:
/// totals over the charts and the worst of each check.
struct Run_figures
{
  int charts = 1, components = 1, cones = 0, wide_cones = 0, cones_given_up = 0, genus = 0, loops = 0, newton = 0,
      moved = 0;
  /// Pairs of crossing border edges, after and before overlap removal (the parameterizer of
  /// an energy or a prescribed border removes none: both are its count).
  std::optional<int> overlaps, raw_overlaps;
  std::size_t seam_edges = 0;
  double seam_length = 0; ///< over the square root of the 3D area
  double curvature_error = 0, length_error = 0, seam_error = 0;
  std::string metrics, fallbacks, layout;
  double seconds_index = 0, seconds_cones = 0, seconds_optimum = 0, seconds_cut = 0, seconds_layout = 0,
         seconds_parameterize = 0;
  std::string energy = ICM::Curvature_entropy::name;
  /// An energy other than the entropy: its optimizer's steps, E at the entropy optimum and
  /// at the result, and why it stopped early (empty if it converged).
  bool optimized_energy = false;
  int energy_iterations = 0;
  double initial_energy = 0, final_energy = 0;
  std::string energy_message;
  /// The border condition (doc/border_conditions.md): "free" unless --boundary prescribed one,
  /// then its faces flat on a straight side, its outer iterations and its circles' deviation.
  std::string boundary = "free";
  int degenerate_faces = 0, border_iterations = 0;
  double circle_deviation = 0;
  /// --atlas: the charts packed, those turned, the share of the square their triangles cover.
  int atlas_charts = 0, atlas_rotated_charts = 0;
  double atlas_utilization = 0;

  /// `ICM::parameterize`'s run of `energy_` with `seam_edges` cut (the energy over the
  /// components: `ICM::energy_summary`).
  Run_figures(const ICM::Surface_parameterization_report& report, std::size_t seam_edges_, const std::string& energy_)
    : components(static_cast<int>(report.charts.size())), seam_edges(seam_edges_), seconds_index(report.seconds_index),
      seconds_cones(report.seconds_cones), seconds_optimum(report.seconds_optimum), seconds_cut(report.seconds_cut),
      seconds_layout(report.seconds_layout), seconds_parameterize(report.seconds_total), energy(energy_),
      optimized_energy(energy_ != ICM::Curvature_entropy::name)
  {
    if(optimized_energy)
    {
      const ICM::Energy_summary summary = ICM::energy_summary(report);
      energy_iterations = summary.iterations;
      initial_energy = summary.initial_energy;
      final_energy = summary.final_energy;
      energy_message = summary.message;
    }
    const ICM::Surface_summary s = ICM::surface_summary(report);
    charts = s.charts;
    cones = s.cones;
    wide_cones = s.wide_cones;
    cones_given_up = s.cones_given_up;
    genus = s.genus;
    loops = s.boundary_loops;
    newton = s.newton_iterations;
    moved = s.moved_vertices;
    overlaps = s.overlapping_border_edges;
    raw_overlaps = s.raw_overlapping_border_edges;
    curvature_error = s.max_curvature_error;
    length_error = s.max_layout_length_error;
    seam_error = s.seam_length_error;
    metrics = s.metrics;
    layout = s.layouts;
    fallbacks = s.fallback_reason;
  }

  /// `Inverse_curvature_map_parameterizer_3`'s run (a prescribed border): one chart, never cut.
  explicit Run_figures(const ICM::Parameterization_report& report)
    : loops(report.boundary_loops), newton(report.newton_iterations), moved(report.moved_vertices),
      overlaps(report.overlapping_border_edges), raw_overlaps(report.overlapping_border_edges),
      curvature_error(report.max_curvature_error), length_error(report.max_layout_length_error), metrics(report.metric),
      fallbacks(report.fallback_reason), layout(report.layout), seconds_index(report.seconds_index),
      seconds_optimum(report.seconds_optimum), seconds_layout(report.seconds_layout),
      seconds_parameterize(report.seconds_total), boundary(report.border_condition),
      degenerate_faces(report.degenerate_faces), border_iterations(report.border_iterations),
      circle_deviation(report.circle_deviation)
  {}
};

struct Timings
{
  double read = 0, write = 0, total = 0;
};

Json optional_count(const std::optional<int>& n)
{
  return n ? Json(*n) : Json();
}

Json summary_json(const Arguments& args, const Mesh& mesh, const ICM::IO::Mesh_reading_report& read,
                  const Run_figures& t, const ICM::Distortion_measures& measures, const Timings& seconds)
{
  Json j;
  j["input"] = args.input;
  j["output"] = args.output;
  j["vertices"] = num_vertices(mesh);
  j["faces"] = num_faces(mesh);
  j["charts"] = t.charts;
  j["components"] = t.components;
  j["boundary_loops"] = t.loops;
  j["genus"] = t.genus;
  j["cones"] = t.cones;
  j["cones_above_full_turn"] = t.wide_cones;
  j["cones_given_up"] = t.cones_given_up;
  j["seam_edges"] = t.seam_edges;
  j["seam_length"] = t.seam_length;
  j["layout"] = t.layout;
  j["newton_iterations"] = t.newton;
  j["max_curvature_error"] = t.curvature_error;
  j["max_layout_length_error"] = t.length_error;
  j["seam_length_error"] = t.seam_error;
  j["overlapping_border_edges"] = optional_count(t.overlaps);
  j["raw_overlapping_border_edges"] = optional_count(t.raw_overlaps);
  j["moved_vertices"] = t.moved;
  j["metric"] = t.metrics;
  j["metric_fallback"] = t.fallbacks;
  j["energy"] = t.energy;
  if(t.optimized_energy)
  {
    j["energy_iterations"] = t.energy_iterations;
    j["initial_energy"] = t.initial_energy;
    j["final_energy"] = t.final_energy;
    j["energy_message"] = t.energy_message;
  }
  j["boundary"] = t.boundary;
  if(t.boundary != "free")
  {
    j["degenerate_faces"] = t.degenerate_faces;
    j["border_iterations"] = t.border_iterations;
    j["circle_deviation"] = t.circle_deviation;
  }
  if(args.atlas)
  {
    j["atlas_size"] = args.atlas->size;
    j["atlas_padding"] = args.atlas->padding;
    j["atlas_packer"] = ICM::atlas_packer_name(args.atlas->packer);
    j["atlas_charts"] = t.atlas_charts;
    j["atlas_rotated_charts"] = t.atlas_rotated_charts;
    j["atlas_utilization"] = t.atlas_utilization;
  }
  j["flipped_faces"] = measures.flipped_faces;
  j["log_area_distortion"] = measures.log_area_distortion;
  j["log_area_distortion_area_weighted"] = measures.log_area_distortion_area_weighted;
  j["area_ratio_min"] = measures.area_ratio_min;
  j["area_ratio_max"] = measures.area_ratio_max;
  j["qc_mean"] = measures.qc_mean;
  j["isolated_vertices_dropped"] = read.isolated_vertices.size();
  j["vertices_split"] = read.split_vertices.size();
  j["faces_triangulated"] = read.triangulated_faces;
  j["faces_reoriented"] = read.reoriented_faces.size();
  j["repairs"] = read.repairs();
  j["seconds_read"] = seconds.read;
  j["seconds_index"] = t.seconds_index;
  j["seconds_cones"] = t.seconds_cones;
  j["seconds_optimum"] = t.seconds_optimum;
  j["seconds_cut"] = t.seconds_cut;
  j["seconds_layout"] = t.seconds_layout;
  j["seconds_parameterize"] = t.seconds_parameterize;
  j["seconds_write"] = seconds.write;
  j["seconds_total"] = seconds.total;
  return j;
}

/// "1 chart", "3 charts": `n` and the noun, plural unless one.
std::string count_of(long long n, const std::string& noun)
{
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

/// The summary line: components and charts apart, as the JSON's `components` and `charts`
/// (the overlap removal cuts a component into several charts).
void print_summary_line(const Arguments& args, const Mesh& mesh, const Run_figures& t,
                        const ICM::Distortion_measures& measures)
{
  std::cerr << args.input << ": " << num_vertices(mesh) << " vertices, " << num_faces(mesh) << " faces, "
            << count_of(t.components, "component") << ", " << count_of(t.charts, "chart") << ", "
            << count_of(t.cones, "cone") << ", " << count_of(static_cast<long long>(t.seam_edges), "seam edge") << ", "
            << t.newton << " Newton iterations, max |k| " << t.curvature_error << ", ";
  if(t.optimized_energy)
    std::cerr << t.energy << " energy " << t.initial_energy << " -> " << t.final_energy << " in " << t.energy_iterations
              << " steps, ";
  if(args.atlas)
    std::cerr << "atlas " << args.atlas->size << " texels, " << count_of(t.atlas_charts, "chart") << " covering "
              << 100 * t.atlas_utilization << "%, ";
  std::cerr << measures.flipped_faces << " flipped faces, log area distortion " << measures.log_area_distortion << ", "
            << t.seconds_parameterize << " s -> " << args.output << "\n";
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

// --- the run ---------------------------------------------------------------------------

template <class Metric>
ICM::Surface_parameterization_report
run_metric(const Mesh& mesh, Mesh::Property_map<Mesh::Halfedge_index, Kernel::Point_2> uv,
           const ICM::Surface_parameterization_options& options, const std::map<Mesh::Vertex_index, double>& cones,
           std::vector<Mesh::Edge_index>& seams, const std::vector<Mesh::Edge_index>& user_seams)
{
  return ICM::parameterize<Metric>(mesh, uv, options, cones, &seams, user_seams);
}

/// A prescribed border by name; the parameterizer is instantiated for each in
/// icm_param_border.cpp.
ICM::Parameterization_report run_border(const Arguments& args, Mesh& mesh, icm_param::Corner_uv_map uvmap)
{
  using namespace icm_param;
  if(args.boundary == "circle")
    return parameterize_disk<ICM::Circular_border<Mesh>>(mesh, args.metric, uvmap);
  if(args.boundary == "square")
    return parameterize_disk<ICM::Square_border<Mesh>>(mesh, args.metric, uvmap);
  return parameterize_disk<ICM::Circle_domain>(mesh, args.metric, uvmap);
}

/// Why the map of a prescribed border is not written, or empty: it folds over itself, and
/// one chart with a UV per vertex cannot be cut apart where it does, as the free border's
/// charts are.
std::string why_an_overlap_is_refused(const Arguments& args, const ICM::Parameterization_report& report)
{
  if(args.keep_overlaps || report.overlapping_border_edges == 0)
    return {};
  return std::string(ICM::error_message(SMP::ERROR_NO_1_TO_1_MAPPING)) + ": the map with the " + args.boundary +
         " border folds over itself (" + std::to_string(report.overlapping_border_edges) +
         " pairs of border edges cross) and is one chart, not cut where it overlaps (with a free border it "
         "is); --keep-overlaps writes it anyway";
}

/// Any energy on any surface, by `ICM::parameterize` (cones and seams where needed): the
/// figures of its run into `figures`, or the reason it failed. The entropy's runs are
/// instantiated here, the other energies' each in its own file (icm_param_energy.h).
std::string run_surface(const Arguments& args, const Mesh& mesh, const std::map<Mesh::Vertex_index, double>& cones,
                        const std::vector<Mesh::Edge_index>& user_seams, icm_param::Corner_uv_map uvmap,
                        std::optional<Run_figures>& figures)
{
  ICM::Surface_parameterization_options options;
  options.remove_overlaps = !args.keep_overlaps;
  options.atlas = args.atlas;
  if(args.max_cones >= 0)
  {
    options.automatic_cones = args.max_cones > 0;
    options.cones.max_cones = args.max_cones;
    options.initial_cones = std::min(options.initial_cones, args.max_cones);
    // A count is exact: no stop on distortion, and a disk gets its cones too.
    options.cones.max_log_scale = 0;
    options.border_max_log_scale = 0;
  }
  if(args.cone_target > 0)
    options.cones.max_log_scale = args.cone_target;
  if(args.cone_placement == "exact")
    options.cones.placement = ICM::Cone_placement::Exact_optimum;
  // A selection file's cones and seams are the singular set, as in CGAL's orbifold examples
  // (its seams alone turn automatic cones off in the library): --cones adds to them.
  if(!args.seams.empty() && !args.cones_asked)
    options.automatic_cones = false;
  Progress_line progress(!args.quiet && num_faces(mesh) >= progress_min_faces);
  options.progress = [&progress](const std::string& stage, double fraction) { progress(stage, fraction); };

  std::vector<Mesh::Edge_index> seams;
  using namespace icm_param;
  const ICM::Surface_parameterization_report report =
    args.energy == ICM::U_square::name
      ? parameterize_surface<ICM::U_square>(mesh, args.metric, uvmap, options, cones, seams, user_seams)
    : args.energy == ICM::Area_distortion::name
      ? parameterize_surface<ICM::Area_distortion>(mesh, args.metric, uvmap, options, cones, seams, user_seams)
    : args.energy == ICM::Angle_distortion::name
      ? parameterize_surface<ICM::Angle_distortion>(mesh, args.metric, uvmap, options, cones, seams, user_seams)
    : args.energy == ICM::Log_area_distortion::name
      ? parameterize_surface<ICM::Log_area_distortion>(mesh, args.metric, uvmap, options, cones, seams, user_seams)
    : args.metric == ICM::Circle_packing_metric::name
      ? run_metric<ICM::Circle_packing_metric>(mesh, uvmap, options, cones, seams, user_seams)
    : args.metric == ICM::Inversive_distance_metric::name
      ? run_metric<ICM::Inversive_distance_metric>(mesh, uvmap, options, cones, seams, user_seams)
    : args.metric == ICM::Vertex_scaling_metric::name
      ? run_metric<ICM::Vertex_scaling_metric>(mesh, uvmap, options, cones, seams, user_seams)
      : run_metric<ICM::Intrinsic_delaunay_metric>(mesh, uvmap, options, cones, seams, user_seams);
  progress.finish();
  if(report.status != SMP::OK)
    return std::string(ICM::error_message(report.status)) + ": " + report.message;
  figures.emplace(report, seams.size(), args.energy);
  figures->atlas_charts = report.atlas_charts;
  figures->atlas_rotated_charts = report.atlas_rotated_charts;
  figures->atlas_utilization = report.atlas_utilization;
  figures->seam_length = ICM::seam_length_over_root_area(mesh, seams);
  return {};
}

int run(const Arguments& args, const Failure_report& fail)
{
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  Timings seconds;

  const std::string bad_output = check_output_paths(args);
  if(!bad_output.empty())
    return fail(bad_output);

  Clock::time_point t = Clock::now();
  Mesh mesh;
  ICM::IO::Mesh_reading_options reading;
  reading.triangulate = args.triangulate;
  ICM::IO::Mesh_reading_report read;
  if(!ICM::IO::read_triangle_mesh(args.input, mesh, read, reading))
    return fail(read.message +
                (read.non_triangle_faces > 0 && !args.triangulate ? " (--triangulate splits them)" : ""));
  seconds.read = since(t);
  // From here on a failure also says what was repaired: it may be why (a dropped vertex).
  std::string repairs;
  for(const std::string& repair : read.repairs())
    repairs += (repairs.empty() ? " (the input was repaired: " : "; ") + repair;
  if(!repairs.empty())
    repairs += ")";
  auto fail_after_reading = [&](const std::string& reason) { return fail(reason + repairs); };

  const std::vector<std::vector<Mesh::Vertex_index>> by_index = vertices_by_file_index(mesh, read);
  std::string error;
  std::map<Mesh::Vertex_index, double> cones = user_cones(args, by_index, error);
  if(!error.empty())
    return fail_after_reading(error);
  std::vector<Mesh::Edge_index> user_seams;
  if(!args.seams.empty() && !read_selection_cones_and_seams(args, mesh, by_index, cones, user_seams, error))
    return fail_after_reading(error);

  auto uvmap = mesh.add_property_map<Mesh::Halfedge_index, Kernel::Point_2>("h:uv").first;
  std::optional<Run_figures> figures;
  if(prescribes_border(args))
  {
    if(const std::string refused =
         icm_param::why_the_border_is_refused("--boundary " + args.boundary, args.boundary, mesh);
       !refused.empty())
      return fail_after_reading(refused);
    const ICM::Parameterization_report report = run_border(args, mesh, uvmap);
    if(report.status != SMP::OK)
      return fail_after_reading(std::string(ICM::error_message(report.status)) + ": " + report.message);
    if(const std::string overlap = why_an_overlap_is_refused(args, report); !overlap.empty())
      return fail_after_reading(overlap);
    figures.emplace(report);
  }
  else
  {
    const std::string reason = run_surface(args, mesh, cones, user_seams, uvmap, figures);
    if(!reason.empty())
      return fail_after_reading(reason);
  }

  t = Clock::now();
  const ICM::IO::Uv_mesh uv_mesh = ICM::IO::make_uv_mesh_from_corners(mesh, uvmap);
  ICM::IO::Mesh_writing_options mesh_options;
  mesh_options.binary_ply = args.ply_binary;
  if(!ICM::IO::write_uv_files(args.output, pictures_of(args), uv_mesh, error, mesh_options))
    return fail_after_reading(error);
  seconds.write = since(t);
  const ICM::Distortion_measures measures = ICM::measure_distortion_corner_uv(mesh, uvmap);
  seconds.total = since(start);

  if(args.json)
    std::cout << summary_json(args, mesh, read, *figures, measures, seconds)
                   .dump(-1, ' ', false, Json::error_handler_t::replace)
              << "\n";
  else
  {
    for(const std::string& repair : read.repairs())
      std::cerr << "icm_param: " << args.input << ": " << repair << "\n";
    print_summary_line(args, mesh, *figures, measures);
  }
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  Arguments args;
  Failure_report fail;
  for(int i = 1; i < argc; ++i)
    fail.json = fail.json || std::string(argv[i]) == "--json";
  const int parsed = parse_arguments(argc, argv, args, fail);
  if(parsed >= 0)
    return parsed;
  fail.json = fail.json || !args.batch_item.empty();
  fail.input = args.input;
  fail.output = args.output;
  try
  {
    if(!args.batch.output_dir.empty() && args.batch_item.empty())
      return icm_param::run_batch(args.batch, argc, argv);
    // Test only (test_cli_batch.cpp): a batch item that crashes, as a bug would.
    if(const char* crash = std::getenv("ICM_PARAM_TEST_CRASH"); crash != nullptr && args.batch_item == crash)
      std::raise(SIGSEGV);
    if(!args.batch_item.empty() && args.batch.max_memory_mb > 0)
      if(std::string error; !icm_param::limit_memory(args.batch.max_memory_mb, error))
        return fail(error);
    return run(args, fail);
  }
  catch(const std::bad_alloc&)
  {
    return fail("out of memory");
  }
  catch(const std::exception& e)
  {
    return fail(std::string("internal error: ") + e.what());
  }
}
