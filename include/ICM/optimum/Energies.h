// Step 5's energies: what "best" means among the admissible curvatures (paper Sec. III-D).
//
// Every conformal parameterization of the mesh with singular set S is one point of the
// admissible curvature space {k_N = 0, sum_S k = 2 pi chi} (Def. 3.1); an energy picks one.
// The `Energy` concept (doc/energies.md, doc/concepts.md):
//
//   e.gradient(state, partials)   required. Adds the partial derivatives of E with respect to
//                                 the state's quantities to `partials` (an `Energy_gradient`):
//                                 dE/du_v (areas and angles held fixed), dE/d area(f),
//                                 dE/d angle(f, c). The state turns them into the gradient
//                                 with respect to u by the chain rule through the metric
//                                 (`Energy_state::gradient_u`), so an energy never needs the
//                                 metric's derivatives.
//   e.value(state)                the value E. Required, except for an energy that gives
//                                 gradient_k and is convex in k (the curvature entropy, whose
//                                 value is a path integral no single state determines); the
//                                 optimizers then decide their steps from directional
//                                 derivatives alone.
//   e.gradient_k(state, h)        optional: grad_k E = Delta(u)^{-1} grad_u E directly (up to
//                                 a constant), as the entropy gives u - u0 without a solve.
//   e.gauss_newton(state, h)      optional: adds the Gauss-Newton Hessian of E with respect
//                                 to u (per vertex of the state's mesh) as entries of its
//                                 lower triangle; the singular-values optimizer's default
//                                 preconditioner reduces it to u_S (Curvature_space_optimizer.h).
//   Energy::reads_faces           optional `static constexpr bool`, false for an energy of u
//                                 and the metric's lengths and weights alone (the entropy,
//                                 u-square): the optimizers then never measure the mesh's
//                                 faces (for the default metric a development per solve),
//                                 and its areas and angles in the state are not current.
//
// Every energy must be invariant under the global scale u -> u + c (the optimizers fix the
// scale, which does not change the parameterization): the state's areas are normalised so
// that their total is the mesh's, and `U_square` measures u - u0 about its mean.
//
// What an energy reads is the state of optimum/Energy_state.h.

#ifndef ICM_OPTIMUM_ENERGIES_H
#define ICM_OPTIMUM_ENERGIES_H

#include <ICM/optimum/Energy_state.h>
#include <ICM/measures/Distortion.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

namespace ICM {

namespace internal {

template <class Energy, class State, class = void>
struct Has_energy_value : std::false_type
{};
template <class Energy, class State>
struct Has_energy_value<Energy, State,
                        std::void_t<decltype(std::declval<const Energy&>().value(std::declval<const State&>()))>>
  : std::true_type
{};

template <class Energy, class State, class = void>
struct Has_curvature_gradient : std::false_type
{};
template <class Energy, class State>
struct Has_curvature_gradient<Energy, State,
                              std::void_t<decltype(std::declval<const Energy&>().gradient_k(
                                std::declval<const State&>(), std::declval<Eigen::VectorXd&>()))>> : std::true_type
{};

template <class Energy, class State, class = void>
struct Has_gauss_newton : std::false_type
{};
template <class Energy, class State>
struct Has_gauss_newton<Energy, State,
                        std::void_t<decltype(std::declval<const Energy&>().gauss_newton(
                          std::declval<const State&>(), std::declval<std::vector<Eigen::Triplet<double, int>>&>()))>>
  : std::true_type
{};

template <class Energy, class = void>
struct Reads_faces : std::true_type
{};
template <class Energy>
struct Reads_faces<Energy, std::void_t<decltype(Energy::reads_faces)>> : std::bool_constant<Energy::reads_faces>
{};

template <class Energy, class = void>
struct Has_energy_name : std::false_type
{};
template <class Energy>
struct Has_energy_name<Energy, std::void_t<decltype(Energy::name)>> : std::true_type
{};

} // namespace internal

/// `Energy::name` ("log-area", ...), or "user-defined" for an energy without one.
template <class Energy>
const char* energy_name()
{
  if constexpr(internal::Has_energy_name<Energy>::value)
    return Energy::name;
  else
    return "user-defined";
}

/// Whether `Energy` gives its value on states of `Metric` (all but the curvature entropy).
template <class Energy, class Metric>
constexpr bool has_energy_value = internal::Has_energy_value<Energy, Energy_state<Metric>>::value;
/// Whether `Energy` gives grad_k E directly (`gradient_k`).
template <class Energy, class Metric>
constexpr bool has_curvature_gradient = internal::Has_curvature_gradient<Energy, Energy_state<Metric>>::value;

/// Whether `Energy` gives its Gauss-Newton Hessian in u (`gauss_newton`), which the
/// singular-values optimizer turns into its default preconditioner.
template <class Energy, class Metric>
constexpr bool has_gauss_newton = internal::Has_gauss_newton<Energy, Energy_state<Metric>>::value;

/// Whether `Energy` reads the mesh's faces of the state (`Energy::reads_faces`, true unless
/// it says otherwise).
template <class Energy>
constexpr bool reads_faces = internal::Reads_faces<Energy>::value;

/// E at the state, or NaN for an energy without a value.
template <class Energy, class Metric>
double energy_value(const Energy& energy, const Energy_state<Metric>& state)
{
  if constexpr(has_energy_value<Energy, Metric>)
    return energy.value(state);
  else
    return std::numeric_limits<double>::quiet_NaN();
}

/// grad_u E at the state; `partials` is scratch, kept by the caller to save allocations.
template <class Energy, class Metric>
void energy_gradient(const Energy& energy, const Energy_state<Metric>& state, Eigen::VectorXd& gradient,
                     Energy_gradient& partials)
{
  partials.reset(static_cast<int>(state.u().size()), state.number_of_faces());
  energy.gradient(state, partials);
  if constexpr(reads_faces<Energy>)
    state.gradient_u(partials, gradient);
  else
    gradient = partials.u; // no face partials to chain through the metric
}

template <class Energy, class Metric>
Eigen::VectorXd energy_gradient(const Energy& energy, const Energy_state<Metric>& state)
{
  Eigen::VectorXd gradient;
  Energy_gradient partials;
  energy_gradient(energy, state, gradient, partials);
  return gradient;
}

// --- The energies ----------------------------------------------------------------------------

/// The curvature entropy E = int_{k0}^{k} (u - u0) . dk (Def. 3.3): convex in k with
/// grad_k E = u - u0; its minimum over the admissible space is the free-boundary optimum
/// u_S - u0_S = const (Thm 3.5), which `free_boundary_optimum` reaches directly. No value
/// (see the file comment); grad_u E = Delta(u) (u - u0).
///
/// \cgalModels{\ref Energy (the default)}
struct Curvature_entropy
{
  static constexpr const char* name = "entropy";
  static constexpr bool reads_faces = false;

  template <class Metric>
  void gradient(const Energy_state<Metric>& state, Energy_gradient& partials) const
  {
    const internal::Mesh_index& t = state.triangulation();
    const Eigen::VectorXd h = state.u() - state.u0();
    for(int e = 0; e < t.number_of_edges(); ++e)
    {
      const int i = t.edges[e][0], j = t.edges[e][1];
      const double flow = state.weights()[e] * (h[i] - h[j]);
      partials.u[i] += flow;
      partials.u[j] -= flow;
    }
  }

  template <class Metric>
  void gradient_k(const Energy_state<Metric>& state, Eigen::VectorXd& h) const
  {
    h = state.u() - state.u0();
  }
};

/// The u-square energy (eq. 7), the spread of the log scale factors: the mean over vertices
/// of (u - u0 - mean(u - u0))^2. The paper takes the mean of u - u0 as zero; measuring
/// about the mean makes the energy independent of the global scale.
///
/// \cgalModels{\ref Energy}
struct U_square
{
  static constexpr const char* name = "u-square";
  static constexpr bool reads_faces = false;

  template <class Metric>
  double value(const Energy_state<Metric>& state) const
  {
    const Eigen::VectorXd h = centred(state);
    return h.squaredNorm() / h.size();
  }

  template <class Metric>
  void gradient(const Energy_state<Metric>& state, Energy_gradient& partials) const
  {
    // The centring is a projection whose image the gradient already lies in.
    const Eigen::VectorXd h = centred(state);
    partials.u += 2.0 / h.size() * h;
  }

private:
  template <class Metric>
  static Eigen::VectorXd centred(const Energy_state<Metric>& state)
  {
    Eigen::VectorXd h = state.u() - state.u0();
    h.array() -= h.mean();
    return h;
  }
};

/// Area distortion (eq. 6): the mean over faces of (s_f / A_f - 1)^2, s_f the face's area
/// under the metric normalised to the mesh's total, A_f its 3D area. As the paper notes it
/// may have local minima.
///
/// \cgalModels{\ref Energy}
struct Area_distortion
{
  static constexpr const char* name = "area";

  template <class Metric>
  double value(const Energy_state<Metric>& state) const
  {
    double sum = 0;
    for(int f = 0; f < state.number_of_faces(); ++f)
    {
      const double x = state.area(f) / state.mesh_area(f) - 1.0;
      sum += x * x;
    }
    return sum / state.number_of_faces();
  }

  template <class Metric>
  void gradient(const Energy_state<Metric>& state, Energy_gradient& partials) const
  {
    const double n = state.number_of_faces();
    for(int f = 0; f < state.number_of_faces(); ++f)
      partials.area[f] += 2.0 / n * (state.area(f) / state.mesh_area(f) - 1.0) / state.mesh_area(f);
  }
};

namespace internal {

/// d angle(f, a) / d u_b of mesh face f in the vertex-scaling form, from the face's angles at
/// the state: 1/2 cot of the third angle off the diagonal, rows summing to zero (the global
/// scale moves no angle). Exact for vertex scaling on the mesh's faces; for the other
/// metrics, and the faces of a development, the nearby conformal change a preconditioner needs.
template <class Metric>
std::array<std::array<double, 3>, 3> angle_jacobian(const Energy_state<Metric>& state, int f)
{
  // A cotangent beyond this (an angle under 1e-3 rad) is a sliver's, whose angles a
  // conformal change hardly moves; capping it keeps the Hessian's scale that of the mesh.
  constexpr double largest_cotangent = 1e3;
  std::array<double, 3> cot;
  for(int c = 0; c < 3; ++c)
  {
    const double theta = std::abs(state.angle(f, c));
    cot[c] = std::clamp(std::cos(theta) / std::sin(theta), -largest_cotangent, largest_cotangent);
  }
  std::array<std::array<double, 3>, 3> j;
  for(int a = 0; a < 3; ++a)
    for(int b = 0; b < 3; ++b)
      j[a][b] = a == b ? -0.5 * (cot[(a + 1) % 3] + cot[(a + 2) % 3]) : 0.5 * cot[3 - a - b];
  return j;
}

} // namespace internal

/// The ABF energy of Sec. III-D against the mesh's own angles: the mean over corners of
/// (theta - theta_mesh)^2 (radians^2, the `angle_distortion` of doc/distortion.md).
///
/// \cgalModels{\ref Energy}
struct Angle_distortion
{
  static constexpr const char* name = "angle";

  template <class Metric>
  double value(const Energy_state<Metric>& state) const
  {
    double sum = 0;
    for(int f = 0; f < state.number_of_faces(); ++f)
      for(int c = 0; c < 3; ++c)
      {
        const double x = state.angle(f, c) - state.mesh_angle(f, c);
        sum += x * x;
      }
    return sum / (3.0 * state.number_of_faces());
  }

  template <class Metric>
  void gradient(const Energy_state<Metric>& state, Energy_gradient& partials) const
  {
    const double n = 3.0 * state.number_of_faces();
    for(int f = 0; f < state.number_of_faces(); ++f)
      for(int c = 0; c < 3; ++c)
        partials.angle[f][c] += 2.0 / n * (state.angle(f, c) - state.mesh_angle(f, c));
  }

  /// (2 / 3F) sum_f J_f^T J_f, J_f = `angle_jacobian`: the angles' residuals are small near
  /// the optimum (the entropy's is already close to it), so Gauss-Newton is nearly the Hessian.
  template <class Metric>
  void gauss_newton(const Energy_state<Metric>& state, std::vector<Eigen::Triplet<double, int>>& h) const
  {
    const double scale = 2.0 / (3.0 * state.number_of_faces());
    for(int f = 0; f < state.number_of_faces(); ++f)
    {
      const std::array<std::array<double, 3>, 3> j = internal::angle_jacobian(state, f);
      const std::array<int, 3>& v = state.mesh().faces[f];
      for(int a = 0; a < 3; ++a)
        for(int b = 0; b < 3; ++b)
          if(v[a] >= v[b])
            h.emplace_back(v[a], v[b], scale * (j[0][a] * j[0][b] + j[1][a] * j[1][b] + j[2][a] * j[2][b]));
    }
  }
};

/// How `Log_area_distortion` weighs its faces.
enum class Face_weighting
{
  Area,   ///< by 3D area, sum_f A_f log^2(...) / sum_f A_f: the integral over the surface
  Uniform ///< one per face, sum_f log^2(...) / (number of faces): paper eq. 8 as Table I reports it
};

/// The log area distortion of Table I (eq. 8), optimised directly: sum_f w_f log^2(s_f / A_f)
/// with s_f normalised to the mesh's total area and the weights w_f of `Face_weighting`
/// (summing to 1). Below the ratio `smallest_ratio` log^2 is continued by its tangent, so
/// that the energy stays finite and C^1 for a face flipped in a development (negative area)
/// and pushes it back. Not by a steeper continuation: a face flipped in the development of
/// an intrinsic metric is most often one the metric's triangulation does not have (an obtuse
/// sliver, or a face where the scale changes by orders of magnitude across it), which no
/// conformal change can unflip. With the second order Taylor polynomial four such faces of
/// the cow (32 cones) made E 110 at the entropy optimum (3.4 with the tangent), and the
/// optimum's mean log^2 area was 22.7 against the entropy's 5.7 (with the tangent: 3.2).
///
/// \cgalModels{\ref Energy}
class Log_area_distortion
{
public:
  static constexpr const char* name = "log-area";
  static constexpr double smallest_ratio = 1e-3;

  explicit Log_area_distortion(Face_weighting weighting = Face_weighting::Area) : weighting_(weighting) {}

  Face_weighting weighting() const { return weighting_; }

  template <class Metric>
  double value(const Energy_state<Metric>& state) const
  {
    double sum = 0;
    for(int f = 0; f < state.number_of_faces(); ++f)
      sum += weight(state, f) * log_squared(state.area(f) / state.mesh_area(f)).value;
    return sum;
  }

  template <class Metric>
  void gradient(const Energy_state<Metric>& state, Energy_gradient& partials) const
  {
    for(int f = 0; f < state.number_of_faces(); ++f)
      partials.area[f] +=
        weight(state, f) * log_squared(state.area(f) / state.mesh_area(f)).derivative / state.mesh_area(f);
  }

  struct Value_and_derivative
  {
    double value, derivative;
  };

  /// log^2(x), continued below `smallest_ratio` by its tangent.
  static Value_and_derivative log_squared(double x)
  {
    if(x >= smallest_ratio)
    {
      const double l = std::log(x);
      return {l * l, 2.0 * l / x};
    }
    const double x0 = smallest_ratio, l = std::log(x0);
    const double slope = 2.0 * l / x0;
    return {l * l + slope * (x - x0), slope};
  }

private:
  template <class Metric>
  double weight(const Energy_state<Metric>& state, int f) const
  {
    return weighting_ == Face_weighting::Area ? state.mesh_area(f) / state.mesh_total_area()
                                              : 1.0 / state.number_of_faces();
  }

  Face_weighting weighting_;
};

} // namespace ICM

#endif // ICM_OPTIMUM_ENERGIES_H
