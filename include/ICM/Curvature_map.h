// Step 2: the curvature map K(u) and its Jacobian, the dynamic Laplacian (paper eq. 1 and 3).
//
// One pass over the faces gives edge lengths, corner angles, vertex curvatures and the edge
// weights w_ij = d theta_i / d u_j summed over the faces at ij. The weights come from the
// chain rule (angle/length derivatives of the law of cosines times length/radius
// derivatives of the metric), which equals the paper's h_ij / l_ij and works for any metric
// policy that provides `length` and `length_derivative`.

#ifndef ICM_CURVATURE_MAP_H
#define ICM_CURVATURE_MAP_H

#include <ICM/Circle_packing_metric.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <vector>

namespace ICM {

/// Angles and area of a triangle from its side lengths; `l[c]` is opposite corner `c`.
struct Triangle_angles
{
  std::array<double, 3> angle;
  std::array<double, 3> cosine;
  double area;
};

/// Heron's formula in product form and atan2 for the angles: accurate for thin triangles,
/// where acos of the law of cosines loses half the digits.
inline Triangle_angles triangle_angles(const std::array<double, 3>& l)
{
  const double a = l[0], b = l[1], c = l[2];
  const double p = (a + b + c) * (-a + b + c) * (a - b + c) * (a + b - c);
  Triangle_angles t;
  t.area = 0.25 * std::sqrt(std::max(p, 0.0));
  const double four_area = 4.0 * t.area;
  for(int i = 0; i < 3; ++i)
  {
    const double li = l[i], lj = l[(i + 1) % 3], lk = l[(i + 2) % 3];
    const double twice_cos_times = lj * lj + lk * lk - li * li; // 2 lj lk cos(theta_i)
    t.angle[i] = std::atan2(four_area, twice_cos_times);
    t.cosine[i] = twice_cos_times / (2.0 * lj * lk);
  }
  return t;
}

/// Evaluates K(u) and the dynamic Laplacian weights on a fixed mesh and metric.
/// Holds per-edge length storage so repeated evaluations allocate nothing.
template <class Metric = Circle_packing_metric>
class Curvature_map
{
public:
  Curvature_map(const internal::Mesh_index& index, const Metric& metric)
    : index_(index), metric_(metric), radii_(index.number_of_vertices()),
      lengths_(index.number_of_edges())
  {}

  const internal::Mesh_index& mesh_index() const { return index_; }
  const Metric& metric() const { return metric_; }

  /// Edge lengths of the metric at `u`; also kept for `lengths()`.
  const std::vector<double>& compute_lengths(const Eigen::VectorXd& u)
  {
    for(int v = 0; v < index_.number_of_vertices(); ++v)
      radii_[v] = std::exp(u[v]);
    for(int e = 0; e < index_.number_of_edges(); ++e)
      lengths_[e] = metric_.length(e, radii_[index_.edges[e][0]], radii_[index_.edges[e][1]]);
    return lengths_;
  }
  const std::vector<double>& lengths() const { return lengths_; }

  /// Curvature k at `u`: 2 pi - angle sum inside, pi - angle sum on the border.
  /// When `weights` is given, also the per-edge Laplacian weights w_e (size #edges).
  void evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& k, std::vector<double>* weights = nullptr)
  {
    compute_lengths(u);
    const int nv = index_.number_of_vertices();
    k.resize(nv);
    for(int v = 0; v < nv; ++v)
      k[v] = index_.is_boundary_vertex[v] ? M_PI : 2.0 * M_PI;
    if(weights)
      weights->assign(index_.number_of_edges(), 0.0);

    for(int f = 0; f < index_.number_of_faces(); ++f)
    {
      const std::array<int, 3>& e = index_.face_edges[f];
      const Triangle_angles t = triangle_angles({lengths_[e[0]], lengths_[e[1]], lengths_[e[2]]});
      for(int c = 0; c < 3; ++c)
        k[index_.faces[f][c]] -= t.angle[c];
      if(weights)
        for(int c = 0; c < 3; ++c)
          (*weights)[e[c]] += face_weight(f, c, t);
    }
  }

  /// d theta_a / d u_b in face f for the edge ab opposite corner c (a = c+1, b = c+2).
  /// Law of cosines: d theta_a/d l_a = l_a/(2A), d theta_a/d l_c = -l_a cos(theta_b)/(2A);
  /// theta_a depends on u_b through l_a (edge bc) and l_c (edge ab).
  /// Uses the radii and lengths of the last `compute_lengths`.
  double face_weight(int f, int c, const Triangle_angles& t) const
  {
    const int ca = (c + 1) % 3, cb = (c + 2) % 3;
    const std::array<int, 3>& v = index_.faces[f];
    const std::array<int, 3>& e = index_.face_edges[f];
    const double la = lengths_[e[ca]], lc = lengths_[e[c]];
    const double dla_dub = metric_.length_derivative(e[ca], radii_[v[cb]], radii_[v[c]], la);
    const double dlc_dub = metric_.length_derivative(e[c], radii_[v[cb]], radii_[v[ca]], lc);
    return la * (dla_dub - t.cosine[cb] * dlc_dub) / (2.0 * t.area);
  }

private:
  const internal::Mesh_index& index_;
  const Metric& metric_;
  std::vector<double> radii_;
  std::vector<double> lengths_;
};

/// Sum of k_i over all vertices minus 2 pi chi: zero for any metric (discrete Gauss-Bonnet).
inline double gauss_bonnet_defect(const internal::Mesh_index& index, const Eigen::VectorXd& k)
{
  return k.sum() - 2.0 * M_PI * index.euler_characteristic();
}

} // namespace ICM

#endif // ICM_CURVATURE_MAP_H
