// A prescribed border with straight sides (a square's): which vertices lie on one side, the
// faces held on a side (segments in any layout, counted apart from flipped faces), and the
// sides made exactly straight after the layout.

#ifndef ICM_BORDER_STRAIGHT_SIDES_H
#define ICM_BORDER_STRAIGHT_SIDES_H

#include <ICM/internal/Vector_geometry.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace ICM {

namespace internal {

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
          stretches[v][0] = id; // the one it ends (at i = n: the last)
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
    flipped += !(internal::twice_signed_area(uv[c[0]], uv[c[1]], uv[c[2]]) > 0);
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

} // namespace internal

} // namespace ICM

#endif // ICM_BORDER_STRAIGHT_SIDES_H
