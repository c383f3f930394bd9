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
// The state (`Energy_state`) holds u, u0, the metric's edge lengths and Jacobian weights on
// its triangulation, and per face of the MESH: its area and corner angles under the metric,
// and the mesh's own 3D area and angles. Per-face terms are evaluated on the mesh's faces,
// because that is what a parameterization is judged on (Table I, eq. 8, measures the layout
// of the mesh's faces). When the metric keeps the mesh's triangulation (circle packing,
// inversive distance, vertex scaling) those are the metric's own faces. A metric that flips
// its own triangulation (the default `Intrinsic_delaunay_metric`) has other faces than the
// mesh, which change with u, and the reference of a face the mesh does not have would be
// undefined; there the mesh's faces are measured in the development of the metric into the
// plane (the layout the parameterizer draws): every vertex is placed from the metric's
// corner angles, face by face across its triangulation, and the mesh's faces are the
// triangles between the placed vertices. This is continuous across the metric's flips (a
// Delaunay flip keeps the metric, so the development) and exact wherever the metric is flat
// off the border, i.e. for S = the border. With interior cones it is developed cut open
// along the edges the metric keeps fixed (the seams `ICM::parameterize` gives it, which pass
// through every cone): each side of a seam is a wedge of its own, placed from its own faces,
// so the development is the cut surface's layout and exact wherever the metric is flat off
// the singular set (doc/energies.md).

#ifndef ICM_OPTIMUM_ENERGIES_H
#define ICM_OPTIMUM_ENERGIES_H

#include <ICM/curvature/Curvature_map.h>
#include <ICM/layout/Layout.h>
#include <ICM/measures/Distortion.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/metrics/Vertex_scaling_metric.h>
#include <ICM/internal/Circle_metric.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Triangle_geometry.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <type_traits>
#include <utility>
#include <vector>

namespace ICM {

/// Partial derivatives of an energy with respect to the quantities of an `Energy_state`;
/// an energy's `gradient` adds to them (they start at zero).
struct Energy_gradient
{
  Eigen::VectorXd u;                        ///< dE/du_v with areas and angles held fixed
  std::vector<double> area;                 ///< dE/d area(f), per mesh face
  std::vector<std::array<double, 3>> angle; ///< dE/d angle(f, c), per mesh face corner

  void reset(int vertices, int faces)
  {
    u.setZero(vertices);
    area.assign(faces, 0.0);
    angle.assign(faces, {0.0, 0.0, 0.0});
  }
};

namespace internal {

/// Whether a metric states d log l / du itself (`m.log_length_derivatives(e, gi, gj)`).
template <class Metric, class = void>
struct Has_log_length_derivatives : std::false_type
{};
template <class Metric>
struct Has_log_length_derivatives<
  Metric, std::void_t<decltype(std::declval<const Metric&>().log_length_derivatives(0, 1.0, 1.0))>>
  : std::true_type
{};

/// {d log l_e / d u_i, d log l_e / d u_j} for the edge e = ij with factors gi = exp(u_i),
/// gj = exp(u_j). Exact for the repository's metrics; a user's metric may provide
/// `log_length_derivatives`, else central differences are used (relative error ~1e-10).
template <class Metric>
std::array<double, 2> log_length_derivatives(const Metric& metric, int e, double gi, double gj)
{
  if constexpr(Has_log_length_derivatives<Metric>::value)
    return metric.log_length_derivatives(e, gi, gj);
  else if constexpr(std::is_base_of<Circle_metric, Metric>::value)
  {
    // l^2 = gi^2 + gj^2 + 2 I gi gj: d l^2 / d u_i = 2 gi (gi + I gj).
    const double I = metric.inversive_distance[e];
    const double l2 = gi * gi + gj * gj + 2.0 * I * gi * gj;
    return {gi * (gi + I * gj) / l2, gj * (gj + I * gi) / l2};
  }
  else if constexpr(std::is_same<Metric, Vertex_scaling_metric>::value ||
                    std::is_same<Metric, Intrinsic_delaunay_metric>::value)
    return {0.5, 0.5}; // l = e^{(u_i + u_j)/2} l0
  else
  {
    const double h = 1e-5, up = std::exp(h), down = std::exp(-h);
    return {(std::log(metric.length(e, gi * up, gj)) - std::log(metric.length(e, gi * down, gj))) / (2 * h),
            (std::log(metric.length(e, gi, gj * up)) - std::log(metric.length(e, gi, gj * down))) / (2 * h)};
  }
}

/// d theta_c / d u_{v_d} of a face from its Jacobian weights: weight[c] is the derivative of
/// either angle at the ends of the edge opposite c by the u of the other end, and a uniform
/// change of u leaves every angle alone, so d theta_c / d u_{v_c} is minus the other two.
inline double angle_derivative(const std::array<double, 3>& weight, int c, int d)
{
  if(c == d)
    return -(weight[(c + 1) % 3] + weight[(c + 2) % 3]);
  return weight[3 - c - d]; // the corner that is neither c nor d: opposite edge cd
}

using Point2 = std::array<double, 2>;

/// Whether a metric keeps some edges of its own triangulation fixed (`m.fixed_edges()`, the
/// seams): a development of it is cut along them.
template <class Metric, class = void>
struct Has_fixed_edges : std::false_type
{};
template <class Metric>
struct Has_fixed_edges<Metric, std::void_t<decltype(std::declval<const Metric&>().fixed_edges())>>
  : std::true_type
{};

/// The seams of a metric's development, per edge: its fixed edges, or none.
template <class Metric>
std::vector<char> development_seams(const Metric& metric, int edges)
{
  if constexpr(Has_fixed_edges<Metric>::value)
    if(static_cast<int>(metric.fixed_edges().size()) == edges)
      return metric.fixed_edges();
  return std::vector<char>(edges, 0);
}

inline double cross(const Point2& a, const Point2& b) { return a[0] * b[1] - a[1] * b[0]; }
inline double dot(const Point2& a, const Point2& b) { return a[0] * b[0] + a[1] * b[1]; }
inline Point2 minus(const Point2& a, const Point2& b) { return {a[0] - b[0], a[1] - b[1]}; }
inline Point2 rotated(const Point2& d, double angle)
{
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * d[0] - s * d[1], s * d[0] + c * d[1]};
}

} // namespace internal

/// What an energy reads: u and u0, the metric at u (edge lengths and Jacobian weights on its
/// triangulation), and per face of the mesh its area and corner angles under the metric next
/// to the mesh's own 3D area and angles (see the file comment for which faces). Areas are
/// normalised so that their total is the mesh's total area.
///
/// Built once per mesh; `update` measures the metric at a new u. The mesh index must outlive
/// the state.
template <class Metric>
class Energy_state
{
public:
  /// True when the per-face quantities come from the development of a metric that flips
  /// its own triangulation, false when they are the metric's own faces.
  static constexpr bool develops_faces = Curvature_map<Metric>::has_intrinsic_triangulation;

  explicit Energy_state(const internal::Mesh_index& mesh) : mesh_(mesh)
  {
    const int nf = mesh.number_of_faces();
    mesh_area_.resize(nf);
    mesh_angle_.resize(nf);
    mesh_total_area_ = 0;
    for(int f = 0; f < nf; ++f)
    {
      const auto& p = mesh.points;
      const auto& v = mesh.faces[f];
      mesh_area_[f] = internal::triangle_area(p[v[0]], p[v[1]], p[v[2]]);
      mesh_angle_[f] = internal::distortion::corner_angles(p[v[0]], p[v[1]], p[v[2]]);
      mesh_total_area_ += mesh_area_[f];
    }
  }
  Energy_state(internal::Mesh_index&&) = delete; // holds a reference

  /// Measures the metric of `curvature` at `u` (flipping its triangulation first if it has
  /// one). Returns false when some face of the metric is not a triangle at u. With
  /// `measure_faces` false the mesh's faces are not measured (for a metric with its own
  /// triangulation: not developed), only the metric's lengths, weights and curvature, which
  /// is all a Newton step needs; `measure_faces()` completes the state.
  bool update(Curvature_map<Metric>& curvature, const Eigen::VectorXd& u, bool measure_faces = true)
  {
    curvature_ = &curvature;
    u_ = u;
    u0_ = curvature.metric().u0;
    lengths_ = curvature.compute_lengths(u);
    const internal::Mesh_index& t = curvature.mesh_index();
    const int nt = t.number_of_faces();
    radii_ = u.array().exp();
    geometry_.resize(nt);
    weights_.assign(t.number_of_edges(), 0.0);
    k_.resize(t.number_of_vertices());
    for(int v = 0; v < t.number_of_vertices(); ++v)
      k_[v] = t.is_boundary_vertex[v] ? M_PI : 2.0 * M_PI;
    invalid_faces_ = 0;
    for(int f = 0; f < nt; ++f)
    {
      const std::array<int, 3>& v = t.faces[f];
      const std::array<int, 3>& e = t.face_edges[f];
      geometry_[f] = curvature.metric().face_geometry(e, {radii_[v[0]], radii_[v[1]], radii_[v[2]]},
                                                      {lengths_[e[0]], lengths_[e[1]], lengths_[e[2]]});
      invalid_faces_ += !geometry_[f].valid;
      for(int c = 0; c < 3; ++c)
      {
        weights_[e[c]] += geometry_[f].weight[c];
        k_[v[c]] -= geometry_[f].angles.angle[c];
      }
    }
    if(measure_faces)
      this->measure_faces();
    return invalid_faces_ == 0;
  }

  /// Measures the mesh's faces at the metric of the last `update`.
  void measure_faces()
  {
    if constexpr(develops_faces)
      measure_developed_faces(curvature_->mesh_index());
    else
      measure_metric_faces();
  }

  const internal::Mesh_index& mesh() const { return mesh_; }
  /// The metric's triangulation at u: the mesh's, or the metric's own.
  const internal::Mesh_index& triangulation() const { return curvature_->mesh_index(); }
  const Eigen::VectorXd& u() const { return u_; }
  const Eigen::VectorXd& u0() const { return u0_; }
  /// Per edge of `triangulation()`: the metric's length and its Jacobian weight
  /// w_ij = d theta / d u summed over the edge's faces (Delta_ij = -w_ij).
  const std::vector<double>& lengths() const { return lengths_; }
  const std::vector<double>& weights() const { return weights_; }
  /// The curvature K(u) per vertex (as `Curvature_map::evaluate` gives it).
  const Eigen::VectorXd& curvature() const { return k_; }
  /// Faces of the metric that are not triangles at u (possible for vertex scaling and
  /// inversive distance only).
  int invalid_faces() const { return invalid_faces_; }

  int number_of_faces() const { return mesh_.number_of_faces(); }
  /// Area of mesh face f under the metric, scaled so that the total is the mesh's total
  /// area. Negative for a face flipped in the development.
  double area(int f) const { return area_[f] * area_scale_; }
  /// Corner angle c of mesh face f under the metric (negative in a flipped developed face).
  double angle(int f, int c) const
  {
    if constexpr(develops_faces)
    {
      // Measured when first asked after a development: three arctangents per face are a
      // sixth of an update on the horse, and only the angle energies read them.
      if(!developed_angles_current_)
        measure_developed_angles();
      return developed_angle_[f][c];
    }
    else
      return angle_[f][c];
  }
  double mesh_area(int f) const { return mesh_area_[f]; }
  double mesh_angle(int f, int c) const { return mesh_angle_[f][c]; }
  double mesh_total_area() const { return mesh_total_area_; }
  /// The developed wedges (when `develops_faces`): the metric laid out in the plane, cut
  /// along its seams. Corner c of mesh face f lies at `development()[developed_corner(f, c)]`.
  const std::vector<std::array<double, 2>>& development() const { return z_; }
  int developed_corner(int f, int c) const { return mesh_wedges_[f][c]; }

  /// The gradient with respect to u of an energy whose partial derivatives are `partials`,
  /// by the chain rule through the metric: exact, because the angle derivatives are the
  /// Jacobian weights the metric states and the length derivatives are the metric's own.
  void gradient_u(const Energy_gradient& partials, Eigen::VectorXd& gradient) const
  {
    gradient = partials.u;
    // The normalisation area = raw * A / S with S the raw total: d/d raw_g of
    // sum_f P_f area_f is (A / S) (P_g - sum_f P_f area_f / A).
    double weighted = 0;
    for(int f = 0; f < number_of_faces(); ++f)
      weighted += partials.area[f] * area(f);
    raw_area_partial_.resize(number_of_faces());
    for(int f = 0; f < number_of_faces(); ++f)
      raw_area_partial_[f] = area_scale_ * (partials.area[f] - weighted / mesh_total_area_);
    if constexpr(develops_faces)
      chain_through_development(partials, gradient);
    else
      chain_through_metric_faces(partials, gradient);
  }

private:
  // --- Faces of the mesh = faces of the metric -------------------------------------------

  void measure_metric_faces()
  {
    const int nf = mesh_.number_of_faces();
    area_.resize(nf);
    angle_.resize(nf);
    double total = 0;
    for(int f = 0; f < nf; ++f)
    {
      area_[f] = geometry_[f].angles.area;
      angle_[f] = geometry_[f].angles.angle;
      total += area_[f];
    }
    area_scale_ = mesh_total_area_ / total;
  }

  /// log area = (1/3) sum_c (log l_{c+1} + log l_{c+2} + log sin theta_c) - log 2, so
  /// d log area = (2/3) sum_e d log l_e + (1/3) sum_c cot theta_c d theta_c.
  void chain_through_metric_faces(const Energy_gradient& partials, Eigen::VectorXd& gradient) const
  {
    const internal::Mesh_index& t = triangulation();
    const Metric& metric = curvature_->metric();
    for(int f = 0; f < t.number_of_faces(); ++f)
    {
      const std::array<int, 3>& v = t.faces[f];
      const std::array<int, 3>& e = t.face_edges[f];
      const Face_geometry& face = geometry_[f];
      const double log_area_partial = raw_area_partial_[f] * area_[f];
      std::array<double, 3> angle_partial = partials.angle[f];
      for(int c = 0; c < 3; ++c)
      {
        const double theta = face.angles.angle[c];
        angle_partial[c] += log_area_partial * std::cos(theta) / std::sin(theta) / 3.0;
        // Edge e[c] joins corners c+1 and c+2.
        const int a = (c + 1) % 3, b = (c + 2) % 3;
        const std::array<double, 2> d =
          internal::log_length_derivatives(metric, e[c], radii_[v[a]], radii_[v[b]]);
        gradient[v[a]] += 2.0 / 3.0 * log_area_partial * d[0];
        gradient[v[b]] += 2.0 / 3.0 * log_area_partial * d[1];
      }
      add_angle_chain(v, face.weight, angle_partial, gradient);
    }
  }

  static void add_angle_chain(const std::array<int, 3>& v, const std::array<double, 3>& weight,
                              const std::array<double, 3>& angle_partial, Eigen::VectorXd& gradient)
  {
    for(int c = 0; c < 3; ++c)
      for(int d = 0; d < 3; ++d)
        gradient[v[d]] += angle_partial[c] * internal::angle_derivative(weight, c, d);
  }

  // --- Faces of the mesh in the development of a metric with its own triangulation -------

  /// One vertex placed from face `face` of the triangulation, at `corner`, from the two
  /// vertices of the face already placed, a the next corner and b the one after:
  /// z_c = z_a + l_ac R(theta_a) (z_b - z_a) / |z_b - z_a|, the metric's length and angle.
  struct Placement
  {
    int face, corner;
  };

  /// Places every vertex by unfolding the triangulation from its central face, as
  /// `layout_by_propagation` does: least estimated error first (breadth first through thin
  /// faces loses every digit on the horse), and every new edge at the metric's length rather
  /// than at a ratio of lengths times an edge already placed, which would carry the relative
  /// error of that edge on (camelhead: edges off by 450 times their length). The order
  /// depends on the lengths only through comparisons, so the development is a smooth
  /// function of the metric's lengths and angles almost everywhere.
  void measure_developed_faces(const internal::Mesh_index& t)
  {
    if(mesh_wedges_.empty())
      cut_along_seams(internal::development_seams(curvature_->metric(), t.number_of_edges()));
    z_.assign(number_of_wedges_, {0.0, 0.0});
    // The order found for this triangulation is kept until the metric flips an edge: it
    // costs three quarters of the development, and a fixed order keeps the development one
    // smooth function of the lengths and angles between flips.
    if(!placements_.empty() && placements_version_ == curvature_->triangulation_version())
    {
      const std::vector<Placement> order = std::move(placements_);
      placements_.clear();
      const std::array<int, 3>& r = wedges_[order.front().face];
      z_[r[1]] = {lengths_[root_edge_], 0.0};
      for(const Placement& p : order)
        place(t, p.face, p.corner);
    }
    else
    {
      placements_version_ = curvature_->triangulation_version();
      find_development_order(t);
    }
    measure_developed_mesh_faces();
  }

  /// The wedges of the mesh's corners: a vertex off the seams is one wedge with its own id,
  /// the sides of a vertex on them are told apart by `wedge_key` (its vertex and the seam
  /// that ends it), which an intrinsic triangulation with the same seams shares.
  void cut_along_seams(const std::vector<char>& seams)
  {
    seams_ = seams;
    const int nv = mesh_.number_of_vertices();
    seam_degree_ = internal::seam_degrees(mesh_, seams_);
    mesh_wedges_ = mesh_.faces;
    number_of_wedges_ = nv;
    std::vector<std::pair<long long, int>> corners; // (key, 3 f + c)
    for(int f = 0; f < mesh_.number_of_faces(); ++f)
      for(int c = 0; c < 3; ++c)
        if(seam_degree_[mesh_.faces[f][c]] > 0)
          corners.push_back({internal::wedge_key(mesh_, seams_, f, c), 3 * f + c});
    std::sort(corners.begin(), corners.end());
    std::vector<char> has_own_id(nv, 0);
    wedge_of_key_.clear();
    for(const auto& [key, corner] : corners)
    {
      if(wedge_of_key_.empty() || wedge_of_key_.back().first != key)
      {
        const int v = mesh_.faces[corner / 3][corner % 3];
        wedge_of_key_.push_back({key, has_own_id[v] ? number_of_wedges_++ : v});
        has_own_id[v] = 1;
      }
      mesh_wedges_[corner / 3][corner % 3] = wedge_of_key_.back().second;
    }
  }

  /// The wedges of the triangulation's corners (its seam edges never flip, so each corner
  /// lies in a wedge of the mesh).
  void find_triangulation_wedges(const internal::Mesh_index& t)
  {
    wedges_ = t.faces;
    if(wedge_of_key_.empty())
      return;
    for(int f = 0; f < t.number_of_faces(); ++f)
      for(int c = 0; c < 3; ++c)
        if(seam_degree_[t.faces[f][c]] > 0)
        {
          const long long key = internal::wedge_key(t, seams_, f, c);
          const auto it = std::lower_bound(wedge_of_key_.begin(), wedge_of_key_.end(), std::make_pair(key, -1));
          if(it != wedge_of_key_.end() && it->first == key)
            wedges_[f][c] = it->second;
        }
  }

  void find_development_order(const internal::Mesh_index& t)
  {
    const int nv = number_of_wedges_;
    find_triangulation_wedges(t);
    placements_.clear();
    constexpr double eps = std::numeric_limits<double>::epsilon();
    // As in `layout_by_propagation_from`: the estimate may overflow on a long strip, so
    // "placed" is a flag of its own.
    std::vector<double> error(nv, 0.0);
    std::vector<char> placed(nv, 0);
    const int root = central_face(t);
    const std::array<int, 3>& r = wedges_[root];
    root_edge_ = t.face_edges[root][2];
    z_[r[0]] = {0.0, 0.0};
    z_[r[1]] = {lengths_[root_edge_], 0.0};
    // Errors in units of length, so that the order does not change with the global scale.
    error[r[0]] = error[r[1]] = eps * lengths_[root_edge_];
    place(t, root, 2);
    error[r[2]] = error[r[0]];
    placed[r[0]] = placed[r[1]] = placed[r[2]] = 1;

    const Faces_around_vertices around(wedges_, nv);
    using Candidate = std::pair<double, std::pair<int, int>>; // (error of the third vertex, (face, corner))
    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<Candidate>> queue;
    auto offer_faces_around = [&](int v) {
      for(int i = around.first[v]; i < around.first[v + 1]; ++i)
      {
        const int f = around.faces[i];
        const std::array<int, 3>& w = wedges_[f];
        for(int c = 0; c < 3; ++c)
        {
          const int a = w[(c + 1) % 3], b = w[(c + 2) % 3];
          if(placed[w[c]] || !placed[a] || !placed[b])
            continue;
          const double l_ab = lengths_[t.face_edges[f][c]], l_ac = lengths_[t.face_edges[f][(c + 2) % 3]];
          queue.push({error[a] + (error[a] + error[b]) * l_ac / l_ab + eps * l_ac, {f, c}});
        }
      }
    };
    for(int v : r)
      offer_faces_around(v);
    while(!queue.empty())
    {
      const auto [estimate, where] = queue.top();
      queue.pop();
      const int third = wedges_[where.first][where.second];
      if(placed[third])
        continue;
      place(t, where.first, where.second);
      error[third] = estimate;
      placed[third] = 1;
      offer_faces_around(third);
    }
  }

  void measure_developed_mesh_faces()
  {
    const int nf = mesh_.number_of_faces();
    area_.resize(nf);
    double total = 0;
    for(int f = 0; f < nf; ++f)
    {
      const std::array<int, 3>& v = mesh_wedges_[f];
      area_[f] = 0.5 * internal::cross(internal::minus(z_[v[1]], z_[v[0]]), internal::minus(z_[v[2]], z_[v[0]]));
      total += area_[f];
    }
    area_scale_ = mesh_total_area_ / total;
    developed_angles_current_ = false;
  }

  void measure_developed_angles() const
  {
    developed_angle_.resize(mesh_.number_of_faces());
    for(int f = 0; f < mesh_.number_of_faces(); ++f)
    {
      const std::array<int, 3>& v = mesh_wedges_[f];
      for(int c = 0; c < 3; ++c)
      {
        const internal::Point2 a = internal::minus(z_[v[(c + 1) % 3]], z_[v[c]]);
        const internal::Point2 b = internal::minus(z_[v[(c + 2) % 3]], z_[v[c]]);
        developed_angle_[f][c] = std::atan2(internal::cross(a, b), internal::dot(a, b));
      }
    }
    developed_angles_current_ = true;
  }

  void place(const internal::Mesh_index& t, int f, int c)
  {
    const std::array<int, 3>& v = wedges_[f];
    const int a = (c + 1) % 3, b = (c + 2) % 3;
    const internal::Point2 d = internal::minus(z_[v[b]], z_[v[a]]);
    const double scale = lengths_[t.face_edges[f][b]] / std::hypot(d[0], d[1]);
    const internal::Point2 w = internal::rotated(d, geometry_[f].angles.angle[a]);
    z_[v[c]] = {z_[v[a]][0] + scale * w[0], z_[v[a]][1] + scale * w[1]};
    placements_.push_back({f, c});
  }

  /// Reverse mode through the development: the partials of the mesh faces' areas and angles
  /// with respect to the placed points, back through every placement to the triangulation's
  /// lengths and angles, and from them to u by the metric's length derivatives and Jacobian
  /// weights.
  void chain_through_development(const Energy_gradient& partials, Eigen::VectorXd& gradient) const
  {
    const internal::Mesh_index& t = triangulation();
    std::vector<internal::Point2>& zbar = z_partial_;
    zbar.assign(z_.size(), {0.0, 0.0});
    auto add = [&zbar](int v, double x, double y) {
      zbar[v][0] += x;
      zbar[v][1] += y;
    };
    for(int f = 0; f < mesh_.number_of_faces(); ++f)
    {
      const std::array<int, 3>& v = mesh_wedges_[f];
      // area = (1/2) (z1 - z0) x (z2 - z0): d area / d z_i = (1/2) (y_j - y_k, x_k - x_j).
      const double q = 0.5 * raw_area_partial_[f];
      for(int c = 0; c < 3; ++c)
      {
        const internal::Point2 &zj = z_[v[(c + 1) % 3]], &zk = z_[v[(c + 2) % 3]];
        add(v[c], q * (zj[1] - zk[1]), q * (zk[0] - zj[0]));
      }
      // theta = angle from a = z_j - z_i to b = z_k - z_i: d theta / d a = (a_y, -a_x) / |a|^2,
      // d theta / d b = (-b_y, b_x) / |b|^2.
      for(int c = 0; c < 3; ++c)
      {
        const double p = partials.angle[f][c];
        if(p == 0.0)
          continue;
        const int i = v[c], j = v[(c + 1) % 3], k = v[(c + 2) % 3];
        const internal::Point2 a = internal::minus(z_[j], z_[i]), b = internal::minus(z_[k], z_[i]);
        const double aa = internal::dot(a, a), bb = internal::dot(b, b);
        const internal::Point2 da = {p * a[1] / aa, -p * a[0] / aa}, db = {-p * b[1] / bb, p * b[0] / bb};
        add(j, da[0], da[1]);
        add(k, db[0], db[1]);
        add(i, -da[0] - db[0], -da[1] - db[1]);
      }
    }

    std::vector<std::array<double, 3>>& theta_bar = angle_partial_;
    theta_bar.assign(t.number_of_faces(), {0.0, 0.0, 0.0});
    std::vector<double>& length_bar = length_partial_;
    length_bar.assign(t.number_of_edges(), 0.0);
    for(auto it = placements_.rbegin(); it != placements_.rend(); ++it)
    {
      // z_c = z_a + l_ac w, w = R(theta_a) n, n = d / |d|, d = z_b - z_a.
      const int f = it->face, c = it->corner, a = (c + 1) % 3, b = (c + 2) % 3;
      const std::array<int, 3>& v = wedges_[f];
      const double theta = geometry_[f].angles.angle[a];
      const int ac = t.face_edges[f][b];
      const internal::Point2 Z = zbar[v[c]];
      const internal::Point2 d = internal::minus(z_[v[b]], z_[v[a]]);
      const double norm = std::hypot(d[0], d[1]);
      const internal::Point2 n = {d[0] / norm, d[1] / norm};
      const internal::Point2 w = internal::rotated(n, theta);
      length_bar[ac] += internal::dot(Z, w);
      theta_bar[f][a] += lengths_[ac] * internal::dot(Z, {-w[1], w[0]});
      const internal::Point2 n_bar = internal::rotated({lengths_[ac] * Z[0], lengths_[ac] * Z[1]}, -theta);
      const double along = internal::dot(n_bar, n);
      const internal::Point2 d_bar = {(n_bar[0] - along * n[0]) / norm, (n_bar[1] - along * n[1]) / norm};
      add(v[a], Z[0] - d_bar[0], Z[1] - d_bar[1]);
      add(v[b], d_bar[0], d_bar[1]);
    }
    const std::array<int, 3>& r = wedges_[placements_.front().face];
    length_bar[root_edge_] += zbar[r[1]][0]; // z_r1 = (l_root, 0)

    const Metric& metric = curvature_->metric();
    for(int e = 0; e < t.number_of_edges(); ++e)
      if(length_bar[e] != 0.0)
      {
        const int i = t.edges[e][0], j = t.edges[e][1];
        const std::array<double, 2> d = internal::log_length_derivatives(metric, e, radii_[i], radii_[j]);
        gradient[i] += length_bar[e] * lengths_[e] * d[0];
        gradient[j] += length_bar[e] * lengths_[e] * d[1];
      }
    for(int f = 0; f < t.number_of_faces(); ++f)
      add_angle_chain(t.faces[f], geometry_[f].weight, theta_bar[f], gradient);
  }

  const internal::Mesh_index& mesh_;
  std::vector<double> mesh_area_;
  std::vector<std::array<double, 3>> mesh_angle_;
  double mesh_total_area_ = 0;

  Curvature_map<Metric>* curvature_ = nullptr;
  Eigen::VectorXd u_, u0_, radii_, k_;
  std::vector<double> lengths_, weights_;
  std::vector<Face_geometry> geometry_; // per face of the triangulation
  int invalid_faces_ = 0;
  std::vector<double> area_;                  // raw, per mesh face
  std::vector<std::array<double, 3>> angle_;  // per mesh face corner (metric faces only)
  double area_scale_ = 1;
  std::vector<internal::Point2> z_;           // developed wedges
  mutable std::vector<std::array<double, 3>> developed_angle_; // per mesh face corner, when asked
  mutable bool developed_angles_current_ = false;
  // The cut of the development: the seams, each vertex's seam degree, the wedges of the mesh's
  // and of the triangulation's corners (vertex ids off the seams), and the wedge of each key.
  std::vector<char> seams_;
  std::vector<int> seam_degree_;
  std::vector<std::array<int, 3>> mesh_wedges_, wedges_;
  std::vector<std::pair<long long, int>> wedge_of_key_;
  int number_of_wedges_ = 0;
  std::vector<Placement> placements_; // the root's third vertex first
  long placements_version_ = -1;      // the triangulation version they were found for
  int root_edge_ = -1;
  // Scratch of gradient_u.
  mutable std::vector<double> raw_area_partial_;
  mutable std::vector<internal::Point2> z_partial_;
  mutable std::vector<std::array<double, 3>> angle_partial_;
  mutable std::vector<double> length_partial_;
};

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
                                std::declval<const State&>(), std::declval<Eigen::VectorXd&>()))>>
  : std::true_type
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
