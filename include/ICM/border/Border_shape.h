// `Border_shape`: the border condition of the polygon a CGAL border parameterizer draws (a
// square gives a rectangle, a circle the conformal map to the disk), and its two common
// forms `Square_border` and `Circular_border` (which need CGAL's
// Square_border_parameterizer_3.h and Circular_border_parameterizer_3.h included).

#ifndef ICM_BORDER_BORDER_SHAPE_H
#define ICM_BORDER_BORDER_SHAPE_H

#include <ICM/border/Border_target.h>
#include <ICM/internal/Mesh_index.h>

#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/internal/kernel_traits.h>

#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

// CGAL's border parameterizers, declared: a user who passes one has included its header, and
// telling a circle from a square needs only the names of their bases.
namespace CGAL {
namespace Surface_mesh_parameterization {
template <class TriangleMesh_>
class Circular_border_parameterizer_3;
template <class TriangleMesh_>
class Circular_border_arc_length_parameterizer_3;
template <class TriangleMesh_>
class Square_border_parameterizer_3;
template <class TriangleMesh_>
class Square_border_arc_length_parameterizer_3;
template <class TriangleMesh_>
class Two_vertices_parameterizer_3;
} // namespace Surface_mesh_parameterization
} // namespace CGAL

namespace ICM {

namespace internal {

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

} // namespace internal

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
///
/// \cgalModels{\ref BorderCondition}
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
  Border_target
  polygon_target(const TriangleMesh& mesh, typename boost::graph_traits<TriangleMesh>::halfedge_descriptor bhd,
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
      Border_target t;
      t.status = Status::failure(status, std::string("the border parameterizer failed: ") +
                                           CGAL::Surface_mesh_parameterization::get_error_message(status));
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
///
/// \cgalModels{\ref BorderCondition}
template <class TriangleMesh>
using Square_border =
  Border_shape<CGAL::Surface_mesh_parameterization::Square_border_arc_length_parameterizer_3<TriangleMesh>>;
/// `Border_shape` with CGAL's arc-length circular border: the disk.
///
/// \cgalModels{\ref BorderCondition}
template <class TriangleMesh>
using Circular_border =
  Border_shape<CGAL::Surface_mesh_parameterization::Circular_border_arc_length_parameterizer_3<TriangleMesh>>;

} // namespace ICM

#endif // ICM_BORDER_BORDER_SHAPE_H
