// icm_param's command line: what it asks (`Arguments`), how a failure is told
// (`Failure_report`), and `parse_arguments`, which fills the one and tells a wrong command
// line through the other (icm_param_arguments.cpp, where the options are defined with CLI11).

#ifndef ICM_PARAM_ARGUMENTS_H
#define ICM_PARAM_ARGUMENTS_H

#include "icm_param_batch.h"

#include <ICM/border/Border_conditions.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/parameterize.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace icm_param {

/// The command line once parsed and checked: one mesh (`input`, `output`), a batch
/// (`batch`), or a batch's child (`batch_item`).
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
  std::string cone_angles = "auto";
  bool no_cone_sweeps = false;               // --no-cone-sweeps: the greedy's cones as placed
  bool cones_asked = false;                  // --cones auto or N > 0, or --cone-target given
  std::vector<std::pair<int, double>> cones; // vertex index, cone angle in degrees
  /// --atlas SIZE [--padding TEXELS] [--atlas-packer NAME]: unset, UVs in the mesh's units.
  std::optional<ICM::Atlas_options> atlas;
  /// -O OUTDIR and the other batch options: many inputs, each in a process of its own.
  Batch_options batch;
  /// --batch-item INPUT (hidden): this process is one mesh of a batch, run by its parent.
  std::string batch_item;
};

/// How a failure is told: one line on stderr, and with --json a JSON object on stdout
/// (icm_param_report.cpp, where the JSON is written).
class Failure_report
{
public:
  bool json = false;
  std::string input, output;

  /// Tells `reason` and returns `exit_code`.
  int operator()(const std::string& reason, int exit_code = 1) const;
};

/// Parses the command line into `args`. Returns -1 to go on, else the exit code (0 after
/// --help or --version, 2 on a usage error, which `fail` has reported).
int parse_arguments(int argc, char** argv, Arguments& args, const Failure_report& fail);

inline bool optimizes_energy(const Arguments& args)
{
  return args.energy != ICM::Curvature_entropy::name;
}

inline bool prescribes_border(const Arguments& args)
{
  return args.boundary != "free";
}

} // namespace icm_param

#endif // ICM_PARAM_ARGUMENTS_H
