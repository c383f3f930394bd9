// Step 7: isometric layout of a flat metric in the plane (paper Sec. III-F).
//
// Two methods:
// - propagation: place a central face, then unfold neighbours breadth first, each new vertex
//   from the two already placed ones and the metric's corner angle (the paper, for small
//   meshes: rounding error grows with the depth of the face tree);
// - harmonic: by Lemma 5.4 the isometric embedding of a flat circle packing metric is
//   harmonic for the dynamic Laplacian of that metric. The border is walked once with the
//   metric's edge lengths and turning angles (the boundary curvatures), then the interior is
//   the solution of Delta_NN x = b — one global solve with the Newton system's own
//   pattern, so no error accumulates across the mesh.
// Both require a topological disk whose metric is flat at every interior vertex.

#ifndef ICM_LAYOUT_H
#define ICM_LAYOUT_H

#include <ICM/Curvature_map.h>
#include <ICM/Distortion.h>
#include <ICM/Dynamic_laplacian.h>
#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <string>
#include <vector>

namespace ICM {

using Uv = std::array<double, 2>;

enum class Layout_method
{
  Automatic,   ///< propagation below `harmonic_layout_min_faces` faces, harmonic above
  Propagation,
  Harmonic
};

/// The face farthest (in face hops) from the border, or face 0 on a closed mesh: unfolding
/// from the middle keeps the face tree shallow.
inline int central_face(const internal::Mesh_index& index)
{
  const int nf = index.number_of_faces();
  std::vector<int> depth(nf, -1);
  std::queue<int> queue;
  for(int e = 0; e < index.number_of_edges(); ++e)
    if(index.edge_faces[e][1] < 0 && depth[index.edge_faces[e][0]] < 0)
    {
      depth[index.edge_faces[e][0]] = 0;
      queue.push(index.edge_faces[e][0]);
    }
  int last = 0;
  while(!queue.empty())
  {
    last = queue.front();
    queue.pop();
    for(int e : index.face_edges[last])
      for(int g : index.edge_faces[e])
        if(g >= 0 && depth[g] < 0)
        {
          depth[g] = depth[last] + 1;
          queue.push(g);
        }
  }
  return last;
}

/// The faces around each vertex, in compressed rows: those of v are
/// `faces[first[v]] .. faces[first[v + 1] - 1]`.
struct Faces_around_vertices
{
  std::vector<int> first, faces;

  explicit Faces_around_vertices(const internal::Mesh_index& index)
    : Faces_around_vertices(index.faces, index.number_of_vertices())
  {}

  /// For faces given by their corners' vertex ids, below `vertices`.
  Faces_around_vertices(const std::vector<std::array<int, 3>>& corners, int vertices) : first(vertices + 1, 0)
  {
    for(const auto& f : corners)
      for(int v : f)
        ++first[v + 1];
    for(int v = 0; v < vertices; ++v)
      first[v + 1] += first[v];
    faces.resize(first[vertices]);
    std::vector<int> fill(first.begin(), first.end() - 1);
    for(std::size_t f = 0; f < corners.size(); ++f)
      for(int v : corners[f])
        faces[fill[v]++] = static_cast<int>(f);
  }
};

/// Unfolds the faces from the central face. Vertex c of a face entered across its edge
/// (a, b) — in the face's orientation — is a + l_ac R(theta_a) (b - a)/|b - a|, so every
/// face keeps the input orientation (counter-clockwise = positive area).
///
/// The order is not breadth first but least estimated error first (Dijkstra): placing c from
/// (a, b) carries a's error and turns the direction of (b - a), known to (err_a + err_b) /
/// l_ab, through l_ac, so err_c ~ err_a + (err_a + err_b) l_ac / l_ab. Entering a thin face
/// through its short edge multiplies the error by its aspect ratio; breadth first did that
/// wherever the face tree went (armadillo with 32 cones: edges off by 1e-7 of their
/// length), this order takes every vertex from its best conditioned chain.
///
/// `angles` are the metric's own per-face angles (`Curvature_map::face_angles`), which keep
/// full relative precision in faces whose radii differ by e^30; recomputed from the lengths,
/// the tiny angles of such faces lose their digits.
inline std::vector<Uv> layout_by_propagation_from(const internal::Mesh_index& index,
                                                  const std::vector<double>& lengths,
                                                  const std::vector<Triangle_angles>& angles, int root)
{
  const int nf = index.number_of_faces(), nv = index.number_of_vertices();
  std::vector<Uv> uv(nv, Uv{0.0, 0.0});
  if(nf == 0)
    return uv;
  const Faces_around_vertices around(index);
  const std::vector<int>&first = around.first, &ring = around.faces;

  constexpr double eps = std::numeric_limits<double>::epsilon();
  // The estimate only orders the candidates: it grows geometrically with the hops from the
  // root and may overflow to infinity on a long strip, so "placed" is a flag of its own;
  // each (face, corner) is then offered at most once and the queue holds at most 3 F.
  std::vector<double> error(nv, 0.0);
  std::vector<char> is_placed(nv, 0);
  auto placed = [&](int v) { return is_placed[v] != 0; };
  {
    const auto& v = index.faces[root];
    const auto& e = index.face_edges[root];
    const double l01 = lengths[e[2]], l02 = lengths[e[1]], theta0 = angles[root].angle[0];
    uv[v[0]] = {0.0, 0.0};
    uv[v[1]] = {l01, 0.0};
    uv[v[2]] = {l02 * std::cos(theta0), l02 * std::sin(theta0)};
    for(int c = 0; c < 3; ++c)
    {
      error[v[c]] = eps * std::max(l01, l02);
      is_placed[v[c]] = 1;
    }
  }
  // Candidates: (estimated error of the third vertex, face, corner of that vertex).
  using Candidate = std::pair<double, std::pair<int, int>>;
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<Candidate>> queue;
  auto offer_faces_around = [&](int v) {
    for(int i = first[v]; i < first[v + 1]; ++i)
    {
      const int g = ring[i];
      const auto& f = index.faces[g];
      for(int c = 0; c < 3; ++c)
      {
        const int a = f[(c + 1) % 3], b = f[(c + 2) % 3];
        if(placed(f[c]) || !placed(a) || !placed(b))
          continue;
        const double l_ab = lengths[index.face_edges[g][c]], l_ac = lengths[index.face_edges[g][(c + 2) % 3]];
        queue.push({error[a] + (error[a] + error[b]) * l_ac / l_ab + eps * l_ac, {g, c}});
      }
    }
  };
  for(int v : index.faces[root])
    offer_faces_around(v);
  while(!queue.empty())
  {
    const auto [estimate, where] = queue.top();
    queue.pop();
    const auto [g, c] = where;
    const int third = index.faces[g][c];
    if(placed(third))
      continue;
    const int a = index.faces[g][(c + 1) % 3], b = index.faces[g][(c + 2) % 3];
    const double theta = angles[g].angle[(c + 1) % 3];
    const double l_ac = lengths[index.face_edges[g][(c + 2) % 3]];
    const double dx = uv[b][0] - uv[a][0], dy = uv[b][1] - uv[a][1];
    const double scale = l_ac / std::hypot(dx, dy);
    const double cs = std::cos(theta) * scale, sn = std::sin(theta) * scale;
    uv[third] = {uv[a][0] + cs * dx - sn * dy, uv[a][1] + sn * dx + cs * dy};
    error[third] = estimate;
    is_placed[third] = 1;
    offer_faces_around(third);
  }
  return uv;
}

/// The face whose UV centroid is nearest the centre of the layout's bounding box.
inline int face_nearest_uv_centre(const internal::Mesh_index& index, const std::vector<Uv>& uv)
{
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
  for(const Uv& p : uv)
    for(int i = 0; i < 2; ++i)
    {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  int best = 0;
  double best_distance = HUGE_VAL;
  for(int f = 0; f < index.number_of_faces(); ++f)
  {
    double d[2];
    for(int i = 0; i < 2; ++i)
      d[i] = (uv[index.faces[f][0]][i] + uv[index.faces[f][1]][i] + uv[index.faces[f][2]][i]) / 3 -
             0.5 * (lo[i] + hi[i]);
    if(d[0] * d[0] + d[1] * d[1] < best_distance)
    {
      best_distance = d[0] * d[0] + d[1] * d[1];
      best = f;
    }
  }
  return best;
}

/// Walks the single border loop counter-clockwise with the metric's edge lengths, turning
/// by the boundary curvature k_i (the exterior angle) at each vertex. The closing gap, zero
/// up to rounding when sum k = 2 pi, is spread along the loop.
inline void layout_border(const internal::Mesh_index& index, const std::vector<double>& lengths,
                          const Eigen::VectorXd& k, std::vector<Uv>& uv)
{
  // Border halfedges leave the interior on their right: walk the loop backwards.
  const std::vector<int>& loop = index.boundary_loops.front();
  const std::vector<int>& loop_edges = index.boundary_loop_edges.front();
  const int m = static_cast<int>(loop.size());
  double heading = 0, x = 0, y = 0;
  std::vector<Uv> walk(m + 1);
  for(int s = 0; s < m; ++s)
  {
    const int i = (m - s) % m;                 // current vertex, loop[0] first
    const int previous = (i - 1 + m) % m;      // next vertex of the backward walk
    walk[s] = {x, y};
    const double l = lengths[loop_edges[previous]];
    x += l * std::cos(heading);
    y += l * std::sin(heading);
    heading += k[loop[previous]];
  }
  walk[m] = {x, y};
  for(int s = 0; s < m; ++s)
  {
    const double t = static_cast<double>(s) / m;
    uv[loop[(m - s) % m]] = {walk[s][0] - t * walk[m][0], walk[s][1] - t * walk[m][1]};
  }
}

/// Harmonic layout: border walk, then Delta_NN x_N = sum_{j in border} w_ij x_j for the
/// interior. `laplacian` must have the interior vertices as its free set; it is assembled
/// here with the weights `w` of the final metric. When it still holds the factorization of
/// Newton's last step — whose weights differ from the final ones by the size of that step —
/// a few refinements solve the system for the cost of a few triangular solves instead of a
/// factorization; otherwise, or if refinement stalls, it is refactorized.
template <class SparseSolver>
bool layout_harmonic(const internal::Mesh_index& index, const std::vector<double>& lengths,
                     const Eigen::VectorXd& k, const std::vector<double>& w,
                     Dynamic_laplacian<SparseSolver>& laplacian, std::vector<Uv>& uv,
                     std::string& message)
{
  uv.assign(index.number_of_vertices(), Uv{0.0, 0.0});
  if(index.number_of_boundary_loops() != 1)
  {
    message = "the harmonic layout needs exactly one boundary loop";
    return false;
  }
  layout_border(index, lengths, k, uv);
  const int n = laplacian.size();
  if(n == 0)
    return true;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const int a = index.edges[e][0], b = index.edges[e][1];
    const int ia = laplacian.free_index(a), ib = laplacian.free_index(b);
    if(ia >= 0 && ib < 0)
      rhs.row(ia) += w[e] * Eigen::RowVector2d(uv[b][0], uv[b][1]);
    if(ib >= 0 && ia < 0)
      rhs.row(ib) += w[e] * Eigen::RowVector2d(uv[a][0], uv[a][1]);
  }
  laplacian.assemble(w);
  Eigen::MatrixXd x;
  if(!laplacian.has_factorization() || !laplacian.solve_refined(rhs, x))
  {
    if(!laplacian.factorize())
    {
      message = "the layout Laplacian could not be factorized";
      return false;
    }
    x = laplacian.solve(rhs);
  }
  if(!x.allFinite())
  {
    message = "the harmonic layout produced non-finite coordinates";
    return false;
  }
  for(int i = 0; i < n; ++i)
    uv[laplacian.vertex(i)] = {x(i, 0), x(i, 1)};
  return true;
}

/// What every layout is checked for.
struct Layout_check
{
  int flipped_faces = 0;                  ///< faces with non-positive signed area
  /// max_e |uv length - metric length| / metric length, after forgiving 64 units in the last
  /// place of the edge's coordinates: a nearly closed surface squeezes whole protrusions
  /// into 1e-12 of its hole, where an edge spans only millions of representable steps and
  /// the unfolding cannot be exact to more than ~1e-7 of its length.
  double max_relative_length_error = 0;
};

/// Twice the signed area of UV triangle (a, b, c).
inline double twice_signed_area(const Uv& a, const Uv& b, const Uv& c)
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/// Faces of `index` whose UV triangle does not have positive area.
inline int count_flipped_faces(const internal::Mesh_index& index, const std::vector<Uv>& uv)
{
  int flipped = 0;
  for(const auto& f : index.faces)
    flipped += !(twice_signed_area(uv[f[0]], uv[f[1]], uv[f[2]]) > 0);
  return flipped;
}

/// The smallest doubled area of the triangles (s[0], s[1], p) over the `sides` of a fan.
inline double smallest_area_at(const std::vector<std::array<Uv, 2>>& sides, const Uv& p)
{
  double m = HUGE_VAL;
  for(const auto& s : sides)
    m = std::min(m, twice_signed_area(s[0], s[1], p));
  return m;
}

/// The point p maximising the smallest of the doubled areas of the faces around a vertex,
/// each affine in p: area_i(p) = g_i . p + c_i for the face's other corners a_i, b_i in
/// order, over the disc centred at the mean of those corners through the farthest of them.
/// A closed fan's best points (its kernel) lie inside that disc anyway, but an open one (a
/// border vertex) grows every face by moving outwards without end: horse, a border vertex
/// sent 30 of its star's radii out magnified a face 629 times. The maximum of a minimum of
/// affine functions over a disc is where three of them are equal inside it, where two are
/// equal on its circle, or where one is largest on it, so all of those are tried (a vertex
/// has a handful of faces). Returns the smallest area at the point found.
inline double max_min_area_point(const std::vector<std::array<Uv, 2>>& sides, Uv& best)
{
  const std::size_t n = sides.size();
  Uv centre{0, 0};
  for(const auto& s : sides)
    for(const Uv& q : s)
      centre = {centre[0] + q[0] / (2 * n), centre[1] + q[1] / (2 * n)};
  double radius = 0;
  for(const auto& s : sides)
    for(const Uv& q : s)
      radius = std::max(radius, std::hypot(q[0] - centre[0], q[1] - centre[1]));

  auto gradient = [&](std::size_t x) {
    const Uv &a = sides[x][0], &b = sides[x][1];
    return Uv{-(b[1] - a[1]), b[0] - a[0]};
  };
  auto constant = [&](std::size_t x) { return twice_signed_area(sides[x][0], sides[x][1], Uv{0, 0}); };
  double best_value = -HUGE_VAL;
  auto consider = [&](const Uv& p) {
    const double value = smallest_area_at(sides, p);
    if(std::isfinite(value) && value > best_value)
    {
      best_value = value;
      best = p;
    }
  };
  // Three equal inside the disc: solve area_i = area_j = area_k for p.
  for(std::size_t i = 0; i < n; ++i)
    for(std::size_t j = i + 1; j < n; ++j)
      for(std::size_t k = j + 1; k < n; ++k)
      {
        const Uv gi = gradient(i), gj = gradient(j), gk = gradient(k);
        const double m00 = gi[0] - gj[0], m01 = gi[1] - gj[1], r0 = constant(j) - constant(i);
        const double m10 = gi[0] - gk[0], m11 = gi[1] - gk[1], r1 = constant(k) - constant(i);
        const double det = m00 * m11 - m01 * m10;
        if(!(std::abs(det) > 0))
          continue;
        const Uv p{(r0 * m11 - m01 * r1) / det, (m00 * r1 - r0 * m10) / det};
        if(std::hypot(p[0] - centre[0], p[1] - centre[1]) <= radius)
          consider(p);
      }
  // Two equal on the circle: the line (g_i - g_j) . p = c_j - c_i meets it.
  for(std::size_t i = 0; i < n; ++i)
    for(std::size_t j = i + 1; j < n; ++j)
    {
      const Uv gi = gradient(i), gj = gradient(j);
      const Uv normal{gi[0] - gj[0], gi[1] - gj[1]};
      const double length = std::hypot(normal[0], normal[1]);
      if(!(length > 0))
        continue;
      const double offset =
        (constant(j) - constant(i) - normal[0] * centre[0] - normal[1] * centre[1]) / length;
      if(!(std::abs(offset) <= radius))
        continue;
      const double half_chord = std::sqrt(radius * radius - offset * offset);
      const Uv unit{normal[0] / length, normal[1] / length};
      for(double side : {-1.0, 1.0})
        consider({centre[0] + offset * unit[0] - side * half_chord * unit[1],
                  centre[1] + offset * unit[1] + side * half_chord * unit[0]});
    }
  // One largest on the circle.
  for(std::size_t i = 0; i < n; ++i)
  {
    const Uv g = gradient(i);
    const double length = std::hypot(g[0], g[1]);
    if(length > 0)
      consider({centre[0] + radius * g[0] / length, centre[1] + radius * g[1] / length});
  }
  return best_value;
}

/// The conformal distortion of a face (v, a, b) of a star as a function of the image p of
/// its centre v: ||J||^2 / det J = sigma_1 / sigma_2 + sigma_2 / sigma_1 (MIPS) for the affine
/// map J from the face in 3D to (p, a, b) in the plane. It is 2 exactly where the face is
/// similar to its 3D shape and grows without bound as the face degenerates. With J = C - p m^T
/// (C and m from the 3D face and a, b), ||J||^2 is a convex quadratic in p and det J affine,
/// so the quotient is convex where det J > 0: its sum over a star has one minimum in the
/// star's kernel, closed fan or open.
struct Face_conformal_distortion
{
  double mm = 0, cc = 0; ///< ||J||^2 = mm |p|^2 - 2 p . cm + cc
  Uv cm{0, 0};
  Uv g{0, 0};            ///< det J = g . p + c
  double c = 0;
  bool valid = false;    ///< false for a face degenerate in 3D

  static Face_conformal_distortion of(const std::array<double, 3>& pv, const std::array<double, 3>& pa,
                                      const std::array<double, 3>& pb, const Uv& a, const Uv& b)
  {
    namespace d = internal::distortion;
    // The 3D face in a frame of its plane: P = [[|e1|, e2.x], [0, e2.y]], x along e1 = pa - pv.
    const d::Point3 e1 = d::difference(pa, pv), e2 = d::difference(pb, pv);
    const double l1 = std::sqrt(d::dot(e1, e1)), twice_area = d::cross_norm(e1, e2);
    if(!(l1 > 0) || !(twice_area > 0))
      return {};
    const double e2x = d::dot(e1, e2) / l1, e2y = twice_area / l1;
    // M = P^{-1}; J = [a - p, b - p] M = C - p m^T with C = [a, b] M and m = M^T (1, 1).
    const double m00 = 1 / l1, m01 = -e2x / (l1 * e2y), m11 = 1 / e2y;
    const Uv m{m00, m01 + m11};
    const double c00 = a[0] * m00, c01 = a[0] * m01 + b[0] * m11;
    const double c10 = a[1] * m00, c11 = a[1] * m01 + b[1] * m11;
    Face_conformal_distortion f;
    f.mm = m[0] * m[0] + m[1] * m[1];
    f.cm = {c00 * m[0] + c01 * m[1], c10 * m[0] + c11 * m[1]};
    f.cc = c00 * c00 + c01 * c01 + c10 * c10 + c11 * c11;
    // det J = twice_signed_area(p, a, b) / det P, and that area is a x b + p x (a - b).
    f.g = {(a[1] - b[1]) / twice_area, -(a[0] - b[0]) / twice_area};
    f.c = (a[0] * b[1] - a[1] * b[0]) / twice_area;
    f.valid = true;
    return f;
  }
  double numerator(const Uv& p) const { return mm * (p[0] * p[0] + p[1] * p[1]) - 2 * (p[0] * cm[0] + p[1] * cm[1]) + cc; }
  double determinant(const Uv& p) const { return g[0] * p[0] + g[1] * p[1] + c; }
};

/// The sum of the `faces`' conformal distortions at p, HUGE_VAL unless every face of the
/// `sides` keeps a positive area there.
inline double star_conformal_distortion(const std::vector<Face_conformal_distortion>& faces,
                                        const std::vector<std::array<Uv, 2>>& sides, const Uv& p)
{
  if(!(smallest_area_at(sides, p) > 0))
    return HUGE_VAL;
  double sum = 0;
  for(const auto& f : faces)
    if(f.valid)
      sum += f.numerator(p) / f.determinant(p);
  return sum;
}

/// Moves p, a point where every face of the star is positive, to where the star is most
/// conformal: the minimum of its faces' summed conformal distortion, by Newton's method in
/// the plane (the sum is convex), each step halved until it lowers the sum with every face
/// kept positive.
inline Uv most_conformal_position(const std::vector<Face_conformal_distortion>& faces,
                                  const std::vector<std::array<Uv, 2>>& sides, Uv p)
{
  constexpr int max_steps = 50;
  double value = star_conformal_distortion(faces, sides, p);
  for(int step = 0; step < max_steps && value < HUGE_VAL; ++step)
  {
    // d(N/D) = dN/D - N g/D^2; d2(N/D) = d2N/D - (dN g^T + g dN^T)/D^2 + 2 N g g^T/D^3.
    double gx = 0, gy = 0, hxx = 0, hxy = 0, hyy = 0;
    for(const auto& f : faces)
    {
      if(!f.valid)
        continue;
      const double n = f.numerator(p), d = f.determinant(p);
      const double nx = 2 * (f.mm * p[0] - f.cm[0]), ny = 2 * (f.mm * p[1] - f.cm[1]);
      gx += nx / d - n * f.g[0] / (d * d);
      gy += ny / d - n * f.g[1] / (d * d);
      const double twice_n_over_d3 = 2 * n / (d * d * d);
      hxx += 2 * f.mm / d - 2 * nx * f.g[0] / (d * d) + twice_n_over_d3 * f.g[0] * f.g[0];
      hyy += 2 * f.mm / d - 2 * ny * f.g[1] / (d * d) + twice_n_over_d3 * f.g[1] * f.g[1];
      hxy += -(nx * f.g[1] + ny * f.g[0]) / (d * d) + twice_n_over_d3 * f.g[0] * f.g[1];
    }
    const double det = hxx * hyy - hxy * hxy;
    Uv direction = det > 0 && hxx > 0 ? Uv{-(hyy * gx - hxy * gy) / det, -(hxx * gy - hxy * gx) / det} : Uv{-gx, -gy};
    const double decrease = -(gx * direction[0] + gy * direction[1]);
    if(!(decrease > 1e-24 * value))
      break;
    bool moved = false;
    for(double t = 1; t > 1e-12; t *= 0.5)
    {
      const Uv q{p[0] + t * direction[0], p[1] + t * direction[1]};
      const double at_q = star_conformal_distortion(faces, sides, q);
      // Near the minimum a full Newton step changes the sum by less than its rounding.
      if(at_q < value || (t == 1 && at_q <= value * (1 + 1e-14)))
      {
        p = q;
        value = at_q;
        moved = true;
        break;
      }
    }
    if(!moved)
      break;
  }
  return p;
}

/// A wedge that must move with another one: the other side of a seam through a flat vertex.
/// Both sides of a seam are congruent, so `uv[twin]` maps into this wedge's frame by one
/// rigid motion, p -> (c p_x - s p_y + tx, s p_x + c p_y + ty); moving both wedges by that
/// motion keeps every seam edge's two sides the same length.
struct Seam_twin
{
  int wedge = -1; ///< the twin, or -1 (the wedge moves alone, if it may move)
  double c = 1, s = 0, tx = 0, ty = 0;

  Uv to_this(const Uv& p) const { return {c * p[0] - s * p[1] + tx, s * p[0] + c * p[1] + ty}; }
  Uv to_twin(const Uv& p) const
  {
    const double x = p[0] - tx, y = p[1] - ty;
    return {c * x + s * y, -s * x + c * y};
  }
};

/// Unflips faces of `index` by moving single vertices, and returns how many moves were made.
///
/// The metric of an intrinsic triangulation is laid out exactly at the vertices, but a face
/// of the mesh that is not a face of that triangulation is drawn straight between its
/// vertices' images, and a very obtuse face (horse: 163 degrees, mannequin-devil: 166) can
/// come out flipped. For each flipped face, the movable corner whose faces can be made most
/// positive (`max_min_area_point`: the largest smallest doubled area mu) moves. If mu > 0 it
/// goes from that point to where its star is most conformal (`most_conformal_position`: the
/// least summed conformal distortion of its faces against their shapes in the mesh,
/// `index.points`, every face kept positive). Moving only as far as needed to unflip, as at
/// first, left slivers: mean QC 13.7 (max 8247) on pig under the angle energy. Else it moves
/// to the max-min point and a later pass moves its neighbours. A border vertex may move; the
/// side of a seam moves only with its `twins` entry (its faces and its twin's, seen in its
/// frame, are the whole star of a flat vertex), else not at all.
inline int unflip_by_moving_vertices(const internal::Mesh_index& index, std::vector<Uv>& uv,
                                     const std::vector<char>& is_movable,
                                     const std::vector<Seam_twin>& twins = {}, int max_passes = 8)
{
  if(count_flipped_faces(index, uv) == 0)
    return 0;
  const Faces_around_vertices around(index);
  const std::vector<int>&first = around.first, &ring = around.faces;

  auto twin_of = [&](int v) -> const Seam_twin* {
    return twins.empty() || twins[v].wedge < 0 ? nullptr : &twins[v];
  };
  // The other two corners of every face around v, in the face's order, and those around its
  // twin seen in v's frame.
  std::vector<std::array<Uv, 2>> sides;
  std::vector<Face_conformal_distortion> distortions;
  auto add_sides = [&](int v, const Seam_twin* seen_from) {
    for(int i = first[v]; i < first[v + 1]; ++i)
    {
      const auto& f = index.faces[ring[i]];
      const int c = f[0] == v ? 0 : f[1] == v ? 1 : 2;
      Uv a = uv[f[(c + 1) % 3]], b = uv[f[(c + 2) % 3]];
      if(seen_from != nullptr)
      {
        a = seen_from->to_this(a);
        b = seen_from->to_this(b);
      }
      sides.push_back({a, b});
      distortions.push_back(Face_conformal_distortion::of(index.points[v], index.points[f[(c + 1) % 3]],
                                                          index.points[f[(c + 2) % 3]], a, b));
    }
  };
  auto sides_around = [&](int v) {
    sides.clear();
    distortions.clear();
    add_sides(v, nullptr);
    if(const Seam_twin* twin = twin_of(v))
      add_sides(twin->wedge, twin);
  };
  auto smallest_at = [&](const Uv& p) { return smallest_area_at(sides, p); };
  int moves = 0;
  for(int pass = 0; pass < max_passes && count_flipped_faces(index, uv) > 0; ++pass)
    for(int f = 0; f < index.number_of_faces(); ++f)
    {
      const auto& face = index.faces[f];
      if(twice_signed_area(uv[face[0]], uv[face[1]], uv[face[2]]) > 0)
        continue;
      // The corner whose faces can be made most positive (the largest mu), moved from the
      // point that does so to its star's most conformal position.
      int best = -1;
      Uv best_point{};
      double best_value = -HUGE_VAL;
      for(int v : face)
      {
        if(!is_movable[v])
          continue;
        sides_around(v);
        Uv target{0.0, 0.0};
        const double value = max_min_area_point(sides, target);
        if(value > best_value && (value > 0 || value > smallest_at(uv[v])))
        {
          if(value > 0)
            target = most_conformal_position(distortions, sides, target);
          best = v;
          best_point = target;
          best_value = value;
        }
      }
      if(best < 0)
        continue;
      uv[best] = best_point;
      if(const Seam_twin* twin = twin_of(best))
        uv[twin->wedge] = twin->to_twin(uv[best]);
      ++moves;
    }
  return moves;
}

inline Layout_check check_layout(const internal::Mesh_index& index,
                                 const std::vector<double>& lengths, const std::vector<Uv>& uv)
{
  Layout_check check;
  check.flipped_faces = count_flipped_faces(index, uv);
  for(int e = 0; e < index.number_of_edges(); ++e)
  {
    const Uv &a = uv[index.edges[e][0]], &b = uv[index.edges[e][1]];
    const double ulp = std::numeric_limits<double>::epsilon() *
                       std::max({std::abs(a[0]), std::abs(a[1]), std::abs(b[0]), std::abs(b[1])});
    const double error =
      std::max(std::abs(std::hypot(a[0] - b[0], a[1] - b[1]) - lengths[e]) - 64.0 * ulp, 0.0) / lengths[e];
    check.max_relative_length_error =
      std::max(check.max_relative_length_error, std::isfinite(error) ? error : HUGE_VAL);
  }
  return check;
}

/// The propagation layout, unfolded from the middle of the chart where that is more exact.
/// Each vertex the unfolding goes around is flat only to Newton's residual (~1e-14 rad), so
/// the direction drifts with the number of vertices between an edge and the root, and the
/// position error with its distance from the root: armadillo with 32 cones spans some 1500
/// of its shortest edges, whose seam sides differed by 1e-9 unfolded from the face farthest
/// from the border in face hops, 1e-10 from the face at the middle of the first layout. But
/// a nearly closed disk squeezes most of its surface into a speck 1e-9 of its size around
/// that farthest face, which only keeps its digits near the origin (re-rooted, armadillo
/// minus one vertex star had edges off by 6%): the more exact of the two layouts is kept.
inline std::vector<Uv> layout_by_propagation(const internal::Mesh_index& index,
                                             const std::vector<double>& lengths,
                                             const std::vector<Triangle_angles>& angles)
{
  std::vector<Uv> first = layout_by_propagation_from(index, lengths, angles, central_face(index));
  if(index.number_of_faces() == 0)
    return first;
  std::vector<Uv> second = layout_by_propagation_from(index, lengths, angles, face_nearest_uv_centre(index, first));
  return check_layout(index, lengths, second).max_relative_length_error <
             check_layout(index, lengths, first).max_relative_length_error
           ? second
           : first;
}

} // namespace ICM

#endif // ICM_LAYOUT_H
