// Vertex scaling on an intrinsic Delaunay triangulation, a model of the `Metric` concept
// (doc/concepts.md) that owns its triangulation.
//
// Plain vertex scaling (Vertex_scaling_metric.h) keeps the mesh's edges, and its valid region
// ends where a face stops being a triangle: the horse's free-boundary optimum would
// degenerate a 171 degree face. Discrete conformal equivalence with edge flips (Gu, Luo,
// Sun, Wu 2018; Springborn 2020; Gillespie, Springborn, Crane 2021) removes that end:
//   1. the mesh is flipped to its intrinsic Delaunay triangulation with Euclidean flips,
//      which do not change the metric (so at u0 the metric is still the mesh);
//   2. at every u the triangulation is flipped to be Delaunay for the scaled lengths, each
//      flip taking its new length from Ptolemy's relation. Ptolemy's relation is invariant
//      under vertex scaling, so the base lengths are the surface's Penner coordinates and do
//      not depend on the path taken; the Delaunay test is written in them, so it is defined
//      even where the scaled lengths of the current triangulation are not triangles.
// The curvature map is then C^1 in u, its Jacobian the cotangent Laplacian of the current
// Delaunay triangulation, and every u has a metric. The triangulation keeps the mesh's
// vertices, faces count and edge count; a flipped edge keeps its id and now joins the two
// corners opposite it. Border edges never flip, nor do edges the caller fixes (seams).

#ifndef ICM_METRICS_INTRINSIC_DELAUNAY_METRIC_H
#define ICM_METRICS_INTRINSIC_DELAUNAY_METRIC_H

#include <ICM/metrics/Vertex_scaling_metric.h>
#include <ICM/internal/Circle_metric.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Triangle_geometry.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace ICM {
namespace internal {

/// The two faces of an interior edge and the corner of each opposite it.
struct Edge_diamond
{
  int f = -1, c = -1, g = -1, d = -1;
};

inline int corner_opposite(const Mesh_index& t, int f, int e)
{
  for(int c = 0; c < 3; ++c)
    if(t.face_edges[f][c] == e)
      return c;
  return -1;
}

/// False for a border edge, and for an edge with the same face on both sides.
inline bool edge_diamond(const Mesh_index& t, int e, Edge_diamond& q)
{
  q.f = t.edge_faces[e][0];
  q.g = t.edge_faces[e][1];
  if(q.f < 0 || q.g < 0 || q.f == q.g)
    return false;
  q.c = corner_opposite(t, q.f, e);
  q.d = corner_opposite(t, q.g, e);
  return true;
}

/// The diamond's vertices p (opposite in f), a, b (the edge, in f's order), q (opposite in
/// g) and its four outer edges. g runs along the edge from b to a (consistent orientation).
struct Diamond_sides
{
  int p, a, b, q;
  int bp, pa, aq, qb;
};

inline Diamond_sides diamond_sides(const Mesh_index& t, const Edge_diamond& x)
{
  Diamond_sides s;
  s.p = t.faces[x.f][x.c];
  s.a = t.faces[x.f][(x.c + 1) % 3];
  s.b = t.faces[x.f][(x.c + 2) % 3];
  s.q = t.faces[x.g][x.d];
  s.bp = t.face_edges[x.f][(x.c + 1) % 3];
  s.pa = t.face_edges[x.f][(x.c + 2) % 3];
  s.aq = t.face_edges[x.g][(x.d + 1) % 3];
  s.qb = t.face_edges[x.g][(x.d + 2) % 3];
  return s;
}

inline void replace_first(std::array<int, 2>& faces, int from, int to)
{
  if(faces[0] == from)
    faces[0] = to;
  else if(faces[1] == from)
    faces[1] = to;
}

/// Flips edge `e` in place: faces (p, a, b) and (q, b, a) become (p, a, q) and (q, b, p),
/// both counter-clockwise again; the edge, and the two faces, keep their ids.
inline void flip_edge(Mesh_index& t, int e, const Edge_diamond& x)
{
  const Diamond_sides s = diamond_sides(t, x);
  t.faces[x.f] = {s.p, s.a, s.q};
  t.face_edges[x.f] = {s.aq, e, s.pa};
  t.faces[x.g] = {s.q, s.b, s.p};
  t.face_edges[x.g] = {s.bp, e, s.qb};
  // Edge aq moves from g to f, edge bp from f to g (in this order, so that an edge that is
  // both ends up on both faces).
  replace_first(t.edge_faces[s.aq], x.g, x.f);
  replace_first(t.edge_faces[s.bp], x.f, x.g);
  t.edges[e] = {std::min(s.p, s.q), std::max(s.p, s.q)};
}

/// One face's half of the Delaunay test of its side ab, seen from the opposite corner p.
/// With sides scaled by sqrt(g_i g_j), (cos theta_p) / l_ab in face (p, a, b) is
/// (l_bp^2 / g_a + l_pa^2 / g_b - l_ab^2 / g_p) / (2 l_bp l_pa): in this form the test is
/// defined for any positive lengths, triangles or not (the horocyclic form of Penner
/// coordinates). `scale` is the magnitude the rounding of `value` is relative to.
struct Delaunay_half
{
  double value = 0, scale = 0;
};

inline Delaunay_half delaunay_half(double l_bp, double l_pa, double l_ab, double g_a, double g_b, double g_p)
{
  const double bp = l_bp * l_bp / g_a, pa = l_pa * l_pa / g_b, ab = l_ab * l_ab / g_p;
  const double sides = l_bp * l_pa;
  return {(bp + pa - ab) / sides, (std::abs(bp) + std::abs(pa) + ab) / sides};
}

/// cos theta_p + cos theta_q >= 0, the Delaunay condition. Ties within rounding count as
/// Delaunay, so that cocircular diamonds do not flip back and forth.
inline bool is_delaunay(const Delaunay_half& f, const Delaunay_half& g)
{
  return !(f.value + g.value < -1e-12 * (f.scale + g.scale));
}

/// Whether the scaled metric is Delaunay at the diamond's edge ab.
inline bool is_delaunay_edge(const Diamond_sides& s, int e, const std::vector<double>& l, const std::vector<double>& g)
{
  return is_delaunay(delaunay_half(l[s.bp], l[s.pa], l[e], g[s.a], g[s.b], g[s.p]),
                     delaunay_half(l[s.qb], l[s.aq], l[e], g[s.a], g[s.b], g[s.q]));
}

/// Both halves of the Delaunay test of every edge, accumulated face by face: each face's
/// corner terms are computed once instead of once per diamond.
inline void accumulate_delaunay_halves(const Mesh_index& t, const std::vector<double>& l, const std::vector<double>& g,
                                       std::vector<Delaunay_half>& halves)
{
  halves.assign(t.number_of_edges(), Delaunay_half());
  for(int f = 0; f < t.number_of_faces(); ++f)
  {
    const std::array<int, 3>& v = t.faces[f];
    const std::array<int, 3>& e = t.face_edges[f];
    for(int c = 0; c < 3; ++c)
    {
      const int next = (c + 1) % 3, last = (c + 2) % 3;
      const Delaunay_half h = delaunay_half(l[e[next]], l[e[last]], l[e[c]], g[v[next]], g[v[last]], g[v[c]]);
      halves[e[c]].value += h.value;
      halves[e[c]].scale += h.scale;
    }
  }
}

/// Length of the new diagonal pq of a Euclidean diamond: unfolded at a, |pq|^2 = |pa|^2 +
/// |aq|^2 - 2 |pa| |aq| cos(theta_a in f + theta_a in g).
inline double euclidean_flipped_length(const Diamond_sides& s, int e, const std::vector<double>& l)
{
  auto angle_at_a = [&](double opposite, double side_1, double side_2) {
    // Angle between side_1 and side_2 of a triangle, opposite `opposite`, without cancellation.
    const std::array<double, 3> excess = {0.5 * (side_1 + side_2 - opposite), 0.5 * (opposite + side_2 - side_1),
                                          0.5 * (opposite + side_1 - side_2)};
    return triangle_angles_from_excesses(excess).angle[0];
  };
  const double theta = angle_at_a(l[s.bp], l[s.pa], l[e]) + angle_at_a(l[s.qb], l[s.aq], l[e]);
  const double pa = l[s.pa], aq = l[s.aq];
  // |pq|^2 = (pa - aq)^2 + 4 pa aq sin^2(theta / 2): no cancellation for small theta.
  const double half_sine = std::sin(0.5 * theta);
  return std::sqrt((pa - aq) * (pa - aq) + 4.0 * pa * aq * half_sine * half_sine);
}

/// Ptolemy's relation |pq| |ab| = |pa| |qb| + |aq| |bp|, exact for a cyclic diamond and
/// invariant under vertex scaling.
inline double ptolemy_flipped_length(const Diamond_sides& s, int e, const std::vector<double>& l)
{
  return (l[s.pa] * l[s.qb] + l[s.aq] * l[s.bp]) / l[e];
}

} // namespace internal

/// \brief Vertex scaling on an intrinsic Delaunay triangulation (the default metric): the
/// mesh's own conformal class, flipped to be Delaunay for the scaled lengths at every u
/// (Ptolemy flips), so that every u away from the border has a metric.
///
/// At u0 = 0 the metric is the mesh (made intrinsic Delaunay by Euclidean flips). The
/// metric owns its triangulation (`triangulation()`): the mesh's vertices and border, its
/// interior edges flipped; a flipped edge keeps its id. Border edges never flip, nor do the
/// edges the constructor fixes (the seams). The Jacobian is the cotangent Laplacian of the
/// current triangulation.
///
/// \cgalModels{\ref Metric (one that owns its triangulation)}
class Intrinsic_delaunay_metric
{
public:
  static constexpr const char* name = "intrinsic-delaunay";

  Eigen::VectorXd u0; ///< zero: the mesh itself

  Intrinsic_delaunay_metric() = default;
  explicit Intrinsic_delaunay_metric(const internal::Mesh_index& index, const std::vector<char>& is_fixed_edge = {})
    : u0(Eigen::VectorXd::Zero(index.number_of_vertices())), triangulation_(index),
      base_lengths_(internal::euclidean_edge_lengths(index)),
      is_fixed_(is_fixed_edge.empty() ? std::vector<char>(index.number_of_edges(), 0) : is_fixed_edge),
      in_stack_(index.number_of_edges(), 0)
  {
    const std::vector<double> unit(index.number_of_vertices(), 1.0);
    mesh_flips_ = flip_to_delaunay(unit, Flip_rule::Euclidean);
  }

  double length(int e, double gi, double gj) const { return std::sqrt(gi) * std::sqrt(gj) * base_lengths_[e]; }

  Face_geometry face_geometry(const std::array<int, 3>& e, const std::array<double, 3>& g,
                              const std::array<double, 3>& /* l */) const
  {
    return internal::vertex_scaling_face_geometry({base_lengths_[e[0]], base_lengths_[e[1]], base_lengths_[e[2]]}, g);
  }

  /// Per edge, whether the caller fixed it (the seams): it never flips, and an energy's
  /// development of the metric is cut along it (Energies.h).
  const std::vector<char>& fixed_edges() const { return is_fixed_; }

  /// The current triangulation: the mesh's vertices and border, its interior edges flipped.
  const internal::Mesh_index& triangulation() const { return triangulation_; }

  /// Flips the triangulation to be Delaunay for the factors `g` = exp(u) (Ptolemy flips, the
  /// metric does not change); returns the number of flips. Flips nothing while frozen.
  int make_delaunay(const std::vector<double>& g) { return frozen_ ? 0 : flip_to_delaunay(g, Flip_rule::Ptolemy); }

  /// While frozen the triangulation is kept: the metric is vertex scaling on it (valid where
  /// its faces are triangles), a smooth function of u whose Laplacian keeps its pattern. The
  /// energy optimizers freeze it between the steps where they flip (Curvature_space_optimizer.h).
  void freeze_triangulation(bool frozen) { frozen_ = frozen; }
  bool is_frozen() const { return frozen_; }

  /// Flips made so far, counting those that made the mesh Delaunay: a version number of the
  /// triangulation's connectivity.
  long flips() const { return flips_; }

  std::string summary() const
  {
    return "the mesh's own lengths; " + std::to_string(mesh_flips_) +
           " edges flipped to its intrinsic Delaunay triangulation, " + std::to_string(flips_ - mesh_flips_) +
           " Ptolemy flips since";
  }

private:
  enum class Flip_rule
  {
    Euclidean,
    Ptolemy
  };

  /// Lawson's algorithm: every non-Delaunay flippable edge is flipped and its diamond's four
  /// sides re-examined. A flip that would join a vertex to itself is skipped; the face
  /// validity check of Newton's line search covers what that leaves non-Delaunay.
  int flip_to_delaunay(const std::vector<double>& g, Flip_rule rule)
  {
    internal::Mesh_index& t = triangulation_;
    // Lawson's stack starts with the edges that fail the test; a flip re-examines its
    // diamond's sides one by one.
    internal::accumulate_delaunay_halves(t, base_lengths_, g, halves_);
    stack_.clear();
    for(int e = 0; e < t.number_of_edges(); ++e)
      if(!is_fixed_[e] && t.edge_faces[e][1] >= 0 && !internal::is_delaunay(halves_[e], {}))
      {
        stack_.push_back(e);
        in_stack_[e] = 1;
      }
    int flips = 0;
    while(!stack_.empty())
    {
      const int e = stack_.back();
      stack_.pop_back();
      in_stack_[e] = 0;
      internal::Edge_diamond x;
      if(!internal::edge_diamond(t, e, x))
        continue;
      const internal::Diamond_sides s = internal::diamond_sides(t, x);
      if(s.p == s.q || internal::is_delaunay_edge(s, e, base_lengths_, g))
        continue;
      const double flipped = rule == Flip_rule::Euclidean ? internal::euclidean_flipped_length(s, e, base_lengths_)
                                                          : internal::ptolemy_flipped_length(s, e, base_lengths_);
      if(!(flipped > 0) || !std::isfinite(flipped))
        continue;
      internal::flip_edge(t, e, x);
      base_lengths_[e] = flipped;
      ++flips;
      for(int side : {s.bp, s.pa, s.aq, s.qb})
        if(!in_stack_[side] && !is_fixed_[side] && t.edge_faces[side][1] >= 0)
        {
          stack_.push_back(side);
          in_stack_[side] = 1;
        }
    }
    flips_ += flips;
    return flips;
  }

  internal::Mesh_index triangulation_;
  std::vector<double> base_lengths_; ///< Penner coordinates: lengths at u = 0
  std::vector<char> is_fixed_;
  std::vector<int> stack_;
  std::vector<char> in_stack_;
  std::vector<internal::Delaunay_half> halves_;
  long flips_ = 0;
  int mesh_flips_ = 0;
  bool frozen_ = false;
};

/// The metric of ICM's parameterizers when none is named: the one whose maps came out most
/// conformal with no flipped face on the shared meshes (doc/benchmarks.md).
using Default_metric = Intrinsic_delaunay_metric;

} // namespace ICM

#endif // ICM_METRICS_INTRINSIC_DELAUNAY_METRIC_H
