// Every option of ICM in one tree, each default written and documented once, with the
// checks of every field (`check_options`: finite, in range, else `ERROR_WRONG_PARAMETER`
// naming the field and its value).
//
//   Chart_options                  what both entry points share: Newton, the energy's
//   |                              optimizer, the layout check, the fallback metric
//   +- Parameterization_options    `Inverse_curvature_map_parameterizer_3` (a disk)
//   +- Surface_parameterization_options   `ICM::parameterize` (every surface): + cones,
//                                  + the atlas mode (`Atlas_options`)
//
// One `Newton_options` serves every stage of a run: the cone placement's and the energy
// optimizer's own (`Cone_options::newton`, `Curvature_space_options::newton`) are unset unless
// a user sets one on purpose, and then take the run's `newton`.
// Figures behind the defaults: doc/benchmarks.md.

#ifndef ICM_OPTIONS_H
#define ICM_OPTIONS_H

#include <ICM/Status.h>
#include <ICM/internal/Option_checks.h>

#include <functional>
#include <optional>
#include <string>

namespace ICM {

/// Newton's method on the dynamic Laplacian (the inverse curvature map, every stage).
struct Newton_options
{
  /// Stop when max_i |k_target_i - k_i| over the free vertices is below this (radians).
  double tolerance = 1e-10;
  int max_iterations = 100;
  /// Halvings of the step before the line search gives up.
  int max_line_search_steps = 60;
  /// Largest change of any log radius in one step. Far from the solution Delta can be
  /// nearly singular (circles that barely interact) and the full step is a poor model: it
  /// can ask for radii to change by e^100. A nearly closed surface needs conformal factors
  /// of e^-40 and reaches them in a few capped steps, where uncapped steps take many more
  /// or fail; on disks the cap costs nothing (doc/benchmarks.md, Nearly closed meshes).
  double max_step = 10.0;
  /// A metric with a limited valid region (vertex scaling, inversive distance) gives up
  /// after this many consecutive steps cut below 1/32 by faces that would stop being
  /// triangles: the target is then beyond the region's edge, and Newton would crawl along
  /// it. Converging runs end with full steps.
  int max_blocked_steps = 4;
};

/// Whether every field of `options` is in range (`ERROR_WRONG_PARAMETER` naming the first
/// that is not); `prefix` names the struct inside its parent ("cones.newton.").
inline Status check_options(const Newton_options& options, const std::string& prefix = "newton.")
{
  return internal::Option_checks(prefix)
    .real("tolerance", options.tolerance, 0, false)
    .at_least("max_iterations", options.max_iterations, 0)
    .at_least("max_line_search_steps", options.max_line_search_steps, 1)
    .real("max_step", options.max_step, 0, false)
    .at_least("max_blocked_steps", options.max_blocked_steps, 1)
    .status();
}

/// A stage's own Newton options when it has them, else its parent's.
inline Newton_options newton_of(const std::optional<Newton_options>& own, const Newton_options& parent)
{
  return own ? *own : parent;
}

/// The checks of a stage's own Newton options, if it has any.
inline Status check_options(const std::optional<Newton_options>& options, const std::string& prefix)
{
  return options ? check_options(*options, prefix) : Status::success();
}

/// The paper's curvature diffusion (Algorithm 5), kept to validate Newton's optimum.
struct Diffusion_options
{
  double tolerance = 1e-10; ///< on max_N |k_i|
  int max_iterations = 2000000;
  /// Fraction of the explicit stability bound 1 / max_i Delta_ii (Gershgorin: Delta's
  /// largest eigenvalue is at most twice its largest diagonal entry).
  double step_fraction = 0.95;
};

inline Status check_options(const Diffusion_options& options, const std::string& prefix = "diffusion.")
{
  return internal::Option_checks(prefix)
    .real("tolerance", options.tolerance, 0, false)
    .at_least("max_iterations", options.max_iterations, 0)
    .real("step_fraction", options.step_fraction, 0, false, 1, true)
    .status();
}

/// What L-BFGS on u_S takes as its initial inverse Hessian (times the usual scalar
/// s.y / y.My).
enum class Lbfgs_preconditioner
{
  /// The identity.
  Identity,
  /// The default: (Z^T H Z)^{-1}, H the energy's `gauss_newton` Hessian in u at the start and
  /// Z the harmonic extension, by one factorization of the KKT matrix
  /// [H + mu, Delta_N.^T; Delta_N., -delta] and one solve per application. The identity for
  /// an energy without `gauss_newton`. Chosen by the steps it saves (doc/energies.md): the
  /// Gauss-Newton Hessian at the start is a good model for the angle energy and a poor one
  /// for the area energies, whose optimum lies far from the start.
  Gauss_newton
};

/// Options of both optimizers of an energy other than the entropy (optimum/).
struct Curvature_space_options
{
  /// Stop when the reduced gradient max_S |dE/du_S| (the singular-values optimizer) is below
  /// this times its value at the start, or (the projected gradient) when the S components
  /// of grad_k E differ by less than this times the spread of grad_k E (Theorem 3.2).
  double tolerance = 1e-6;
  /// Also stop (the singular-values optimizer, for an energy with a value) once E fell by
  /// less than this, relative, over the last `stall_window` steps: where the metric flips its
  /// triangulation as it goes the energy is only C^1 and L-BFGS creeps for little gain
  /// (doc/energies.md). 0 turns this off.
  double energy_tolerance = 1e-3;
  int stall_window = 10;
  int max_iterations = 500;
  /// Largest change of any u_S (or, for the projected gradient, of any k_S) in one step.
  double max_step = 5.0;
  /// Pairs kept by L-BFGS.
  int memory = 10;
  /// For a metric that flips its own triangulation (`Intrinsic_delaunay_metric`), the
  /// singular-values optimizer keeps the triangulation frozen for up to this many steps and
  /// then flips it to be Delaunay at the current metric (a *refresh*); 0 flips at every
  /// evaluation. Frozen, the metric is vertex scaling on a fixed triangulation: a smooth
  /// function of u, whose Laplacian keeps its pattern, symbolic analysis, factorization (for
  /// the refined solves) and development order from step to step. A refresh also happens
  /// when a frozen line search fails, and before the optimizer stops, so that the result is
  /// the metric with flips (flat off S on its Delaunay triangulation); when that refresh
  /// flipped edges the stopping test is taken again.
  int frozen_steps = 0;
  /// The singular-values optimizer solves the line search's trial metrics only to max |k_N|
  /// <= this times max_S |dE/du_S| at the step's start (at most 1e-4 rad, at least the
  /// Newton tolerance), as an inexact Newton's forcing term: a trial need not be flat to
  /// round-off to be ranked, once its E is corrected to first order by the adjoint of the
  /// reduced gradient's solve (E - y . k_N). The metric where it stops (or fails) is solved
  /// to the Newton tolerance. 0: every trial to the Newton tolerance.
  double trial_tolerance_factor = 1.0;
  Lbfgs_preconditioner preconditioner = Lbfgs_preconditioner::Gauss_newton;
  /// Trial steps per line search before giving up.
  int max_line_search_steps = 30;
  /// Sufficient decrease of the line searches (Armijo).
  double armijo = 1e-4;
  /// The Dirichlet (or, for the projected gradient, the inverse curvature map) Newton: unset,
  /// the run's `Chart_options::newton` (called directly, the defaults).
  std::optional<Newton_options> newton;
};

inline Status check_options(const Curvature_space_options& options, const std::string& prefix = "energy.")
{
  return internal::Option_checks(prefix)
    .real("tolerance", options.tolerance, 0, true)
    .real("energy_tolerance", options.energy_tolerance, 0, true)
    .at_least("stall_window", options.stall_window, 1)
    .at_least("max_iterations", options.max_iterations, 0)
    .real("max_step", options.max_step, 0, false)
    .at_least("memory", options.memory, 1)
    .at_least("frozen_steps", options.frozen_steps, 0)
    .real("trial_tolerance_factor", options.trial_tolerance_factor, 0, true)
    .one_of("preconditioner", options.preconditioner, 2)
    .at_least("max_line_search_steps", options.max_line_search_steps, 1)
    .real("armijo", options.armijo, 0, false, 1, false)
    .nested(check_options(options.newton, prefix + "newton."))
    .status();
}

/// How automatic cones are placed (cones/Singular_vertices.h).
enum class Cone_placement
{
  /// Greedy on the linearized optimum, one factorization for all rounds (default: at 8 cones
  /// 3 to 300 times less area distortion than the exact greedy on the shared closed meshes,
  /// lower on most with the default count too, in a fraction of the time;
  /// doc/benchmarks.md, Cones).
  Linearized,
  /// Greedy on the exact entropy optimum, one Newton run per round, from Algorithm 3's
  /// strongest minima on a closed surface.
  Exact_optimum
};

/// What chooses the angles of the automatic cones (with the entropy, the default energy; another
/// energy minimises over them itself).
enum class Cone_angles
{
  /// At a count the user names (`Cone_options::max_log_scale` 0), on a closed surface with the
  /// linearized placement: the exact maps with the entropy's angles and with the least log
  /// area's, whichever measures better (no fold where the other folds, else the lower
  /// area-weighted mean log^2 area), at most twice the entropy's time. Elsewhere the entropy's.
  Automatic,
  /// The entropy's: every cone keeps the mesh's own scale (u = u0), as BFF's and CEPS's do.
  Entropy,
  /// On a closed surface with the linearized placement, at any count: the least log area's alone (the entropy's when the exact
  /// optimum fails at them): the angles whose linearized metric has the least area-weighted
  /// variance of u - u0 (the linearized area-weighted mean log^2 area), each angle held within
  /// [1, 4 pi], prescribed to the exact optimum.
  Least_log_area
};

/// The greedy cone placement (`greedy_cones`).
struct Cone_options
{
  /// Stop adding cones once every non-singular vertex has |u - u0| below this: the area
  /// of its neighbourhood changes by less than exp(2 * this), within e^1.2 ~ 3.3 by default
  /// (the trade of distortion against cones: doc/benchmarks.md, Every surface). 0: place
  /// exactly `max_cones`.
  double max_log_scale = 0.6;
  /// At most this many interior cones (a user limit); 0 means none. A closed genus-0 surface
  /// gets at least two.
  int max_cones = 32;
  Cone_placement placement = Cone_placement::Linearized;
  /// Linearized placement: 1 makes the largest |u - u0| the next cone (BFF's rule); N > 1
  /// compares the N largest peaks by the area-weighted variance of the linearized u each
  /// leaves. The variance is the linearized log area figure, which it lowers at a fixed count
  /// on most closed meshes but not where the linearization is far off (the camel's legs:
  /// doc/benchmarks.md, Cones), so the default is 1.
  int ranked_candidates = 1;
  /// Linearized placement: after the greedy, up to this many sweeps over the automatic cones,
  /// each moved to where the linearized |u - u0| is largest without it (0: none). At 8 cones
  /// one sweep lowers sphere966's and armadillo's area distortion and raises bear's; with the
  /// default's 32 cones it helps on half the shared meshes and hurts on the other half
  /// (doc/benchmarks.md, Cones), so the default is none.
  int sweeps = 0;
  Cone_angles angles = Cone_angles::Automatic; ///< what chooses the cones' angles
  /// At a named count (`max_log_scale` 0) on a closed surface, with the linearized
  /// placement: after the greedy, cones moved one at a time (the weakest to the largest
  /// |u - u0|, or each to its ring neighbour of largest |u - u0|), a move kept only when the
  /// exact entropy optimum it gives has less area distortion; until no move is kept or about
  /// the rest of the call's time is spent (cones/Exact_cone_sweeps.h).
  bool exact_sweeps = true;
  /// Unset: the run's `Surface_parameterization_options::newton` (called directly, the
  /// defaults).
  std::optional<Newton_options> newton;
  /// Called after each greedy round with the share of the placement done, from 0 to 1 and
  /// never less than before: the cones placed of `max_cones`, or how far the largest
  /// |u - u0| has come down (in log) to `max_log_scale`, whichever is further. A round takes
  /// a solve of the whole mesh, so a large mesh spends seconds in each; `parameterize`
  /// reports it as its "cones" stage. It must not throw.
  std::function<void(double done)> progress;
};

inline Status check_options(const Cone_options& options, const std::string& prefix = "cones.")
{
  return internal::Option_checks(prefix)
    .real("max_log_scale", options.max_log_scale, 0, true)
    .one_of("placement", options.placement, 2)
    .at_least("ranked_candidates", options.ranked_candidates, 1)
    .at_least("sweeps", options.sweeps, 0)
    .one_of("angles", options.angles, 3)
    .at_least("max_cones", options.max_cones, 0)
    .nested(check_options(options.newton, prefix + "newton."))
    .status();
}

/// `stage` with its Newton options set: its own, or else `parent`.
template <class StageOptions>
StageOptions with_newton(StageOptions stage, const Newton_options& parent)
{
  stage.newton = newton_of(stage.newton, parent);
  return stage;
}

/// How the optimal metric is computed.
enum class Optimum_method
{
  Newton,             ///< Dirichlet problem u_S = u0_S, K(u)_N = 0 by Newton (default)
  Curvature_diffusion ///< the paper's Algorithm 5 (slow; for validation)
};

/// How a flat metric is laid out in the plane (layout/Layout.h).
enum class Layout_method
{
  Automatic, ///< propagation below `harmonic_layout_min_faces` faces, harmonic above
  Propagation,
  Harmonic
};

/// What both entry points share: steps 5 and 7 of one chart (pipeline/Chart_solver.h).
struct Chart_options
{
  /// Every Newton solve of the run (the optimum, and the cones' and the energy's unless they
  /// set their own): tolerance on max |k| over the free vertices, caps.
  Newton_options newton;
  /// The optimizer of an energy other than the entropy, run from the entropy optimum over
  /// the same singular set (the border and the cones).
  Curvature_space_options energy;
  /// A layout whose edge lengths differ from the metric's by more than this fails (relative,
  /// see `Layout_check::max_relative_length_error`). The propagation across a long cut disk
  /// loses more digits on CAD slivers than on a plain disk, while its seams still agree.
  double max_layout_length_error = 1e-5;
  /// When the requested metric cannot reach the optimum (a face would stop being a
  /// triangle, or the layout fails), retry with `Circle_packing_metric`, whose every u is
  /// valid.
  bool fall_back_to_circle_packing = true;
};

inline Status check_options(const Chart_options& options)
{
  return internal::Option_checks()
    .nested(check_options(options.newton))
    .nested(check_options(options.energy))
    .real("max_layout_length_error", options.max_layout_length_error, 0, false)
    .status();
}

/// Options of `Inverse_curvature_map_parameterizer_3`.
struct Parameterization_options : Chart_options
{
  Diffusion_options diffusion; ///< used with `Optimum_method::Curvature_diffusion`
  Optimum_method optimum = Optimum_method::Newton;
  Layout_method layout = Layout_method::Automatic;
  /// `Automatic` switches to the harmonic layout here. The paper switches at 30k faces;
  /// in double precision the least-error propagation still reproduces the metric far
  /// beyond, at a fraction of the cost of a factorization.
  int harmonic_layout_min_faces = 200000;
  /// Called at the start of each stage with its name ("index", "metric", "optimum", "layout").
  std::function<void(const std::string&)> progress;
};

inline Status check_options(const Parameterization_options& options)
{
  return internal::Option_checks()
    .nested(check_options(static_cast<const Chart_options&>(options)))
    .nested(check_options(options.diffusion))
    .one_of("optimum", options.optimum, 2)
    .one_of("layout", options.layout, 3)
    .at_least("harmonic_layout_min_faces", options.harmonic_layout_min_faces, 0)
    .status();
}

/// How the charts' boxes are packed into the atlas.
enum class Atlas_packer
{
  /// Rows of boxes, tallest first, each row the square's width (Chart_packing.h's shelves).
  Shelf,
  /// stb_rect_pack's skyline bottom-left packer; only when ICM_HAS_STB_RECT_PACK.
  Skyline
};

/// Whether this build can pack with `packer`.
inline bool atlas_packer_available(Atlas_packer packer)
{
#ifdef ICM_HAS_STB_RECT_PACK
  return packer == Atlas_packer::Shelf || packer == Atlas_packer::Skyline;
#else
  return packer == Atlas_packer::Shelf;
#endif
}

inline const char* atlas_packer_name(Atlas_packer packer)
{
  return packer == Atlas_packer::Skyline ? "skyline" : "shelf";
}

/// The packer that covered more of the square on the shared meshes, when this build has it
/// (layout/Atlas_packing.h).
inline constexpr Atlas_packer default_atlas_packer()
{
#ifdef ICM_HAS_STB_RECT_PACK
  return Atlas_packer::Skyline;
#else
  return Atlas_packer::Shelf;
#endif
}

/// Atlas mode (`Surface_parameterization_options::atlas`): the UVs in [0, 1]^2.
struct Atlas_options
{
  /// Texels per side of the square texture the atlas is for. At most 65536: beyond every
  /// GPU's texture limit, and texel coordinates stay far from the packers' int range.
  int size = 1024;
  /// Texels kept free between any two charts and between a chart and the square's border.
  /// 4 by default: bilinear filtering reads one texel beyond a chart's edge, and each mipmap
  /// level halves the padding, so 4 texels keep charts a texel apart down to the level of a
  /// quarter of the size; on atlases of 512 texels and more it costs little area.
  int padding = 4;
  /// Charts may be turned by a quarter turn (a rotation: orientation is kept, nothing
  /// flips) when that packs them at a larger scale.
  bool allow_rotation = true;
  Atlas_packer packer = default_atlas_packer();
};

inline Status check_options(const Atlas_options& options, const std::string& prefix = "atlas.")
{
  internal::Option_checks checks(prefix);
  checks.at_least("size", options.size, 1).at_most("size", options.size, 65536).at_least("padding", options.padding, 0);
  if(options.size >= 1)
    checks.at_most("padding", options.padding, (options.size - 1) / 2,
                   "so that a " + std::to_string(options.size) +
                     "-texel square keeps at least one texel inside its border");
  checks.one_of("packer", options.packer, 2);
  if(checks.status().ok() && !atlas_packer_available(options.packer))
    return Status::wrong_parameter("option " + prefix + "packer = " + atlas_packer_name(options.packer) +
                                   ": ICM was built without stb_rect_pack.h (Debian: libstb-dev)");
  return checks.status();
}

/// Options of `ICM::parameterize`.
struct Surface_parameterization_options : Chart_options
{
  /// Interior cones chosen automatically (`greedy_cones`) on closed surfaces, and on
  /// surfaces with a border whose free-boundary optimum is extreme. False: only the border
  /// and the user's cones are singular (a torus then needs none; a closed genus-0 surface
  /// needs user cones).
  bool automatic_cones = true;
  Cone_options cones;
  /// With `Cone_placement::Exact_optimum`: the cones a closed genus-0 surface starts from
  /// (Algorithm 3's strongest minima; its first optima with two cones need conformal factors
  /// no metric reaches) before the greedy placement adds more; 8 is BFF's default count. The
  /// linearized placement starts from the user's cones alone.
  int initial_cones = 8;
  /// A surface with a border gets automatic interior cones only when its free-boundary
  /// optimum changes some area by more than exp(2 * this) ~ 55; an ordinary disk keeps its
  /// free boundary and no seam. Chosen on the shared meshes, where a lower threshold gives
  /// more meshes cones and a higher one leaves extreme maps alone (doc/benchmarks.md).
  double border_max_log_scale = 2.0;
  /// A chart whose layout overlaps itself is cut into pieces that do not (`remove_overlaps`);
  /// false keeps the raw optimum and only counts its overlaps.
  bool remove_overlaps = true;
  /// Called, when set, at the start of each stage of each component ("cones", "cut",
  /// "optimum", "overlaps") and once at the end ("done"), with the share of the work done so
  /// far, 0 to 1 (components weighted by their faces; within one, a fixed share per stage).
  /// For a progress line on long runs; it must not throw.
  std::function<void(const std::string& stage, double fraction)> progress;
  /// Unset (the default): the charts side by side at their 3D scale, UVs in the mesh's
  /// units from (0, 0). Set: every chart into [0, 1]^2 for a texture of `atlas->size`
  /// texels, at one texel density, `atlas->padding` texels apart (layout/Atlas_packing.h);
  /// the report gives the share of the square covered (`atlas_utilization`).
  std::optional<Atlas_options> atlas;
};

inline Status check_options(const Surface_parameterization_options& options)
{
  return internal::Option_checks()
    .nested(check_options(static_cast<const Chart_options&>(options)))
    .nested(options.atlas ? check_options(*options.atlas) : Status::success())
    .nested(check_options(options.cones))
    .at_least("initial_cones", options.initial_cones, 0)
    .real("border_max_log_scale", options.border_max_log_scale, 0, true)
    .status();
}

} // namespace ICM

#endif // ICM_OPTIONS_H
