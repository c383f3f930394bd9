// What an energy reads (`Energy_state`), and the chain rule that turns an energy's partial
// derivatives into its gradient in u (optimum/Energies.h has the `Energy` concept).
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

#ifndef ICM_OPTIMUM_ENERGY_STATE_H
#define ICM_OPTIMUM_ENERGY_STATE_H

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
  Metric, std::void_t<decltype(std::declval<const Metric&>().log_length_derivatives(0, 1.0, 1.0))>> : std::true_type
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

/// Whether a metric keeps some edges of its own triangulation fixed (`m.fixed_edges()`, the
/// seams): a development of it is cut along them.
template <class Metric, class = void>
struct Has_fixed_edges : std::false_type
{};
template <class Metric>
struct Has_fixed_edges<Metric, std::void_t<decltype(std::declval<const Metric&>().fixed_edges())>> : std::true_type
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

inline Uv rotated(const Uv& d, double angle)
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
///
/// \tparam Metric a model of \ref ::Metric "Metric"
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
      // good part of an update, and only the angle energies read them.
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
        const std::array<double, 2> d = internal::log_length_derivatives(metric, e[c], radii_[v[a]], radii_[v[b]]);
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

  /// Places every wedge by unfolding the triangulation from its central face (`unfold`, as
  /// the layout does), so that the development is a smooth function of the metric's lengths
  /// and angles almost everywhere.
  void measure_developed_faces(const internal::Mesh_index& t)
  {
    if(mesh_wedges_.empty())
      cut_along_seams(internal::development_seams(curvature_->metric(), t.number_of_edges()));
    z_.assign(number_of_wedges_, {0.0, 0.0});
    // The order found for this triangulation is kept until the metric flips an edge: it
    // costs three quarters of the development, and a fixed order keeps the development one
    // smooth function of the lengths and angles between flips.
    auto angle = [this](int f, int c) { return geometry_[f].angles.angle[c]; };
    if(!placements_.empty() && placements_version_ == curvature_->triangulation_version())
    {
      z_[wedges_[placements_.front().face][1]] = {lengths_[root_edge_], 0.0};
      for(const Unfolding_step& p : placements_)
        place_corner(wedges_[p.face], p.corner, lengths_[t.face_edges[p.face][(p.corner + 2) % 3]],
                     angle(p.face, (p.corner + 1) % 3), z_);
    }
    else
    {
      placements_version_ = curvature_->triangulation_version();
      find_triangulation_wedges(t);
      const int root = central_face(t);
      root_edge_ = t.face_edges[root][2];
      placements_ = unfold(wedges_, t.face_edges, lengths_, angle, root, z_);
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

  void measure_developed_mesh_faces()
  {
    const int nf = mesh_.number_of_faces();
    area_.resize(nf);
    double total = 0;
    for(int f = 0; f < nf; ++f)
    {
      const std::array<int, 3>& v = mesh_wedges_[f];
      area_[f] = 0.5 * internal::twice_signed_area(z_[v[0]], z_[v[1]], z_[v[2]]);
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
        const Uv a = internal::difference(z_[v[(c + 1) % 3]], z_[v[c]]);
        const Uv b = internal::difference(z_[v[(c + 2) % 3]], z_[v[c]]);
        developed_angle_[f][c] = std::atan2(internal::cross(a, b), internal::dot(a, b));
      }
    }
    developed_angles_current_ = true;
  }

  /// Reverse mode through the development: the partials of the mesh faces' areas and angles
  /// with respect to the placed points, back through every placement to the triangulation's
  /// lengths and angles, and from them to u by the metric's length derivatives and Jacobian
  /// weights.
  void chain_through_development(const Energy_gradient& partials, Eigen::VectorXd& gradient) const
  {
    const internal::Mesh_index& t = triangulation();
    std::vector<Uv>& zbar = z_partial_;
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
        const Uv &zj = z_[v[(c + 1) % 3]], &zk = z_[v[(c + 2) % 3]];
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
        const Uv a = internal::difference(z_[j], z_[i]), b = internal::difference(z_[k], z_[i]);
        const double aa = internal::dot(a, a), bb = internal::dot(b, b);
        const Uv da = {p * a[1] / aa, -p * a[0] / aa}, db = {-p * b[1] / bb, p * b[0] / bb};
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
      const Uv Z = zbar[v[c]];
      const Uv d = internal::difference(z_[v[b]], z_[v[a]]);
      const double norm = std::hypot(d[0], d[1]);
      const Uv n = {d[0] / norm, d[1] / norm};
      const Uv w = internal::rotated(n, theta);
      length_bar[ac] += internal::dot(Z, w);
      theta_bar[f][a] += lengths_[ac] * internal::dot(Z, {-w[1], w[0]});
      const Uv n_bar = internal::rotated({lengths_[ac] * Z[0], lengths_[ac] * Z[1]}, -theta);
      const double along = internal::dot(n_bar, n);
      const Uv d_bar = {(n_bar[0] - along * n[0]) / norm, (n_bar[1] - along * n[1]) / norm};
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
  std::vector<double> area_;                 // raw, per mesh face
  std::vector<std::array<double, 3>> angle_; // per mesh face corner (metric faces only)
  double area_scale_ = 1;
  std::vector<Uv> z_;                                          // developed wedges
  mutable std::vector<std::array<double, 3>> developed_angle_; // per mesh face corner, when asked
  mutable bool developed_angles_current_ = false;
  // The cut of the development: the seams, each vertex's seam degree, the wedges of the mesh's
  // and of the triangulation's corners (vertex ids off the seams), and the wedge of each key.
  std::vector<char> seams_;
  std::vector<int> seam_degree_;
  std::vector<std::array<int, 3>> mesh_wedges_, wedges_;
  std::vector<std::pair<long long, int>> wedge_of_key_;
  int number_of_wedges_ = 0;
  std::vector<Unfolding_step> placements_; // the root's third vertex first
  long placements_version_ = -1;           // the triangulation version they were found for
  int root_edge_ = -1;
  // Scratch of gradient_u.
  mutable std::vector<double> raw_area_partial_;
  mutable std::vector<Uv> z_partial_;
  mutable std::vector<std::array<double, 3>> angle_partial_;
  mutable std::vector<double> length_partial_;
};

} // namespace ICM

#endif // ICM_OPTIMUM_ENERGY_STATE_H
