// Boundary conditions of `Inverse_curvature_map_parameterizer_3`, as one notion in curvature
// space (issue 9, parts 3 and 4).
//
// Every condition says what the curvature of the border is; the interior is always flat.
//  - `Free_border`: the border curvature is left to the optimum of the curvature entropy
//    (u = u0 on the border, the paper's Thm 3.5): today's behaviour.
//  - `Prescribed_border_curvature`: the user gives the turning angle k_i of every border
//    vertex; the metric is u = K^{-1}(k) (Algorithm 1, one vertex pinned for the scale). The
//    admissible space is then a single point.
//  - `Border_shape<BorderParameterizer>`: the turning angles of the polygon a CGAL border
//    parameterizer draws (a square: pi/2 at its four corners, 0 along its sides), then as
//    above: conformal inside, the border's angles prescribed, so a square gives a rectangle.
//    A circular border parameterizer gives the circle condition below on the one loop.
//  - `Circle_domain`: every border loop a circle (paper Fig. 8), the outer one around the
//    domain, the others holes in it; genus 0 with any number of loops, laid out without cut.
//
// The circle condition, exact for any metric: a polygon with sides l_e is inscribed in a
// circle of radius R when each side subtends theta_e = 2 asin(l_e / 2R) at the centre and
// the angles close, sum_e theta_e = 2 pi. Its turning angle at the vertex between sides a
// and b is then (theta_a + theta_b) / 2, positive around the outer loop and negative around
// a hole. The targets depend on u through the lengths: `solve_circle_domain` iterates
// u <- K^{-1}(T(u)) with Anderson acceleration (doc/border_conditions.md has the numbers).

#ifndef ICM_BORDER_BORDER_CONDITIONS_H
#define ICM_BORDER_BORDER_CONDITIONS_H

#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/layout/Layout.h>
#include <ICM/internal/Mesh_index.h>

#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/Square_border_parameterizer_3.h>
#include <CGAL/boost/graph/iterator.h>

#include <boost/property_map/property_map.hpp>

#include <Eigen/Core>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <deque>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace ICM {

/// What a border condition asks of the border, in curvature space.
enum class Border_kind
{
  Free,                  ///< left to the entropy optimum (u = u0 on the border)
  Prescribed_curvature,  ///< a given turning angle per border vertex
  Circles                ///< every loop a circle (outer loop around the domain)
};

/// A border condition applied to one indexed mesh: what `Inverse_curvature_map_parameterizer_3`
/// solves for. `status` is not `OK` when the condition cannot hold on this mesh (`message`
/// says why).
struct Border_target
{
  Border_kind kind = Border_kind::Free;
  /// `Prescribed_curvature`: k per vertex of the index (0 at interior vertices).
  Eigen::VectorXd curvature;
  /// `Circles`: the loop of `Mesh_index::boundary_loops` that goes around the domain.
  int outer_loop = 0;
  /// `Circles`: cap on the outer iterations u <- K^{-1}(T(u)), and the Anderson depth.
  int max_iterations = 200;
  int anderson_depth = 6;
  CGAL::Surface_mesh_parameterization::Error_code status = CGAL::Surface_mesh_parameterization::OK;
  std::string message;

  bool ok() const { return status == CGAL::Surface_mesh_parameterization::OK; }
  bool prescribes_border() const { return kind != Border_kind::Free; }
};

namespace internal {

inline Border_target refused(const std::string& why)
{
  Border_target t;
  t.status = CGAL::Surface_mesh_parameterization::ERROR_WRONG_PARAMETER;
  t.message = why;
  return t;
}

/// Checks discrete Gauss-Bonnet, sum k = 2 pi chi, of a prescribed curvature: relative to
/// the number of border vertices, since each value may carry its own rounding.
inline Border_target checked_gauss_bonnet(const Mesh_index& index, Border_target t, const std::string& what)
{
  int border_vertices = 0;
  for(int v = 0; v < index.number_of_vertices(); ++v)
  {
    border_vertices += index.is_boundary_vertex[v];
    if(!std::isfinite(t.curvature[v]))
      return refused(what + " is not finite at vertex " + std::to_string(v));
  }
  const double defect = gauss_bonnet_defect(index, t.curvature);
  if(!(std::abs(defect) <= 1e-9 * std::max(1, border_vertices)))
    return refused(what + " violates Gauss-Bonnet: its sum is " + std::to_string(t.curvature.sum()) +
                   ", not 2 pi chi = " + std::to_string(2 * M_PI * index.euler_characteristic()) +
                   " (chi = " + std::to_string(index.euler_characteristic()) + ")");
  return t;
}

/// The loop of `Mesh_index::boundary_loops` through vertex `v`, or -1.
inline int loop_of_vertex(const Mesh_index& index, int v)
{
  for(int l = 0; l < index.number_of_boundary_loops(); ++l)
    if(std::find(index.boundary_loops[l].begin(), index.boundary_loops[l].end(), v) !=
       index.boundary_loops[l].end())
      return l;
  return -1;
}

/// The target of halfedge `h` (a free function: inside a policy, `target` is the member).
template <class TriangleMesh>
typename boost::graph_traits<TriangleMesh>::vertex_descriptor
target_vertex(typename boost::graph_traits<TriangleMesh>::halfedge_descriptor h, const TriangleMesh& mesh)
{
  return target(h, mesh);
}

/// The loop whose 3D length (in the index's coordinates) is largest.
inline int longest_loop(const Mesh_index& index)
{
  int best = 0;
  double best_length = -1;
  for(int l = 0; l < index.number_of_boundary_loops(); ++l)
  {
    const std::vector<int>& loop = index.boundary_loops[l];
    double length = 0;
    for(std::size_t i = 0; i < loop.size(); ++i)
      length += std::sqrt(squared_distance(index.points[loop[i]], index.points[loop[(i + 1) % loop.size()]]));
    if(length > best_length)
    {
      best_length = length;
      best = l;
    }
  }
  return best;
}

/// Whether a CGAL border parameterizer draws a circle (derives from
/// `Circular_border_parameterizer_3`) or a square.
template <class BorderParameterizer, class = void>
struct Border_parameterizer_shape
{
  static constexpr bool is_circle = false, is_square = false;
};
template <class BorderParameterizer>
struct Border_parameterizer_shape<BorderParameterizer, std::void_t<typename BorderParameterizer::Triangle_mesh>>
{
  using Mesh = typename BorderParameterizer::Triangle_mesh;
  static constexpr bool is_circle =
    std::is_base_of<CGAL::Surface_mesh_parameterization::Circular_border_parameterizer_3<Mesh>,
                    BorderParameterizer>::value;
  static constexpr bool is_square =
    std::is_base_of<CGAL::Surface_mesh_parameterization::Square_border_parameterizer_3<Mesh>,
                    BorderParameterizer>::value;
};

/// The circle through a closed polygon of side lengths `lengths`: its radius, and the side
/// that subtends more than pi (the centre is beyond it), or -1.
struct Inscribed_circle
{
  double radius = 0;
  int long_side = -1;
  bool exists = false;
};

/// Sum of the angles the sides subtend at the centre of a circle of radius R, the side
/// `long_side` (if any) taken on the far arc.
inline double subtended_angle_sum(const std::vector<double>& lengths, double R, int long_side)
{
  double sum = 0;
  for(std::size_t e = 0; e < lengths.size(); ++e)
  {
    const double half = std::asin(std::min(1.0, lengths[e] / (2 * R)));
    sum += static_cast<int>(e) == long_side ? 2 * M_PI - 2 * half : 2 * half;
  }
  return sum;
}

/// Solves the closure sum_e theta_e(R) = 2 pi. With every side on its short arc the sum
/// falls with R from its value at R = l_max / 2; when even that is short of 2 pi, the longest
/// side is on its far arc (the centre lies outside the polygon, beyond that side), and the
/// root is where the other sides' angles equal the longest one's. A polygon exists (and the
/// root is unique) iff the longest side is shorter than the others together. Bisection in
/// log R: a root to the last bits in a few dozen evaluations whatever the branch.
inline Inscribed_circle inscribed_circle(const std::vector<double>& lengths)
{
  Inscribed_circle c;
  if(lengths.size() < 3)
    return c;
  const auto longest = std::max_element(lengths.begin(), lengths.end());
  double others = 0;
  for(double l : lengths)
    others += l;
  others -= *longest;
  if(!(*longest < others))
    return c;
  double low = *longest / 2;
  c.long_side = subtended_angle_sum(lengths, low, -1) >= 2 * M_PI
                  ? -1
                  : static_cast<int>(longest - lengths.begin());
  // On the short branch the sum falls below 2 pi by R = sum l / 4 (asin x <= pi x / 2); on
  // the far branch it rises to 2 pi, crossing where the other sides balance the long one.
  double high = (others + *longest) / 4;
  while(c.long_side >= 0 && subtended_angle_sum(lengths, high, c.long_side) < 2 * M_PI && high < 1e300)
    high *= 2;
  const double sign = c.long_side < 0 ? 1.0 : -1.0; // sum - 2 pi has this sign below the root
  for(int i = 0; i < 200 && high - low > 4e-16 * high; ++i)
  {
    const double mid = std::sqrt(low * high);
    if(sign * (subtended_angle_sum(lengths, mid, c.long_side) - 2 * M_PI) > 0)
      low = mid;
    else
      high = mid;
  }
  c.radius = std::sqrt(low * high);
  c.exists = std::isfinite(c.radius);
  return c;
}

/// Per vertex, the straight stretches of a prescribed border it must lie on, {-1, -1} for
/// none. A stretch is a run of border vertices with turning angle exactly 0 with the two
/// vertices that end it, numbered by the turning vertex that starts it (a turning vertex is
/// on two). An interior vertex whose neighbours all lie on one stretch lies on it too in
/// any layout without flipped faces (it is inside the hull of its neighbours): horse's
/// vertex 700, whose six neighbours are border vertices of one side of a square.
inline std::vector<std::array<int, 2>> straight_stretches(const Mesh_index& index, const Eigen::VectorXd& curvature)
{
  const int nv = index.number_of_vertices();
  std::vector<std::array<int, 2>> stretches(nv, {-1, -1});
  int first_id = 0;
  for(const std::vector<int>& loop : index.boundary_loops)
  {
    const int n = static_cast<int>(loop.size());
    int start = -1;
    for(int p = 0; p < n && start < 0; ++p)
      if(curvature[loop[p]] != 0)
        start = p;
    if(start < 0)
      continue; // a loop that never turns is not closed: Gauss-Bonnet refused it before
    int id = first_id - 1;
    for(int i = 0; i <= n; ++i)
    {
      const int v = loop[(start + i) % n];
      if(curvature[v] != 0)
      {
        stretches[v][1] = i == n ? stretches[v][1] : id + 1; // the one it starts
        if(i > 0)
          stretches[v][0] = id;                              // the one it ends (at i = n: the last)
        ++id;
      }
      else
        stretches[v] = {id, id};
    }
    first_id = id;
  }
  // Interior vertices pinned by their neighbours, until none is added: the stretches every
  // neighbour shares (unset = not yet met a neighbour).
  const std::array<int, 2> unset{-2, -2};
  std::vector<std::array<int, 2>> shared(nv);
  auto meet = [&](int v, const std::array<int, 2>& neighbour) {
    std::array<int, 2>& s = shared[v];
    if(s == unset)
      s = neighbour;
    for(int& x : s)
      if(x >= 0 && x != neighbour[0] && x != neighbour[1])
        x = -1;
  };
  for(bool added = true; added;)
  {
    std::fill(shared.begin(), shared.end(), unset);
    for(const std::array<int, 2>& e : index.edges)
    {
      meet(e[0], stretches[e[1]]);
      meet(e[1], stretches[e[0]]);
    }
    added = false;
    for(int v = 0; v < nv; ++v)
      if(!index.is_boundary_vertex[v] && stretches[v][0] < 0)
        for(int x : shared[v])
          if(x >= 0)
          {
            stretches[v] = {x, x};
            added = true;
            break;
          }
  }
  return stretches;
}

/// The faces whose three corners all lie on one straight stretch (`straight_stretches`):
/// any layout with that border makes them segments, so no flat metric can lay them out as
/// triangles. An "ear" (a face with two border edges) on a square's side is one; CGAL's
/// square border parameterizer warns of the same degeneracy.
inline std::vector<int> faces_on_a_straight_stretch(const Mesh_index& index,
                                                    const std::vector<std::array<int, 2>>& stretches)
{
  auto on = [&](int v, int stretch) { return stretches[v][0] == stretch || stretches[v][1] == stretch; };
  std::vector<int> degenerate;
  for(int f = 0; f < index.number_of_faces(); ++f)
  {
    const std::array<int, 3>& c = index.faces[f];
    for(int stretch : stretches[c[0]])
      if(stretch >= 0 && on(c[1], stretch) && on(c[2], stretch))
      {
        degenerate.push_back(f);
        break;
      }
  }
  return degenerate;
}

/// How many of `faces` have no positive area in `uv`.
inline int count_flipped_faces_among(const Mesh_index& index, const std::vector<Uv>& uv, const std::vector<int>& faces)
{
  int flipped = 0;
  for(int f : faces)
  {
    const std::array<int, 3>& c = index.faces[f];
    flipped += !(twice_signed_area(uv[c[0]], uv[c[1]], uv[c[2]]) > 0);
  }
  return flipped;
}

/// A rectangle border (one loop, four turning angles pi/2, the others 0): turns the layout
/// so that its sides are axis-parallel and puts every vertex of a side, and every interior
/// vertex pinned to it (`straight_stretches`), exactly on it (they are within the layout's
/// round-off of it). The faces of `faces_on_a_straight_stretch` then have exactly zero area
/// instead of a round-off sign. Returns false, changing nothing, for another border.
inline bool make_rectangle_sides_exact(const Mesh_index& index, const Eigen::VectorXd& curvature,
                                       const std::vector<std::array<int, 2>>& stretches, std::vector<Uv>& uv)
{
  if(index.number_of_boundary_loops() != 1)
    return false;
  const std::vector<int>& loop = index.boundary_loops[0];
  const int n = static_cast<int>(loop.size());
  std::vector<int> corners;
  for(int p = 0; p < n; ++p)
    if(curvature[loop[p]] != 0)
    {
      if(std::abs(std::abs(curvature[loop[p]]) - M_PI / 2) > 1e-12)
        return false;
      corners.push_back(p);
    }
  if(corners.size() != 4)
    return false;
  const Uv origin = uv[loop[corners[0]]], towards = uv[loop[corners[1]]];
  const double angle = std::atan2(towards[1] - origin[1], towards[0] - origin[0]);
  const double c = std::cos(angle), s = std::sin(angle);
  for(Uv& p : uv)
  {
    const double x = p[0] - origin[0], y = p[1] - origin[1];
    p = {c * x + s * y, -s * x + c * y};
  }
  for(int side = 0; side < 4; ++side)
  {
    const int from = corners[side], to = corners[(side + 1) % 4];
    const Uv start = uv[loop[from]], end = uv[loop[to]];
    const int axis = std::abs(end[0] - start[0]) > std::abs(end[1] - start[1]) ? 1 : 0; // the coordinate kept
    for(int p = from;; p = (p + 1) % n)
    {
      uv[loop[p]][axis] = start[axis];
      if(p == to)
        break;
    }
    // The stretch a corner starts is numbered by it: this side is stretch `side`.
    for(int v = 0; v < index.number_of_vertices(); ++v)
      if(!index.is_boundary_vertex[v] && stretches[v][0] == side)
        uv[v][axis] = start[axis];
  }
  return true;
}

/// The circle-domain targets at the metric of `u`: per loop, the circle through its
/// polygon of metric lengths, and each vertex's turning angle on it (outer loop +, holes -).
/// Interior vertices 0. Returns false (with `why`) when a loop has no circumscribed circle.
template <class Metric>
bool circle_domain_targets(const Mesh_index& index, const Metric& metric, const Eigen::VectorXd& u,
                           int outer_loop, Eigen::VectorXd& target, std::vector<double>& lengths,
                           std::vector<double>& radii, std::string& why)
{
  target.setZero(index.number_of_vertices());
  radii.resize(index.number_of_boundary_loops());
  for(int l = 0; l < index.number_of_boundary_loops(); ++l)
  {
    const std::vector<int>& loop = index.boundary_loops[l];
    const std::vector<int>& loop_edges = index.boundary_loop_edges[l];
    const std::size_t n = loop.size();
    lengths.resize(n);
    // Border edges never flip, so their ids and lengths are the mesh's in every metric.
    for(std::size_t i = 0; i < n; ++i)
      lengths[i] = metric.length(loop_edges[i], std::exp(u[loop[i]]), std::exp(u[loop[(i + 1) % n]]));
    const Inscribed_circle circle = inscribed_circle(lengths);
    if(!circle.exists)
    {
      why = "border loop " + std::to_string(l) + " (" + std::to_string(n) +
            " edges) has no circumscribed circle: one edge is longer than all others together";
      return false;
    }
    radii[l] = circle.radius;
    const double sign = l == outer_loop ? 1.0 : -1.0;
    auto theta = [&](std::size_t e) {
      const double half = std::asin(std::min(1.0, lengths[e] / (2 * circle.radius)));
      return static_cast<int>(e) == circle.long_side ? 2 * M_PI - 2 * half : 2 * half;
    };
    // Vertex loop[i] lies between side i-1 (from loop[i-1]) and side i (to loop[i+1]).
    for(std::size_t i = 0; i < n; ++i)
      target[loop[i]] = sign * 0.5 * (theta((i + n - 1) % n) + theta(i));
  }
  return true;
}

/// Anderson acceleration (type II) of a fixed-point map x -> g(x): from the last `depth`
/// residuals f = g(x) - x, the combination of the g's whose residual is least in the
/// least-squares sense. Plain x <- g(x) when the history is empty.
class Anderson_mixing
{
public:
  explicit Anderson_mixing(int depth) : depth_(depth) {}

  void reset()
  {
    x_.clear();
    f_.clear();
  }

  /// The next iterate from the current x and g(x).
  Eigen::VectorXd next(const Eigen::VectorXd& x, const Eigen::VectorXd& gx)
  {
    Eigen::VectorXd f = gx - x;
    x_.push_back(x);
    f_.push_back(f);
    if(static_cast<int>(x_.size()) > depth_ + 1)
    {
      x_.pop_front();
      f_.pop_front();
    }
    const int m = static_cast<int>(x_.size()) - 1;
    if(m == 0)
      return gx;
    // Minimise |f - dF gamma| over gamma, dF's columns the differences of successive f.
    Eigen::MatrixXd dF(f.size(), m), dX(f.size(), m);
    for(int j = 0; j < m; ++j)
    {
      dF.col(j) = f_[j + 1] - f_[j];
      dX.col(j) = x_[j + 1] - x_[j];
    }
    const Eigen::VectorXd gamma = dF.colPivHouseholderQr().solve(f);
    if(!gamma.allFinite())
    {
      reset();
      return gx;
    }
    return gx - (dX + dF) * gamma;
  }

private:
  int depth_;
  std::deque<Eigen::VectorXd> x_, f_;
};

} // namespace internal

/// What a border solve did (`solve_prescribed_border`, `solve_circle_domain`).
struct Border_solve_report
{
  bool converged = false;
  std::string message;
  int newton_iterations = 0;  ///< Newton steps of every inverse curvature map solved
  int outer_iterations = 0;   ///< circle domain: evaluations of u <- K^{-1}(T(u))
  /// max |K(u) - target| over all vertices (circle domains: the targets at the final u) at
  /// the start of each outer iteration, and at the end.
  std::vector<double> residual_history;
  double final_residual() const { return residual_history.empty() ? 0.0 : residual_history.back(); }
};

namespace internal {

/// Where a prescribed curvature was missed most, and how far it was from the start: "...
/// is at border vertex 2, where the target turns 1.571 rad and the mesh turns -2.747 rad". A
/// target far from the mesh's own curvature at a few vertices (a square's corner put where
/// the border is concave) is the usual reason Newton cannot reach it.
template <class Metric>
std::string largest_curvature_miss(Curvature_map<Metric>& curvature, const Eigen::VectorXd& target,
                                   const Eigen::VectorXd& start_curvature, const Eigen::VectorXd& u)
{
  Eigen::VectorXd k;
  if(curvature.evaluate(u, k) > 0 || !k.allFinite())
    k = start_curvature;
  Eigen::Index v = 0;
  (k - target).cwiseAbs().maxCoeff(&v);
  const bool border = curvature.mesh_index().is_boundary_vertex[v];
  std::ostringstream out;
  out.precision(4);
  out << "; the largest curvature error (" << std::abs(k[v] - target[v]) << " rad) is at "
      << (border ? "border vertex " : "vertex ") << v << ", where the target " << (border ? "turns" : "has curvature")
      << " " << target[v] << " rad and the mesh " << (border ? "turns" : "has") << " " << start_curvature[v] << " rad";
  return out.str();
}

} // namespace internal

/// Algorithm 1 for a prescribed curvature `target` (Gauss-Bonnet already checked): u moves
/// from its value until K(u) = target. `solver` must have been built with every vertex free
/// but one (the scale). When Newton fails, the message also names the vertex whose target
/// was missed most and its curvature at the start.
template <class SparseSolver, class Metric>
Border_solve_report solve_prescribed_border(Inverse_curvature_map<SparseSolver, Metric>& solver,
                                            const Eigen::VectorXd& target, Eigen::VectorXd& u,
                                            const Newton_options& options)
{
  Border_solve_report report;
  Eigen::VectorXd start_curvature;
  solver.curvature_map().evaluate(u, start_curvature);
  const Newton_report newton = solver.solve(target, u, options);
  report.newton_iterations = newton.iterations;
  report.residual_history = newton.residual_history;
  report.converged = newton.converged;
  report.message = newton.message;
  if(!newton.converged)
    report.message += internal::largest_curvature_miss(solver.curvature_map(), target, start_curvature, u);
  return report;
}

/// The circle domain metric: the fixed point u = K^{-1}(T(u)) of the circle targets T
/// (`internal::circle_domain_targets`), Anderson-accelerated, each K^{-1} a Newton solve
/// warm-started from the current u. Converged when max |K(u) - T(u)| <= options.tolerance.
/// `solver` must have been built with every vertex free but one (the scale).
template <class SparseSolver, class Metric>
Border_solve_report solve_circle_domain(Inverse_curvature_map<SparseSolver, Metric>& solver,
                                        const internal::Mesh_index& index, const Border_target& circles,
                                        Eigen::VectorXd& u, const Newton_options& options)
{
  Border_solve_report report;
  Eigen::VectorXd target, gu, last_gu;
  std::vector<double> lengths, radii;
  internal::Anderson_mixing anderson(circles.anderson_depth);
  // Each inner solve goes a decade below the outer tolerance, so that the fixed point is
  // not limited by it.
  Newton_options inner = options;
  inner.tolerance = options.tolerance / 10;
  for(;; ++report.outer_iterations)
  {
    const Metric& metric = solver.curvature_map().metric();
    if(!internal::circle_domain_targets(index, metric, u, circles.outer_loop, target, lengths, radii,
                                        report.message))
      return report;
    gu = u;
    Newton_report newton = solver.solve(target, gu, inner);
    if(newton.residual_history.empty() && report.outer_iterations > 0)
    {
      // The extrapolated u left the metric's valid region: restart plain from the last g.
      anderson.reset();
      u = last_gu;
      continue;
    }
    report.newton_iterations += newton.iterations;
    const double residual = newton.residual_history.empty() ? HUGE_VAL : newton.residual_history.front();
    report.residual_history.push_back(residual);
    if(!newton.converged)
    {
      report.message = "circle domain, outer iteration " + std::to_string(report.outer_iterations) +
                       ": " + newton.message;
      return report;
    }
    if(residual <= options.tolerance)
    {
      u = gu;
      // The pinned vertex is outside Newton's residual: measure every vertex at the end.
      if(!internal::circle_domain_targets(index, metric, u, circles.outer_loop, target, lengths, radii,
                                          report.message))
        return report;
      Eigen::VectorXd k;
      solver.curvature_map().evaluate(u, k);
      const double final_residual = (k - target).cwiseAbs().maxCoeff();
      report.residual_history.push_back(final_residual);
      report.converged = true;
      return report;
    }
    if(report.outer_iterations == circles.max_iterations)
    {
      report.message = "the circle domain did not converge in " + std::to_string(circles.max_iterations) +
                       " outer iterations (curvature error " + std::to_string(residual) + ")";
      return report;
    }
    last_gu = gu;
    u = anderson.next(u, gu);
  }
}

/// How far the layout of each border loop is from a circle: per loop, the circle fitted to
/// its vertices by least squares (Kasa's algebraic fit, exact for points on a circle), and
/// max |distance to its centre - radius| / radius; the largest over the loops.
inline double max_circle_deviation(const internal::Mesh_index& index, const std::vector<Uv>& uv)
{
  double worst = 0;
  for(const std::vector<int>& loop : index.boundary_loops)
  {
    // Centred at the mean first, so that the normal equations keep their digits.
    double mx = 0, my = 0;
    for(int v : loop)
    {
      mx += uv[v][0];
      my += uv[v][1];
    }
    mx /= loop.size();
    my /= loop.size();
    Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for(int v : loop)
    {
      const Eigen::Vector3d row(uv[v][0] - mx, uv[v][1] - my, 1.0);
      const double rhs = -(row[0] * row[0] + row[1] * row[1]);
      a += row * row.transpose();
      b += rhs * row;
    }
    const Eigen::Vector3d def = a.ldlt().solve(b); // x^2 + y^2 + D x + E y + F = 0
    const double cx = -def[0] / 2, cy = -def[1] / 2;
    const double radius = std::sqrt(cx * cx + cy * cy - def[2]);
    for(int v : loop)
      worst = std::max(worst, std::abs(std::hypot(uv[v][0] - mx - cx, uv[v][1] - my - cy) - radius) / radius);
  }
  return worst;
}

/// \brief The free boundary (default): every border vertex singular, the border curvature
/// the optimum of the curvature entropy (paper Thm 3.5), or of the parameterizer's `Energy`.
struct Free_border
{
  std::string name() const { return "free"; }

  template <class TriangleMesh, class VertexIndexMap>
  Border_target target(const TriangleMesh&, typename boost::graph_traits<TriangleMesh>::halfedge_descriptor,
                       const internal::Mesh_index&,
                       const std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>&,
                       VertexIndexMap) const
  {
    return Border_target();
  }
};

/// \brief The user's geodesic curvature (turning angle, radians) at every border vertex; the
/// interior is flat and the metric is u = K^{-1}(k) (Algorithm 1).
///
/// The turning angle at a border vertex is pi minus its interior angle in the layout: a
/// square's corners have pi/2, a straight border vertex 0, a reflex one a negative value.
/// The values must satisfy Gauss-Bonnet, sum over the border = 2 pi chi (2 pi on a disk);
/// else the parameterizer refuses with `ERROR_WRONG_PARAMETER` and the sum in its message.
/// Values at interior vertices are ignored. Needs a topological disk.
///
/// \tparam VertexCurvatureMap a model of `ReadablePropertyMap`, key the mesh's
///         `vertex_descriptor`, value convertible to `double`
template <class VertexCurvatureMap>
class Prescribed_border_curvature
{
public:
  explicit Prescribed_border_curvature(VertexCurvatureMap curvature = VertexCurvatureMap())
    : curvature_(curvature)
  {}

  std::string name() const { return "prescribed-curvature"; }
  const VertexCurvatureMap& curvature_map() const { return curvature_; }

  template <class TriangleMesh, class VertexIndexMap>
  Border_target target(const TriangleMesh&, typename boost::graph_traits<TriangleMesh>::halfedge_descriptor,
                       const internal::Mesh_index& index,
                       const std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& vertices,
                       VertexIndexMap) const
  {
    Border_target t;
    t.kind = Border_kind::Prescribed_curvature;
    t.curvature.setZero(index.number_of_vertices());
    for(int v = 0; v < index.number_of_vertices(); ++v)
      if(index.is_boundary_vertex[v])
        t.curvature[v] = static_cast<double>(get(curvature_, vertices[v]));
    return internal::checked_gauss_bonnet(index, std::move(t), "the prescribed border curvature");
  }

private:
  VertexCurvatureMap curvature_;
};

/// \brief The border's angles of the polygon that a CGAL border parameterizer draws: conformal
/// inside, each border vertex turning as in that polygon.
///
/// `BorderParameterizer` is run as CGAL's fixed-border parameterizers run it,
/// `parameterize(mesh, bhd, uvmap, vimap, vpmap)`; the turning angle of its polygon at each
/// border vertex becomes the target (values within 1e-12 of 0 are 0, so the sides are
/// straight), then as `Prescribed_border_curvature`. A square's four corners get pi/2 and
/// the result is a rectangle whose aspect ratio is the border's conformal modulus, with the
/// corners CGAL chose (or gave it). Where the vertices fall along the sides is decided by
/// conformality, not by the border parameterizer's spacing.
///
/// A circle (a border parameterizer derived from `Circular_border_parameterizer_3`) is the
/// one shape whose angles alone do not make it: the condition is then the circle's own (as
/// `Circle_domain` with one loop), the conformal map to the disk.
///
/// Needs a topological disk. `name()` is "square", "circle", or "polygon" for another border
/// parameterizer.
///
/// \tparam BorderParameterizer a CGAL border parameterizer, e.g.
///         `CGAL::Surface_mesh_parameterization::Square_border_arc_length_parameterizer_3<TriangleMesh>`
template <class BorderParameterizer>
class Border_shape
{
  using Shape = internal::Border_parameterizer_shape<BorderParameterizer>;

public:
  using Border_parameterizer = BorderParameterizer;

  explicit Border_shape(const BorderParameterizer& border = BorderParameterizer()) : border_(border) {}

  std::string name() const { return Shape::is_circle ? "circle" : Shape::is_square ? "square" : "polygon"; }
  const BorderParameterizer& border_parameterizer() const { return border_; }

  template <class TriangleMesh, class VertexIndexMap>
  Border_target target(const TriangleMesh& mesh, typename boost::graph_traits<TriangleMesh>::halfedge_descriptor bhd,
                       const internal::Mesh_index& index,
                       const std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& vertices,
                       VertexIndexMap vimap) const
  {
    if constexpr(Shape::is_circle)
    {
      Border_target t;
      t.kind = Border_kind::Circles;
      t.outer_loop = 0;
      return t;
    }
    else
      return polygon_target(mesh, bhd, index, vertices, vimap);
  }

private:
  template <class TriangleMesh, class VertexIndexMap>
  Border_target polygon_target(const TriangleMesh& mesh,
                               typename boost::graph_traits<TriangleMesh>::halfedge_descriptor bhd,
                               const internal::Mesh_index& index,
                               const std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& vertices,
                               VertexIndexMap vimap) const
  {
    using Point_2 =
      typename CGAL::Surface_mesh_parameterization::internal::Kernel_traits<TriangleMesh>::Kernel::Point_2;
    // Property maps over the vertex index map, fresh for this call: CGAL's square border
    // reads `vpmap` to find the corners it has set.
    std::size_t size = 0;
    for(const auto& v : vertices)
      size = std::max<std::size_t>(size, get(vimap, v) + 1);
    std::vector<Point_2> uv_storage(size);
    std::vector<bool> parameterized_storage(size, false);
    auto uvmap = boost::make_iterator_property_map(uv_storage.begin(), vimap);
    auto vpmap = boost::make_iterator_property_map(parameterized_storage.begin(), vimap);
    BorderParameterizer border = border_;
    const auto status = border.parameterize(mesh, bhd, uvmap, vimap, vpmap);
    if(status != CGAL::Surface_mesh_parameterization::OK)
    {
      Border_target t = internal::refused(std::string("the border parameterizer failed: ") +
                                          CGAL::Surface_mesh_parameterization::get_error_message(status));
      t.status = status;
      return t;
    }

    Border_target t;
    t.kind = Border_kind::Prescribed_curvature;
    t.curvature.setZero(index.number_of_vertices());
    const std::vector<int>& loop = index.boundary_loops[0];
    const std::size_t n = loop.size();
    double total = 0;
    for(std::size_t i = 0; i < n; ++i)
    {
      const Point_2 &p = get(uvmap, vertices[loop[(i + n - 1) % n]]), &q = get(uvmap, vertices[loop[i]]),
                    &r = get(uvmap, vertices[loop[(i + 1) % n]]);
      const double ax = CGAL::to_double(q.x() - p.x()), ay = CGAL::to_double(q.y() - p.y());
      const double bx = CGAL::to_double(r.x() - q.x()), by = CGAL::to_double(r.y() - q.y());
      if((ax == 0 && ay == 0) || (bx == 0 && by == 0))
        return internal::refused("the border parameterizer put two border vertices at one point");
      double turning = std::atan2(ax * by - ay * bx, ax * bx + ay * by);
      if(std::abs(turning) <= 1e-12)
        turning = 0;
      t.curvature[loop[i]] = turning;
      total += turning;
    }
    // The index's loop may run either way round the polygon: the domain is to the left
    // when the turning angles add up to +2 pi.
    if(total < 0)
      t.curvature = -t.curvature;
    for(std::size_t i = 0; i < n; ++i)
      if(!(std::abs(t.curvature[loop[i]]) < M_PI - 1e-9))
        return internal::refused("the border polygon folds back on itself at border vertex " + std::to_string(loop[i]));
    return internal::checked_gauss_bonnet(index, std::move(t), "the border shape's turning angles");
  }

  BorderParameterizer border_;
};

/// `Border_shape` with CGAL's arc-length square border: a rectangle.
template <class TriangleMesh>
using Square_border =
  Border_shape<CGAL::Surface_mesh_parameterization::Square_border_arc_length_parameterizer_3<TriangleMesh>>;
/// `Border_shape` with CGAL's arc-length circular border: the disk.
template <class TriangleMesh>
using Circular_border =
  Border_shape<CGAL::Surface_mesh_parameterization::Circular_border_arc_length_parameterizer_3<TriangleMesh>>;

/// \brief A genus-0 mesh with any number of border loops, mapped without a cut onto a circle
/// domain (paper Fig. 8): the outer loop a circle with the domain inside, every other loop a
/// circle with the domain outside, the interior flat.
///
/// The condition is the exact one of inscribed polygons for any metric (header comment);
/// the metric is the fixed point of u <- K^{-1}(T(u)), Anderson-accelerated.
/// The outer loop is the longest in 3D (`Outer_loop::Longest`, default), or the loop of the
/// border halfedge given to `parameterize()` (`Outer_loop::Of_border_halfedge`).
class Circle_domain
{
public:
  enum class Outer_loop
  {
    Longest,            ///< the loop of largest 3D length
    Of_border_halfedge  ///< the loop of the halfedge passed to `parameterize()`
  };

  explicit Circle_domain(Outer_loop outer = Outer_loop::Longest, int max_iterations = 200, int anderson_depth = 6)
    : outer_(outer), max_iterations_(max_iterations), anderson_depth_(anderson_depth)
  {}

  std::string name() const { return "circle-domain"; }
  Outer_loop outer_loop() const { return outer_; }

  template <class TriangleMesh, class VertexIndexMap>
  Border_target target(const TriangleMesh& mesh, typename boost::graph_traits<TriangleMesh>::halfedge_descriptor bhd,
                       const internal::Mesh_index& index,
                       const std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& vertices,
                       VertexIndexMap) const
  {
    Border_target t;
    t.kind = Border_kind::Circles;
    t.max_iterations = max_iterations_;
    t.anderson_depth = anderson_depth_;
    t.outer_loop = internal::longest_loop(index);
    if(outer_ == Outer_loop::Of_border_halfedge)
    {
      const auto v = std::find(vertices.begin(), vertices.end(), internal::target_vertex(bhd, mesh));
      t.outer_loop = v == vertices.end() ? -1 : internal::loop_of_vertex(index, static_cast<int>(v - vertices.begin()));
      if(t.outer_loop < 0)
        return internal::refused("the border halfedge given is not on a border loop of its component");
    }
    return t;
  }

private:
  Outer_loop outer_;
  int max_iterations_, anderson_depth_;
};

} // namespace ICM

#endif // ICM_BORDER_BORDER_CONDITIONS_H
