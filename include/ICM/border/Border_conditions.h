// Border conditions of `Inverse_curvature_map_parameterizer_3`, as one notion in curvature
// space: every condition says what the curvature of the border is; the interior is always
// flat (doc/border_conditions.md).
//  - `Free_border`: the border curvature is left to the optimum of the curvature entropy
//    (u = u0 on the border, the paper's Thm 3.5).
//  - `Prescribed_border_curvature`: the user gives the turning angle k_i of every border
//    vertex; the metric is u = K^{-1}(k) (Algorithm 1, one vertex pinned for the scale). The
//    admissible space is then a single point.
//  - `Circle_domain`: every border loop a circle (paper Fig. 8), the outer one around the
//    domain, the others holes in it; genus 0 with any number of loops, laid out without cut.
//  - `Border_shape<BorderParameterizer>` (border/Border_shape.h): the turning angles of the polygon a CGAL border parameterizer
//    draws, so a square gives a rectangle, a circle the conformal map to the disk.
// What a condition asks of one mesh is a `Border_target` (border/Border_target.h); the
// metric that meets it is solved in border/Border_solve.h.

#ifndef ICM_BORDER_BORDER_CONDITIONS_H
#define ICM_BORDER_BORDER_CONDITIONS_H

#include <ICM/border/Border_target.h>
#include <ICM/internal/Mesh_index.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace ICM {

/// \brief The free boundary (default): every border vertex singular, the border curvature
/// the optimum of the curvature entropy (paper Thm 3.5), or of the parameterizer's `Energy`.
///
/// \cgalModels{\ref BorderCondition (the default)}
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
///
/// \cgalModels{\ref BorderCondition}
template <class VertexCurvatureMap>
class Prescribed_border_curvature
{
public:
  explicit Prescribed_border_curvature(VertexCurvatureMap curvature = VertexCurvatureMap()) : curvature_(curvature) {}

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

namespace internal {

/// A face whose three corners lie on one hole's loop has them on that loop's circle, where
/// the triangle lies inside the circle, in the hole and not in the domain: no layout of the
/// condition has it unflipped. Such a face (an ear of the hole, or one across it) is refused
/// by name before any solve; the outer loop's are inside the domain, as they should be.
inline Border_target refuse_faces_inside_a_hole(const Mesh_index& index, Border_target t)
{
  std::vector<int> loop_of(index.number_of_vertices(), -1);
  for(int l = 0; l < index.number_of_boundary_loops(); ++l)
    for(int v : index.boundary_loops[l])
      loop_of[v] = l;
  int count = 0, first = -1;
  for(int f = 0; f < index.number_of_faces(); ++f)
  {
    const std::array<int, 3>& c = index.faces[f];
    const int l = loop_of[c[0]];
    if(l >= 0 && l != t.outer_loop && loop_of[c[1]] == l && loop_of[c[2]] == l)
    {
      first = first < 0 ? f : first;
      ++count;
    }
  }
  if(count == 0)
    return t;
  t.status =
    Status::failure(CGAL::Surface_mesh_parameterization::ERROR_NO_1_TO_1_MAPPING,
                    std::to_string(count) +
                      " face(s) have all three corners on one hole's border (the first "
                      "is face " +
                      std::to_string(first) + ", on border loop " + std::to_string(loop_of[index.faces[first][0]]) +
                      "): on that loop's circle they "
                      "would lie inside the hole, flipped; split them, or choose another border condition");
  return t;
}

} // namespace internal

/// \brief A genus-0 mesh with any number of border loops, mapped without a cut onto a circle
/// domain (paper Fig. 8): the outer loop a circle with the domain inside, every other loop a
/// circle with the domain outside, the interior flat.
///
/// The condition is the exact one of inscribed polygons for any metric (header comment);
/// the metric is the fixed point of u <- K^{-1}(T(u)), Anderson-accelerated.
/// The outer loop is the longest in 3D (`Outer_loop::Longest`, default), or the loop of the
/// border halfedge given to `parameterize()` (`Outer_loop::Of_border_halfedge`).
///
/// \cgalModels{\ref BorderCondition}
class Circle_domain
{
public:
  enum class Outer_loop
  {
    Longest,           ///< the loop of largest 3D length
    Of_border_halfedge ///< the loop of the halfedge passed to `parameterize()`
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
    return internal::refuse_faces_inside_a_hole(index, std::move(t));
  }

private:
  Outer_loop outer_;
  int max_iterations_, anderson_depth_;
};

} // namespace ICM

#endif // ICM_BORDER_BORDER_CONDITIONS_H
