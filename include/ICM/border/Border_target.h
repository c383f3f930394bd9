// What a border condition asks of one indexed mesh (`Border_target`), and the checks every
// condition shares: discrete Gauss-Bonnet of a prescribed curvature, the loops of the border.

#ifndef ICM_BORDER_BORDER_TARGET_H
#define ICM_BORDER_BORDER_TARGET_H

#include <ICM/Status.h>
#include <ICM/curvature/Curvature_map.h>
#include <ICM/internal/Mesh_index.h>

#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <boost/graph/graph_traits.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace ICM {

/// What a border condition asks of the border, in curvature space.
enum class Border_kind
{
  Free,                 ///< left to the entropy optimum (u = u0 on the border)
  Prescribed_curvature, ///< a given turning angle per border vertex
  Circles               ///< every loop a circle (outer loop around the domain)
};

/// A border condition applied to one indexed mesh: what `Inverse_curvature_map_parameterizer_3`
/// solves for. `status` is not `OK` when the condition cannot hold on this mesh, and says
/// why.
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
  Status status;

  bool ok() const { return status.ok(); }
  bool prescribes_border() const { return kind != Border_kind::Free; }
};

namespace internal {

inline Border_target refused(const std::string& why)
{
  Border_target t;
  t.status = Status::wrong_parameter(why);
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
  if(!meets_gauss_bonnet(defect, border_vertices))
    return refused(what + " violates Gauss-Bonnet: its sum is " + std::to_string(t.curvature.sum()) +
                   ", not 2 pi chi = " + std::to_string(2 * M_PI * index.euler_characteristic()) +
                   " (chi = " + std::to_string(index.euler_characteristic()) + ")");
  return t;
}

/// The loop of `Mesh_index::boundary_loops` through vertex `v`, or -1.
inline int loop_of_vertex(const Mesh_index& index, int v)
{
  for(int l = 0; l < index.number_of_boundary_loops(); ++l)
    if(std::find(index.boundary_loops[l].begin(), index.boundary_loops[l].end(), v) != index.boundary_loops[l].end())
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

} // namespace internal

} // namespace ICM

#endif // ICM_BORDER_BORDER_TARGET_H
