// Unflipping: a face of the mesh that the metric's own (intrinsic) triangulation does not have
// can land flipped in its layout; moving a vertex of it to where its star is most conformal
// unflips it (see `unflip_by_moving_vertices`).

#ifndef ICM_LAYOUT_UNFLIP_H
#define ICM_LAYOUT_UNFLIP_H

#include <ICM/layout/Layout.h>
#include <ICM/internal/Mesh_index.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace ICM {

/// The smallest doubled area of the triangles (s[0], s[1], p) over the `sides` of a fan.
inline double smallest_area_at(const std::vector<std::array<Uv, 2>>& sides, const Uv& p)
{
  double m = HUGE_VAL;
  for(const auto& s : sides)
    m = std::min(m, internal::twice_signed_area(s[0], s[1], p));
  return m;
}

/// The point p maximising the smallest of the doubled areas of the faces around a vertex,
/// each affine in p: area_i(p) = g_i . p + c_i for the face's other corners a_i, b_i in
/// order, over the disc centred at the mean of those corners through the farthest of them.
/// A closed fan's best points (its kernel) lie inside that disc anyway, but an open one (a
/// border vertex) grows every face by moving outwards without end, magnifying its faces
/// hundreds of times. The maximum of a minimum of
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
  auto constant = [&](std::size_t x) { return internal::twice_signed_area(sides[x][0], sides[x][1], Uv{0, 0}); };
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
      const double offset = (constant(j) - constant(i) - normal[0] * centre[0] - normal[1] * centre[1]) / length;
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
  Uv g{0, 0}; ///< det J = g . p + c
  double c = 0;
  bool valid = false; ///< false for a face degenerate in 3D

  static Face_conformal_distortion of(const std::array<double, 3>& pv, const std::array<double, 3>& pa,
                                      const std::array<double, 3>& pb, const Uv& a, const Uv& b)
  {
    // The 3D face in a frame of its plane: P = [[|e1|, e2.x], [0, e2.y]], x along e1 = pa - pv.
    const internal::Point3 e1 = internal::difference(pa, pv), e2 = internal::difference(pb, pv);
    const double l1 = std::sqrt(internal::dot(e1, e1)), twice_area = internal::cross_norm(e1, e2);
    if(!(l1 > 0) || !(twice_area > 0))
      return {};
    const double e2x = internal::dot(e1, e2) / l1, e2y = twice_area / l1;
    // M = P^{-1}; J = [a - p, b - p] M = C - p m^T with C = [a, b] M and m = M^T (1, 1).
    const double m00 = 1 / l1, m01 = -e2x / (l1 * e2y), m11 = 1 / e2y;
    const Uv m{m00, m01 + m11};
    const double c00 = a[0] * m00, c01 = a[0] * m01 + b[0] * m11;
    const double c10 = a[1] * m00, c11 = a[1] * m01 + b[1] * m11;
    Face_conformal_distortion f;
    f.mm = m[0] * m[0] + m[1] * m[1];
    f.cm = {c00 * m[0] + c01 * m[1], c10 * m[0] + c11 * m[1]};
    f.cc = c00 * c00 + c01 * c01 + c10 * c10 + c11 * c11;
    // det J = internal::twice_signed_area(p, a, b) / det P, and that area is a x b + p x (a - b).
    f.g = {(a[1] - b[1]) / twice_area, -(a[0] - b[0]) / twice_area};
    f.c = (a[0] * b[1] - a[1] * b[0]) / twice_area;
    f.valid = true;
    return f;
  }
  double numerator(const Uv& p) const
  {
    return mm * (p[0] * p[0] + p[1] * p[1]) - 2 * (p[0] * cm[0] + p[1] * cm[1]) + cc;
  }
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
/// vertices' images, and a very obtuse face (above 160 degrees on the shared meshes) can
/// come out flipped. For each flipped face, the movable corner whose faces can be made most
/// positive (`max_min_area_point`: the largest smallest doubled area mu) moves. If mu > 0 it
/// goes from that point to where its star is most conformal (`most_conformal_position`: the
/// least summed conformal distortion of its faces against their shapes in the mesh,
/// `index.points`, every face kept positive): moving only as far as needed to unflip leaves
/// slivers of a huge quasi-conformal ratio. Else it moves
/// to the max-min point and a later pass moves its neighbours. A border vertex may move; the
/// side of a seam moves only with its `twins` entry (its faces and its twin's, seen in its
/// frame, are the whole star of a flat vertex), else not at all.
inline int unflip_by_moving_vertices(const internal::Mesh_index& index, std::vector<Uv>& uv,
                                     const std::vector<char>& is_movable, const std::vector<Seam_twin>& twins = {},
                                     int max_passes = 8)
{
  if(count_flipped_faces(index, uv) == 0)
    return 0;
  const Faces_around_vertices around(index);
  const std::vector<int>&first = around.first, &ring = around.faces;

  auto twin_of = [&](int v) -> const Seam_twin* { return twins.empty() || twins[v].wedge < 0 ? nullptr : &twins[v]; };
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
      if(internal::twice_signed_area(uv[face[0]], uv[face[1]], uv[face[2]]) > 0)
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

} // namespace ICM

#endif // ICM_LAYOUT_UNFLIP_H
