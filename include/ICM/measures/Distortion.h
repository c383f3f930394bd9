// Distortion measures of a surface parameterization (paper Table I).
//
// A diagnostic: it reads a triangle mesh and its UVs and reports how far the piecewise linear
// map from each 3D triangle to its UV triangle is from an isometry / a similarity. It is never
// called inside parameterize(), so bad input is reported by exceptions (std::invalid_argument).
//
// Conventions (full formulas and sources in doc/distortion.md):
//  * Before measuring, the UVs are mirrored (v -> -v) when their total signed area is negative
//    (a layout reflected as a whole is not "flipped"), then scaled uniformly so that the total
//    |UV area| equals the total 3D area. Every figure is therefore invariant under similarities
//    and reflections of the whole layout.
//  * Per face, J is the 2x2 Jacobian of the affine map from an isometric 2D frame of the 3D
//    triangle (oriented by its corner order) to the normalised UV triangle; sigma1 >= |sigma2|
//    are its singular values, sigma2 carrying the sign of det J (det J < 0: flipped face).
//    A_f is the 3D area, s_f the normalised UV area, det J = s_f(signed) / A_f.
//  * degenerate_3d_faces: A_f <= 1e-14 * mean 3D face area. No map exists: excluded everywhere.
//    degenerate_uv_faces: |s_f| <= 1e-14 * mean 3D face area. Excluded from the measures that
//    divide by sigma2 or s_f (shear, stretch, log area, area ratios, qc), kept in conformality
//    and angle distortion, where they are finite. flipped_faces: non-degenerate with s_f < 0.
//
//   conformality        = sum_f A_f (sigma1 - sigma2)^2 / 2 / sum_f A_f         (Levy 2002)
//   angle_distortion    = mean over corners of (theta_uv - theta_3d)^2, radians^2
//   l2_shear            = sqrt( sum_f A_f (s1/s2 + s2/s1 - 2) / sum_f A_f ),  s = |sigma|
//   l2_stretch          = sqrt( sum_f A_f (1/s1^2 + 1/s2^2) / 2 / sum_f A_f )  (Sander 2001)
//   log_area_distortion = mean_f log^2(|s_f| / A_f)         (paper eq. 8 divided by #faces)
//   log_area_distortion_area_weighted = sum_f A_f log^2(|s_f| / A_f) / sum_f A_f
//                         (the integral over the surface: BFF's and CEPS's papers report it)
//   area_ratio_min/max  = min/max of |s_f| / A_f
//   qc_mean / qc_max    = area-weighted mean / max of s1/s2
#ifndef ICM_MEASURES_DISTORTION_H
#define ICM_MEASURES_DISTORTION_H

#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Unit_frame.h>
#include <ICM/internal/Vector_geometry.h>

#include <CGAL/boost/graph/properties.h>
#include <CGAL/number_utils.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace ICM {

/// The figures of paper Table I plus counts; see the file comment and doc/distortion.md.
struct Distortion_measures
{
  std::size_t faces = 0;               ///< all faces read
  std::size_t flipped_faces = 0;       ///< normalised UV orientation opposite to the 3D one
  std::size_t degenerate_uv_faces = 0; ///< UV area (near) zero
  std::size_t degenerate_3d_faces = 0; ///< 3D area (near) zero: no map, excluded everywhere
  double conformality = 0;
  double angle_distortion = 0;
  double l2_shear = 0;
  double l2_stretch = 0;
  double log_area_distortion = 0;
  double log_area_distortion_area_weighted = 0;
  double qc_mean = 0;
  double qc_max = 0;
  double area_ratio_min = 0;
  double area_ratio_max = 0;
};

namespace internal {
namespace distortion {

/// Relative size (to the mean 3D face area) under which an area counts as zero.
constexpr double degenerate_area_factor = 1e-14;

/// Neumaier's compensated sum: the sums run over up to millions of faces of very different
/// sizes, and the figures are compared across methods to several digits.
class Compensated_sum
{
public:
  void add(double x)
  {
    const double t = sum_ + x;
    compensation_ += (std::abs(sum_) >= std::abs(x)) ? (sum_ - t) + x : (x - t) + sum_;
    sum_ = t;
  }
  double value() const { return sum_ + compensation_; }

private:
  double sum_ = 0, compensation_ = 0;
};

/// Angle between two vectors by atan2(|a x b|, a.b): accurate near 0 and pi, unlike acos.
inline double angle_between(const Point3& a, const Point3& b)
{
  return std::atan2(cross_norm(a, b), dot(a, b));
}
inline double angle_between(const Uv& a, const Uv& b)
{
  return std::atan2(std::abs(cross(a, b)), dot(a, b));
}

template <class Point>
std::array<double, 3> corner_angles(const Point& p0, const Point& p1, const Point& p2)
{
  return {angle_between(difference(p1, p0), difference(p2, p0)), angle_between(difference(p2, p1), difference(p0, p1)),
          angle_between(difference(p0, p2), difference(p1, p2))};
}

/// The uniform map applied to every UV before measuring: v -> mirror * v, then * scale.
struct Uv_normalisation
{
  double mirror = 1;
  double scale = 1;
  double total_3d_area = 0;
  double degenerate_area = 0; ///< areas at or below this count as zero

  Uv apply_to_vector(const Uv& d) const { return {scale * d[0], scale * mirror * d[1]}; }
  double apply_to_area(double signed_area) const { return scale * scale * mirror * signed_area; }
};

inline void require_finite(const double* first, std::size_t count, const char* what)
{
  for(std::size_t i = 0; i < count; ++i)
    if(!std::isfinite(first[i]))
      throw std::invalid_argument(std::string("ICM::measure_distortion: non-finite ") + what + " coordinate");
}

/// Copies of `points` in their `Unit_frame` (centred, half the longest side of their box is
/// 1). Every measure is invariant under it, and areas of a mesh (or a layout) at 1e-300 or
/// 1e+300 then neither underflow nor overflow. \pre every coordinate is finite.
template <std::size_t N>
std::vector<std::array<double, N>> to_unit_size(const std::vector<std::array<double, N>>& points)
{
  const Unit_frame<N> frame = unit_frame_of<N>(points);
  std::vector<std::array<double, N>> out(points.size());
  for(std::size_t i = 0; i < points.size(); ++i)
    out[i] = frame.apply(points[i]);
  return out;
}

inline Uv_normalisation uv_normalisation(const std::vector<Point3>& xyz, const std::vector<Uv>& uv)
{
  Compensated_sum area_3d, signed_area_uv, abs_area_uv;
  for(std::size_t c = 0; c < xyz.size(); c += 3)
  {
    require_finite(xyz[c].data(), 9, "3D");
    require_finite(uv[c].data(), 6, "UV");
    area_3d.add(triangle_area(xyz[c], xyz[c + 1], xyz[c + 2]));
    const double s = 0.5 * internal::twice_signed_area(uv[c], uv[c + 1], uv[c + 2]);
    signed_area_uv.add(s);
    abs_area_uv.add(std::abs(s));
  }
  Uv_normalisation n;
  n.total_3d_area = area_3d.value();
  n.mirror = signed_area_uv.value() < 0 ? -1.0 : 1.0;
  if(abs_area_uv.value() > 0 && n.total_3d_area > 0)
    n.scale = std::sqrt(n.total_3d_area / abs_area_uv.value());
  const double face_count = static_cast<double>(xyz.size() / 3);
  n.degenerate_area = face_count > 0 ? degenerate_area_factor * n.total_3d_area / face_count : 0;
  return n;
}

/// J = [[a, b], [c, d]] and the rotation-invariant split of it used by every measure:
/// J = conformal part + anti-conformal part, with Q = |conformal|, R = |anti-conformal|, so that
/// sigma1 = Q + R and signed sigma2 = Q - R, without forming sigma2 by cancellation.
struct Face_jacobian
{
  double a = 0, b = 0, c = 0, d = 0;
  double area_3d = 0;     ///< A_f
  double signed_area = 0; ///< s_f, normalised UV area, signed
  double determinant() const { return signed_area / area_3d; }
  double conformal_norm() const { return 0.5 * std::hypot(a + d, c - b); }     // Q
  double anticonformal_norm() const { return 0.5 * std::hypot(a - d, c + b); } // R
};

/// The frame: origin p0, x axis along p0p1, y axis in the face plane so that p2 has y > 0;
/// it is an isometry of the 3D triangle, oriented by the corner order.
inline Face_jacobian face_jacobian(const Point3& p0, const Point3& p1, const Point3& p2, const Uv& du1, const Uv& du2,
                                   double signed_uv_area)
{
  const Point3 e1 = difference(p1, p0), e2 = difference(p2, p0);
  const double length1 = std::sqrt(dot(e1, e1));
  const double twice_area = cross_norm(e1, e2);
  const double x2 = dot(e1, e2) / length1;
  const double y2 = twice_area / length1;
  // J * [length1 x2; 0 y2] = [du1 du2]: solve the upper triangular system column by column.
  const Uv column1 = {du1[0] / length1, du1[1] / length1};
  const Uv column2 = {(du2[0] - x2 * column1[0]) / y2, (du2[1] - x2 * column1[1]) / y2};
  Face_jacobian j;
  j.a = column1[0];
  j.b = column2[0];
  j.c = column1[1];
  j.d = column2[1];
  j.area_3d = 0.5 * twice_area;
  j.signed_area = signed_uv_area;
  return j;
}

/// Running sums of every measure; one add() per face, finish() once.
class Distortion_accumulator
{
public:
  void add_degenerate_3d_face() { ++result_.degenerate_3d_faces; }

  /// Terms finite on every face with a map: conformality and angles.
  void add_conformal_terms(const Face_jacobian& j, const std::array<double, 3>& angles_3d,
                           const std::array<double, 3>& angles_uv)
  {
    const double r = j.anticonformal_norm();
    // (sigma1 - sigma2)^2 / 2 with signed sigma2 = 2 R^2; exact, no cancellation near conformal.
    conformality_.add(j.area_3d * 2.0 * r * r);
    mapped_area_.add(j.area_3d);
    for(int k = 0; k < 3; ++k)
    {
      const double e = angles_uv[k] - angles_3d[k];
      squared_angle_error_.add(e * e);
    }
    corners_ += 3;
  }

  void add_degenerate_uv_face() { ++result_.degenerate_uv_faces; }

  /// Terms that divide by sigma2 or by the UV area: non-degenerate faces only.
  void add_shape_terms(const Face_jacobian& j)
  {
    if(j.signed_area < 0)
      ++result_.flipped_faces;
    const double q = j.conformal_norm(), r = j.anticonformal_norm();
    const double abs_det = std::abs(j.determinant()); // = s1 * s2 = |s_f| / A_f
    const double s1_squared = (q + r) * (q + r);
    const double smaller = std::min(q, r);                        // s1 - s2 = 2 min(Q, R) with s = |sigma|
    const double shear = 4.0 * smaller * smaller / abs_det;       // s1/s2 + s2/s1 - 2
    const double stretch = (q * q + r * r) / (abs_det * abs_det); // (1/s1^2 + 1/s2^2) / 2
    const double qc = s1_squared / abs_det;                       // s1 / s2
    const double log_ratio = std::log(abs_det);

    shape_area_.add(j.area_3d);
    shear_.add(j.area_3d * shear);
    stretch_.add(j.area_3d * stretch);
    qc_.add(j.area_3d * qc);
    log_area_.add(log_ratio * log_ratio);
    weighted_log_area_.add(j.area_3d * log_ratio * log_ratio);
    ++log_area_faces_;
    result_.qc_max = std::max(result_.qc_max, qc);
    ratio_min_ = std::min(ratio_min_, abs_det);
    ratio_max_ = std::max(ratio_max_, abs_det);
  }

  Distortion_measures finish(std::size_t faces)
  {
    result_.faces = faces;
    const double mapped_area = mapped_area_.value(), shape_area = shape_area_.value();
    if(mapped_area > 0)
      result_.conformality = conformality_.value() / mapped_area;
    if(corners_ > 0)
      result_.angle_distortion = squared_angle_error_.value() / static_cast<double>(corners_);
    if(shape_area > 0)
    {
      result_.l2_shear = std::sqrt(shear_.value() / shape_area);
      result_.l2_stretch = std::sqrt(stretch_.value() / shape_area);
      result_.qc_mean = qc_.value() / shape_area;
      result_.log_area_distortion = log_area_.value() / static_cast<double>(log_area_faces_);
      result_.log_area_distortion_area_weighted = weighted_log_area_.value() / shape_area;
      result_.area_ratio_min = ratio_min_;
      result_.area_ratio_max = ratio_max_;
    }
    return result_;
  }

private:
  Distortion_measures result_;
  Compensated_sum conformality_, mapped_area_, squared_angle_error_;
  Compensated_sum shape_area_, shear_, stretch_, qc_, log_area_, weighted_log_area_;
  std::size_t log_area_faces_ = 0;
  std::size_t corners_ = 0;
  double ratio_min_ = std::numeric_limits<double>::infinity();
  double ratio_max_ = 0;
};

// --- reading points of any type ------------------------------------------------------------

template <class T, class = void>
struct Has_xy_members : std::false_type
{};
template <class T>
struct Has_xy_members<T, std::void_t<decltype(std::declval<const T&>().x()), decltype(std::declval<const T&>().y())>>
  : std::true_type
{};

template <class T, class = void>
struct Has_z_member : std::false_type
{};
template <class T>
struct Has_z_member<T, std::void_t<decltype(std::declval<const T&>().z())>> : std::true_type
{};

/// UV value: anything with .x()/.y() (CGAL Point_2, Vector_2) or [0]/[1] (arrays, Eigen).
template <class P>
Uv to_point2(const P& p)
{
  if constexpr(Has_xy_members<P>::value)
    return {CGAL::to_double(p.x()), CGAL::to_double(p.y())};
  else
    return {CGAL::to_double(p[0]), CGAL::to_double(p[1])};
}

template <class P>
Point3 to_point3(const P& p)
{
  if constexpr(Has_xy_members<P>::value && Has_z_member<P>::value)
    return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
  else
    return {CGAL::to_double(p[0]), CGAL::to_double(p[1]), CGAL::to_double(p[2])};
}

/// Flattens a FaceGraph into the 3-corners-per-face arrays of the core; uv_of_corner(h) gives
/// the UV of the corner at target(h) in face(h). Throws on a face that is not a triangle.
template <class TriangleMesh, class VertexPointMap, class CornerUv>
Distortion_measures measure_faces(const TriangleMesh& mesh, VertexPointMap vpm, CornerUv uv_of_corner);

inline Distortion_measures measure_unit_size(const std::vector<std::array<double, 3>>& xyz,
                                             const std::vector<std::array<double, 2>>& uv);

} // namespace distortion
} // namespace internal

/// Flat core. xyz and uv hold three corners per face (sizes 3F, same order); the 3D corner
/// order orients the face. Throws std::invalid_argument on mismatched sizes or non-finite input.
inline Distortion_measures measure_distortion_of_triangles(const std::vector<std::array<double, 3>>& xyz,
                                                           const std::vector<std::array<double, 2>>& uv)
{
  namespace d = internal::distortion;
  if(xyz.size() != uv.size() || xyz.size() % 3 != 0)
    throw std::invalid_argument("ICM::measure_distortion_of_triangles: xyz and uv must both hold 3 corners per face "
                                "(got " +
                                std::to_string(xyz.size()) + " and " + std::to_string(uv.size()) + ")");

  for(std::size_t c = 0; c < xyz.size(); ++c)
  {
    d::require_finite(xyz[c].data(), 3, "3D");
    d::require_finite(uv[c].data(), 2, "UV");
  }
  return d::measure_unit_size(d::to_unit_size(xyz), d::to_unit_size(uv));
}

namespace internal {
namespace distortion {

/// `measure_distortion_of_triangles` on corners already scaled to unit size.
inline Distortion_measures measure_unit_size(const std::vector<std::array<double, 3>>& xyz,
                                             const std::vector<std::array<double, 2>>& uv)
{
  namespace d = internal::distortion;
  const d::Uv_normalisation normalisation = d::uv_normalisation(xyz, uv);
  d::Distortion_accumulator accumulator;
  for(std::size_t c = 0; c < xyz.size(); c += 3)
  {
    const internal::Point3 &p0 = xyz[c], &p1 = xyz[c + 1], &p2 = xyz[c + 2];
    if(internal::triangle_area(p0, p1, p2) <= normalisation.degenerate_area)
    {
      accumulator.add_degenerate_3d_face();
      continue;
    }
    // Work on differences only: the layout's translation never enters, nor its rounding.
    const Uv du1 = normalisation.apply_to_vector(internal::difference(uv[c + 1], uv[c]));
    const Uv du2 = normalisation.apply_to_vector(internal::difference(uv[c + 2], uv[c]));
    const double signed_area =
      normalisation.apply_to_area(0.5 * internal::twice_signed_area(uv[c], uv[c + 1], uv[c + 2]));
    const d::Face_jacobian j = d::face_jacobian(p0, p1, p2, du1, du2, signed_area);

    const Uv origin = {0, 0};
    accumulator.add_conformal_terms(j, d::corner_angles(p0, p1, p2), d::corner_angles(origin, du1, du2));
    if(std::abs(signed_area) <= normalisation.degenerate_area)
      accumulator.add_degenerate_uv_face();
    else
      accumulator.add_shape_terms(j);
  }
  return accumulator.finish(xyz.size() / 3);
}

} // namespace distortion
} // namespace internal

/// UV per vertex, 3D points from `vpm`. Works for any FaceGraph (Surface_mesh, Polyhedron_3,
/// Seam_mesh with a map keyed by its own vertex_descriptor, ...). Throws std::invalid_argument
/// on a non-triangle face.
template <class TriangleMesh, class VertexUVMap, class VertexPointMap>
Distortion_measures measure_distortion(const TriangleMesh& mesh, VertexUVMap uvmap, VertexPointMap vpm)
{
  using halfedge_descriptor = typename boost::graph_traits<TriangleMesh>::halfedge_descriptor;
  return internal::distortion::measure_faces(mesh, vpm,
                                             [&](halfedge_descriptor h) { return get(uvmap, target(h, mesh)); });
}

/// UV per vertex, 3D points from `get(CGAL::vertex_point, mesh)`.
template <class TriangleMesh, class VertexUVMap>
Distortion_measures measure_distortion(const TriangleMesh& mesh, VertexUVMap uvmap)
{
  return measure_distortion(mesh, uvmap, get(CGAL::vertex_point, mesh));
}

/// UV per corner: `halfedge_uv_map[h]` is the UV of the corner at target(h) in face(h)
/// (as a texture atlas stores it), 3D points from `vpm`.
template <class TriangleMesh, class HalfedgeUVMap, class VertexPointMap>
Distortion_measures measure_distortion_corner_uv(const TriangleMesh& mesh, HalfedgeUVMap halfedge_uv_map,
                                                 VertexPointMap vpm)
{
  using halfedge_descriptor = typename boost::graph_traits<TriangleMesh>::halfedge_descriptor;
  return internal::distortion::measure_faces(mesh, vpm, [&](halfedge_descriptor h) { return get(halfedge_uv_map, h); });
}

/// UV per corner, 3D points from `get(CGAL::vertex_point, mesh)`.
template <class TriangleMesh, class HalfedgeUVMap>
Distortion_measures measure_distortion_corner_uv(const TriangleMesh& mesh, HalfedgeUVMap halfedge_uv_map)
{
  return measure_distortion_corner_uv(mesh, halfedge_uv_map, get(CGAL::vertex_point, mesh));
}

/// The total 3D length of the edges `seams` over the square root of the mesh's 3D area: the
/// length of a cut free of the mesh's scale, 0 without a seam (`seam_length` in icm_param's
/// JSON and in the Python module's report; `Chart_report::seam_length` per component).
template <class TriangleMesh, class EdgeRange>
double seam_length_over_root_area(const TriangleMesh& mesh, const EdgeRange& seams)
{
  const auto vpm = get(CGAL::vertex_point, mesh);
  const auto point = [&](auto v) {
    const auto& p = get(vpm, v);
    return std::array<double, 3>{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
  };
  const auto minus = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::array<double, 3>{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  };
  double length = 0, area = 0;
  for(const auto& e : seams)
  {
    const std::array<double, 3> d = minus(point(target(e, mesh)), point(source(e, mesh)));
    length += std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  }
  for(auto f : faces(mesh))
  {
    const auto h = halfedge(f, mesh);
    const std::array<double, 3> a = point(source(h, mesh));
    const std::array<double, 3> u = minus(point(target(h, mesh)), a), w = minus(point(target(next(h, mesh), mesh)), a);
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  return area > 0 ? length / std::sqrt(area) : 0.0;
}

namespace internal {
namespace distortion {

template <class TriangleMesh, class VertexPointMap, class CornerUv>
Distortion_measures measure_faces(const TriangleMesh& mesh, VertexPointMap vpm, CornerUv uv_of_corner)
{
  std::vector<Point3> xyz;
  std::vector<Uv> uv;
  const std::size_t face_count = static_cast<std::size_t>(std::distance(faces(mesh).begin(), faces(mesh).end()));
  xyz.reserve(3 * face_count);
  uv.reserve(3 * face_count);
  for(auto f : faces(mesh))
  {
    std::size_t corners = 0;
    internal::for_each_halfedge_of_face(f, mesh, [&](auto h) {
      if(++corners > 3)
        return false;
      xyz.push_back(to_point3(get(vpm, target(h, mesh))));
      uv.push_back(to_point2(uv_of_corner(h)));
      return true;
    });
    if(corners != 3)
      throw std::invalid_argument("ICM::measure_distortion: the mesh has a face with " +
                                  std::string(corners > 3 ? "more than 3" : std::to_string(corners)) +
                                  " corners; the distortion measures need a triangle mesh "
                                  "(triangulate it first, e.g. CGAL::Polygon_mesh_processing::triangulate_faces)");
  }
  return measure_distortion_of_triangles(xyz, uv);
}

} // namespace distortion
} // namespace internal
} // namespace ICM

#endif // ICM_MEASURES_DISTORTION_H
