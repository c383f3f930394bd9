// Step 2: the curvature map K(u) and its Jacobian, the dynamic Laplacian (paper eq. 1 and 3).
//
// One pass over the faces gives edge lengths, corner angles, vertex curvatures and the edge
// weights w_ij = d theta_i / d u_j summed over the faces at ij (the paper's h_ij / l_ij).
// A metric (the `Metric` concept, doc/concepts.md) provides `length(e, gi, gj)` and
// `face_geometry(edges, radii, lengths)`, the face's angles, weights and validity, because
// only the metric knows how to compute them without cancellation when the radii of one face
// differ by many orders of magnitude.
//
// A metric may own its triangulation (`Intrinsic_delaunay_metric`): it then provides
// `triangulation()` and `make_delaunay(g)`, the curvature map flips it at every u before
// measuring, and `mesh_index()` is that triangulation instead of the mesh's.

#ifndef ICM_CURVATURE_CURVATURE_MAP_H
#define ICM_CURVATURE_CURVATURE_MAP_H

#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Triangle_geometry.h>

#include <Eigen/Core>

#include <array>
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>
#include <vector>

namespace ICM {
namespace internal {

/// Whether a metric owns a triangulation that it flips with u (see the header comment).
template <class Metric, class = void>
struct Has_intrinsic_triangulation : std::false_type
{};
template <class Metric>
struct Has_intrinsic_triangulation<
  Metric, std::void_t<decltype(std::declval<Metric&>().make_delaunay(std::declval<const std::vector<double>&>()))>>
  : std::true_type
{};

} // namespace internal

/// Evaluates K(u) and the dynamic Laplacian weights for a metric. Holds its own copy of the
/// metric (whose triangulation may change with u) and per-edge length storage, so repeated
/// evaluations allocate nothing.
///
/// \tparam Metric a model of \ref ::Metric "Metric"
template <class Metric = Circle_packing_metric>
class Curvature_map
{
public:
  Curvature_map(const internal::Mesh_index& index, const Metric& metric)
    : index_(index), metric_(metric), radii_(index.number_of_vertices()), lengths_(index.number_of_edges())
  {}

  static constexpr bool has_intrinsic_triangulation = internal::Has_intrinsic_triangulation<Metric>::value;

  /// The triangulation the metric lives on: the mesh's, or the metric's own as of the last
  /// `evaluate` or `compute_lengths`.
  const internal::Mesh_index& mesh_index() const
  {
    if constexpr(has_intrinsic_triangulation)
      return metric_.triangulation();
    else
      return index_;
  }
  /// Changes whenever `mesh_index()` changes its edges (always 0 for a fixed triangulation).
  long triangulation_version() const
  {
    if constexpr(has_intrinsic_triangulation)
      return metric_.flips();
    else
      return 0;
  }
  const Metric& metric() const { return metric_; }
  /// The metric's own copy, e.g. to freeze its triangulation (`Intrinsic_delaunay_metric`).
  Metric& metric() { return metric_; }

  /// Edge lengths of the metric at `u` (flipping its triangulation first if it has one);
  /// also kept for `lengths()`.
  const std::vector<double>& compute_lengths(const Eigen::VectorXd& u)
  {
    for(int v = 0; v < index_.number_of_vertices(); ++v)
      radii_[v] = std::exp(u[v]);
    if constexpr(has_intrinsic_triangulation)
      metric_.make_delaunay(radii_);
    const internal::Mesh_index& t = mesh_index();
    for(int e = 0; e < t.number_of_edges(); ++e)
      lengths_[e] = metric_.length(e, radii_[t.edges[e][0]], radii_[t.edges[e][1]]);
    return lengths_;
  }
  const std::vector<double>& lengths() const { return lengths_; }

  /// Curvature k at `u`: 2 pi - angle sum inside, pi - angle sum on the border.
  /// When `weights` is given, also the per-edge Laplacian weights w_e (one per edge).
  /// Returns the number of faces whose lengths at `u` are not a triangle (always 0 for the
  /// circle packing); k is then meaningless.
  int evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& k, std::vector<double>* weights = nullptr)
  {
    int invalid_faces = 0;
    compute_lengths(u);
    const internal::Mesh_index& t = mesh_index();
    const int nv = t.number_of_vertices();
    k.resize(nv);
    for(int v = 0; v < nv; ++v)
      k[v] = t.is_boundary_vertex[v] ? M_PI : 2.0 * M_PI;
    if(weights)
      weights->assign(t.number_of_edges(), 0.0);

    for(int f = 0; f < t.number_of_faces(); ++f)
    {
      const std::array<int, 3>& e = t.face_edges[f];
      const Face_geometry face = face_geometry(f);
      invalid_faces += !face.valid;
      for(int c = 0; c < 3; ++c)
        k[t.faces[f][c]] -= face.angles.angle[c];
      if(weights)
        for(int c = 0; c < 3; ++c)
          (*weights)[e[c]] += face.weight[c];
    }
    return invalid_faces;
  }

  /// Corner angles of every face at the u of the last `evaluate` or `compute_lengths`.
  std::vector<Triangle_angles> face_angles() const
  {
    std::vector<Triangle_angles> angles(index_.number_of_faces());
    for(int f = 0; f < index_.number_of_faces(); ++f)
      angles[f] = face_geometry(f).angles;
    return angles;
  }

  /// Angles and Laplacian weights of face f at the u of the last `evaluate` or
  /// `compute_lengths`.
  Face_geometry face_geometry(int f) const
  {
    const std::array<int, 3>& v = mesh_index().faces[f];
    const std::array<int, 3>& e = mesh_index().face_edges[f];
    return metric_.face_geometry(e, {radii_[v[0]], radii_[v[1]], radii_[v[2]]},
                                 {lengths_[e[0]], lengths_[e[1]], lengths_[e[2]]});
  }

private:
  const internal::Mesh_index& index_;
  Metric metric_;
  std::vector<double> radii_;
  std::vector<double> lengths_;
};

/// Sum of k_i over all vertices minus 2 pi chi: zero for any metric (discrete Gauss-Bonnet).
inline double gauss_bonnet_defect(const internal::Mesh_index& index, const Eigen::VectorXd& k)
{
  return k.sum() - 2.0 * M_PI * index.euler_characteristic();
}

/// Whether a sum of `values` given curvatures misses 2 pi chi by no more than their rounding:
/// each value may carry its own, so the tolerance grows with their number. The one
/// Gauss-Bonnet test of every prescribed curvature (a border's, Algorithm 1's target, the
/// user's cones).
inline bool meets_gauss_bonnet(double defect, int values)
{
  constexpr double tolerance_per_value = 1e-9;
  return std::abs(defect) <= tolerance_per_value * std::max(1, values);
}

} // namespace ICM

#endif // ICM_CURVATURE_CURVATURE_MAP_H
