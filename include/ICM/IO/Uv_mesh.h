// Copyright (c) the ICM authors.
//
// A flat, writer-friendly copy of a parameterized triangle mesh: positions and UVs are indexed
// separately per face corner, exactly as a Wavefront OBJ stores them, so that a vertex split by
// a seam keeps one position but gets one UV per side of the seam.

#ifndef ICM_IO_UV_MESH_H
#define ICM_IO_UV_MESH_H

#include <ICM/Status.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/number_utils.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <ostream>
#include <locale>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

namespace CGAL {
// Declared only. <CGAL/boost/graph/Seam_mesh.h> calls the underlying mesh's graph functions
// with qualified names, so it must come after that mesh's headers (e.g. <CGAL/Surface_mesh.h>);
// including it here would put it first whenever this header is included first. Whoever has a
// Seam_mesh to pass has included it anyway.
template <class TM, class SEM, class SVM>
class Seam_mesh;
} // namespace CGAL

namespace ICM {
namespace IO {

/// A triangle mesh whose faces index 3D positions (`v`) and UVs (`vt`) separately.
///
/// `face_positions[f]` and `face_uvs[f]` are the three corners of face `f`, in the same
/// (counterclockwise in 3D) order; both arrays have one entry per face. Indices are 0-based.
struct Uv_mesh
{
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<double, 2>> uvs;
  std::vector<std::array<int, 3>> face_positions;
  std::vector<std::array<int, 3>> face_uvs;

  std::size_t number_of_faces() const { return face_positions.size(); }
};

/// The value log area ratios take for faces with a zero area on one side only
/// (log 0 would be -inf or +inf, which neither plots nor sums well).
constexpr double log_area_ratio_clamp = 50.;

} // namespace IO

namespace internal {

/// Writes `x` so that reading it back as a `Real` gives the same number: the shortest such
/// form where the standard library has it (std::to_chars, independent of the stream's
/// locale), otherwise max_digits10 significant digits in the stream's locale.
template <class Real>
void put_exact_number(std::ostream& os, Real x)
{
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  char buffer[32];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof(buffer), x);
  os.write(buffer, r.ptr - buffer);
#else
  const std::streamsize old_precision = os.precision(std::numeric_limits<Real>::max_digits10);
  os << x;
  os.precision(old_precision);
#endif
}

/// Why a UV that is not finite overflowed, when it is infinite rather than NaN: parameterizers
/// lay a mesh out at unit size and scale the UVs back to the mesh's (each chart's UV area is
/// its 3D area), and near the largest double the layout can outgrow it. Empty for a NaN.
inline std::string why_uvs_overflow(const IO::Uv_mesh& m, const std::array<double, 2>& uv)
{
  if(std::isnan(uv[0]) || std::isnan(uv[1]))
    return {};
  double extent = 0.;
  for(int k = 0; k < 3 && !m.positions.empty(); ++k)
  {
    double low = m.positions[0][k], high = low;
    for(const auto& p : m.positions)
    {
      low = (std::min)(low, p[k]);
      high = (std::max)(high, p[k]);
    }
    extent = (std::max)(extent, high - low);
  }
  return ": the layout, scaled back to the mesh's extent (" + internal::message_number(extent, 3) +
         "), is beyond the range of a double (scale the mesh down)";
}

} // namespace internal

namespace IO {

/// Checks that the face arrays have the same size, that every index is in range and that every
/// coordinate is finite. On failure fills `error` with a one-line reason and returns false.
inline bool is_valid_uv_mesh(const Uv_mesh& m, std::string& error)
{
  if(m.face_positions.size() != m.face_uvs.size())
  {
    error = "the mesh has " + std::to_string(m.face_positions.size()) + " position faces but " +
            std::to_string(m.face_uvs.size()) + " UV faces";
    return false;
  }
  for(std::size_t f = 0; f < m.face_positions.size(); ++f)
  {
    for(int k = 0; k < 3; ++k)
    {
      const int p = m.face_positions[f][k], t = m.face_uvs[f][k];
      if(p < 0 || static_cast<std::size_t>(p) >= m.positions.size() || t < 0 ||
         static_cast<std::size_t>(t) >= m.uvs.size())
      {
        error = "face " + std::to_string(f) + " has an index out of range";
        return false;
      }
    }
  }
  for(std::size_t i = 0; i < m.positions.size(); ++i)
  {
    const auto& p = m.positions[i];
    if(!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      error = "position " + std::to_string(i) + " is not finite";
      return false;
    }
  }
  for(std::size_t i = 0; i < m.uvs.size(); ++i)
  {
    if(!std::isfinite(m.uvs[i][0]) || !std::isfinite(m.uvs[i][1]))
    {
      error = "UV " + std::to_string(i) + " is not finite" + internal::why_uvs_overflow(m, m.uvs[i]);
      return false;
    }
  }
  return true;
}

/// Signed area of face `f` in the UV plane (positive when counterclockwise).
/// \pre `m` is valid (`is_valid_uv_mesh()`).
inline double uv_signed_area(const Uv_mesh& m, std::size_t f)
{
  const auto& a = m.uvs[m.face_uvs[f][0]];
  const auto& b = m.uvs[m.face_uvs[f][1]];
  const auto& c = m.uvs[m.face_uvs[f][2]];
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

/// Area of face `f` in 3D.
/// \pre `m` is valid (`is_valid_uv_mesh()`).
inline double position_area(const Uv_mesh& m, std::size_t f)
{
  const auto& a = m.positions[m.face_positions[f][0]];
  const auto& b = m.positions[m.face_positions[f][1]];
  const auto& c = m.positions[m.face_positions[f][2]];
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

} // namespace IO

namespace internal {

/// Half the longest side of the bounding box of `points` (1 if none or zero).
template <class Points>
double half_extent(const Points& points)
{
  if(points.empty())
    return 1.;
  auto low = points[0], high = points[0];
  for(const auto& p : points)
    for(std::size_t k = 0; k < p.size(); ++k)
    {
      low[k] = (std::min)(low[k], p[k]);
      high[k] = (std::max)(high[k], p[k]);
    }
  double half = 0.;
  for(std::size_t k = 0; k < low.size(); ++k)
    half = (std::max)(half, high[k] / 2 - low[k] / 2); // halves first: no overflow
  return half > 0. && std::isfinite(half) ? half : 1.;
}

/// `m` with positions and UVs each divided by their half extent (faces unchanged).
inline IO::Uv_mesh at_unit_size(const IO::Uv_mesh& m)
{
  IO::Uv_mesh unit = m;
  const double p = half_extent(m.positions), t = half_extent(m.uvs);
  for(auto& x : unit.positions)
    for(double& c : x)
      c /= p;
  for(auto& x : unit.uvs)
    for(double& c : x)
      c /= t;
  return unit;
}

} // namespace internal

namespace IO {

/// Per face log(s_uv / s_3d), where the UVs are first scaled uniformly so that the total
/// |UV area| equals the total 3D area: the result does not depend on the scale of the layout,
/// only on how unevenly it distributes area (0 everywhere means area preserving up to scale).
/// UV areas are taken in absolute value, so a flipped face is measured by its size only.
///
/// Degenerate faces: a face with zero UV area and a positive 3D area gets
/// `-log_area_ratio_clamp`, one with zero 3D area and a positive UV area gets
/// `+log_area_ratio_clamp`, and one with both zero gets 0 (nothing to compare). Every other
/// value is clamped to the same range. If the whole layout has zero area, every face with a
/// positive 3D area gets `-log_area_ratio_clamp`.
/// \pre `m` is valid (`is_valid_uv_mesh()`).
inline std::vector<double> log_area_ratios(const Uv_mesh& m)
{
  // Areas of a copy at unit size: at 1e-300 or 1e+300 the products of coordinates would
  // underflow or overflow, and the ratios do not depend on either scale.
  const Uv_mesh unit = internal::at_unit_size(m);
  const std::size_t nf = m.number_of_faces();
  std::vector<double> uv_area(nf), area_3d(nf);
  double total_uv = 0., total_3d = 0.;
  for(std::size_t f = 0; f < nf; ++f)
  {
    uv_area[f] = std::abs(uv_signed_area(unit, f));
    area_3d[f] = position_area(unit, f);
    total_uv += uv_area[f];
    total_3d += area_3d[f];
  }

  // Work with log(scale) rather than the scale itself so that layouts with tiny or huge
  // coordinates do not overflow or underflow the normalisation.
  const double log_scale = (total_uv > 0. && total_3d > 0.) ? std::log(total_3d) - std::log(total_uv) : 0.;

  std::vector<double> ratios(nf);
  for(std::size_t f = 0; f < nf; ++f)
  {
    const bool uv_zero = !(uv_area[f] > 0.) || !(total_uv > 0.);
    const bool zero_3d = !(area_3d[f] > 0.);
    double r;
    if(uv_zero && zero_3d)
      r = 0.;
    else if(uv_zero)
      r = -log_area_ratio_clamp;
    else if(zero_3d)
      r = log_area_ratio_clamp;
    else
      r = std::log(uv_area[f]) + log_scale - std::log(area_3d[f]);
    ratios[f] = (std::min)(log_area_ratio_clamp, (std::max)(-log_area_ratio_clamp, r));
  }
  return ratios;
}

} // namespace IO

namespace internal {

template <class Point_3>
std::array<double, 3> to_array_3(const Point_3& p)
{
  return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
}

template <class Point_2>
std::array<double, 2> to_array_2(const Point_2& p)
{
  return {{CGAL::to_double(p.x()), CGAL::to_double(p.y())}};
}

/// The 3D position of every vertex, in `vertices(mesh)` order, into `out.positions`; returns
/// each vertex's index there.
template <class TriangleMesh>
std::unordered_map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, int>
copy_positions(const TriangleMesh& mesh, IO::Uv_mesh& out)
{
  const auto vpm = get(CGAL::vertex_point, mesh);
  std::unordered_map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, int> index;
  index.reserve(num_vertices(mesh));
  out.positions.reserve(num_vertices(mesh));
  for(auto v : vertices(mesh))
  {
    index.emplace(v, static_cast<int>(out.positions.size()));
    out.positions.push_back(to_array_3(get(vpm, v)));
  }
  return index;
}

} // namespace internal

namespace IO {

/// Copies a parameterized triangle mesh into a `Uv_mesh`, one UV per vertex.
///
/// \tparam TriangleMesh a model of `FaceGraph` with an internal `vertex_point` map
///         (`CGAL::Surface_mesh`, `CGAL::Polyhedron_3`, ...). Faces must be triangles.
/// \tparam VertexUVMap a readable property map from `vertex_descriptor` to a 2D point
///         (anything with `.x()` and `.y()`, e.g. `CGAL::Point_2`).
///
/// Position `i` and UV `i` are the `i`-th vertex in `vertices(mesh)` order. The indices come
/// from a local map, so meshes with removed elements or without a vertex index work too.
template <class TriangleMesh, class VertexUVMap>
Uv_mesh make_uv_mesh(const TriangleMesh& mesh, VertexUVMap uvmap)
{
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  using halfedge_descriptor = typename boost::graph_traits<TriangleMesh>::halfedge_descriptor;
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;

  Uv_mesh out;
  const std::unordered_map<vertex_descriptor, int> index = internal::copy_positions(mesh, out);
  out.uvs.reserve(num_vertices(mesh));
  for(vertex_descriptor v : vertices(mesh))
    out.uvs.push_back(internal::to_array_2(get(uvmap, v)));

  out.face_positions.reserve(num_faces(mesh));
  for(face_descriptor f : faces(mesh))
  {
    std::array<int, 3> corners{{0, 0, 0}};
    int k = 0;
    for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, mesh), mesh))
    {
      CGAL_precondition_msg(k < 3, "make_uv_mesh() needs a triangle mesh");
      if(k < 3)
        corners[k] = index.at(target(h, mesh));
      ++k;
    }
    CGAL_precondition_msg(k == 3, "make_uv_mesh() needs a triangle mesh");
    out.face_positions.push_back(corners);
  }
  // One UV per vertex: both index arrays are the same.
  out.face_uvs = out.face_positions;
  return out;
}

/// Copies a mesh with one UV per corner (a halfedge map: the UV of `target(h)` in `face(h)`,
/// as `ICM::parameterize` writes it) into a `Uv_mesh`. Corners of one vertex with the same UV
/// share one `vt`, so a vertex gets one UV per side of the seams through it.
template <class TriangleMesh, class HalfedgeUVMap>
Uv_mesh make_uv_mesh_from_corners(const TriangleMesh& mesh, HalfedgeUVMap uvmap)
{
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  using halfedge_descriptor = typename boost::graph_traits<TriangleMesh>::halfedge_descriptor;
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  Uv_mesh out;
  const std::unordered_map<vertex_descriptor, int> index = internal::copy_positions(mesh, out);
  // Per vertex, the vt indices it has so far (a handful at most: one per seam side).
  std::vector<std::vector<int>> vts(out.positions.size());
  for(face_descriptor f : faces(mesh))
  {
    std::array<int, 3> p{{0, 0, 0}}, t{{0, 0, 0}};
    int k = 0;
    for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, mesh), mesh))
    {
      CGAL_precondition_msg(k < 3, "make_uv_mesh_from_corners() needs a triangle mesh");
      if(k == 3)
        break;
      const int v = index.at(target(h, mesh));
      const std::array<double, 2> uv = internal::to_array_2(get(uvmap, h));
      int found = -1;
      for(int candidate : vts[v])
        if(out.uvs[candidate] == uv)
          found = candidate;
      if(found < 0)
      {
        found = static_cast<int>(out.uvs.size());
        out.uvs.push_back(uv);
        vts[v].push_back(found);
      }
      p[k] = v;
      t[k] = found;
      ++k;
    }
    out.face_positions.push_back(p);
    out.face_uvs.push_back(t);
  }
  return out;
}

/// Copies a parameterized seam mesh into a `Uv_mesh`.
///
/// `positions` holds one entry per vertex of the underlying mesh (`seam_mesh.mesh()`), in its
/// `vertices()` order; `uvs` one entry per vertex of the seam mesh, so a vertex on a seam has
/// one position and two or more UVs. `face_positions` index the underlying vertices and
/// `face_uvs` the seam mesh vertices.
///
/// \tparam VertexUVMap a readable property map keyed by the seam mesh `vertex_descriptor`
///         (a map keyed by the underlying mesh's `halfedge_descriptor`, as in CGAL's
///         parameterization examples, works too: the seam vertex converts to it).
template <class TM, class SeamEdgeMap, class SeamVertexMap, class VertexUVMap>
Uv_mesh make_uv_mesh(const CGAL::Seam_mesh<TM, SeamEdgeMap, SeamVertexMap>& seam_mesh, VertexUVMap uvmap)
{
  using Seam_mesh = CGAL::Seam_mesh<TM, SeamEdgeMap, SeamVertexMap>;
  using vertex_descriptor = typename boost::graph_traits<Seam_mesh>::vertex_descriptor;
  using halfedge_descriptor = typename boost::graph_traits<Seam_mesh>::halfedge_descriptor;
  using face_descriptor = typename boost::graph_traits<Seam_mesh>::face_descriptor;
  using TM_vertex_descriptor = typename boost::graph_traits<TM>::vertex_descriptor;

  const TM& tm = seam_mesh.mesh();
  Uv_mesh out;
  const std::unordered_map<TM_vertex_descriptor, int> position_index = internal::copy_positions(tm, out);

  // Seam_mesh::vertex_descriptor is a canonical halfedge of the underlying mesh pointing to
  // the vertex; it is what target(h, seam_mesh) returns, so it is a sound hash key.
  std::unordered_map<vertex_descriptor, int> uv_index;
  for(vertex_descriptor v : vertices(seam_mesh))
  {
    uv_index.emplace(v, static_cast<int>(out.uvs.size()));
    out.uvs.push_back(internal::to_array_2(get(uvmap, v)));
  }

  out.face_positions.reserve(num_faces(tm));
  out.face_uvs.reserve(num_faces(tm));
  for(face_descriptor f : faces(seam_mesh))
  {
    std::array<int, 3> p{{0, 0, 0}}, t{{0, 0, 0}};
    int k = 0;
    for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, seam_mesh), seam_mesh))
    {
      CGAL_precondition_msg(k < 3, "make_uv_mesh() needs a triangle mesh");
      if(k < 3)
      {
        // The seam halfedge wraps a halfedge of the underlying mesh with the same target.
        p[k] = position_index.at(target(h.tmhd, tm));
        t[k] = uv_index.at(target(h, seam_mesh));
      }
      ++k;
    }
    CGAL_precondition_msg(k == 3, "make_uv_mesh() needs a triangle mesh");
    out.face_positions.push_back(p);
    out.face_uvs.push_back(t);
  }
  return out;
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_UV_MESH_H
