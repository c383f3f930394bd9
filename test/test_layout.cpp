// The layout stage (layout/): the propagation and harmonic layouts, the unflipping, the global
// overlaps of a layout (Border_overlaps.h) and the packing of several charts into one UV map
// (Chart_packing.h), and into the unit square of a texture (Atlas_packing.h).
//
// Every mesh is built by hand so that the expected answer is known: a disk laid out as itself,
// a strip bent along a spiral (past one turn it lies over itself although no face is flipped),
// polygons with touching, collinear and one-ulp-apart border vertices, and random polygons
// checked against an all-pairs count.

#include "atlas_checks.h"
#include "test_support.h"

#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Dynamic_laplacian.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/layout/Atlas_packing.h>
#include <ICM/layout/Border_overlaps.h>
#include <ICM/layout/Chart_packing.h>
#include <ICM/layout/Layout.h>
#include <ICM/layout/Overlap_removal.h>
#include <ICM/layout/Unflip.h>
#include <ICM/internal/Box_pairs.h>
#include <ICM/internal/Exact_predicates.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/pipeline/Chart_solver.h>
#include <ICM/optimum/Optimal_metric.h>
#include <ICM/cut/Cut_graph.h>
#include <ICM/cut/Cut_mesh.h>
#include <ICM/pipeline/Surface_component.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>
#include <utility>
#include <vector>

namespace {

using ICM::Uv;
using ICM::internal::Mesh_index;

const double pi = 3.14159265358979323846;

/// The index of a planar mesh whose 3D points are its plane points (z = 0).
Mesh_index make_index(const std::vector<Uv>& plane, const std::vector<std::array<int, 3>>& faces)
{
  Mesh_index index;
  for(const Uv& p : plane)
    index.points.push_back({p[0], p[1], 0.0});
  index.faces = faces;
  const ICM::Status status = ICM::internal::build_connectivity(index);
  EXPECT_TRUE(status.ok()) << status.message;
  return index;
}

double signed_area(const Uv& a, const Uv& b, const Uv& c)
{
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

int non_positive_faces(const Mesh_index& index, const std::vector<Uv>& uv)
{
  int count = 0;
  for(const auto& f : index.faces)
    if(!(signed_area(uv[f[0]], uv[f[1]], uv[f[2]]) > 0))
      ++count;
  return count;
}

/// A disk of `rings` rings of `sectors` vertices around a centre, counter-clockwise.
struct Polar_disk
{
  std::vector<Uv> plane;
  std::vector<std::array<int, 3>> faces;
};

Polar_disk polar_disk(int rings, int sectors)
{
  Polar_disk disk;
  disk.plane.push_back({0.0, 0.0});
  for(int r = 1; r <= rings; ++r)
    for(int s = 0; s < sectors; ++s)
    {
      const double angle = 2 * pi * (s + 0.5 * (r % 2)) / sectors;
      disk.plane.push_back({r * std::cos(angle), r * std::sin(angle)});
    }
  auto vertex = [sectors](int r, int s) { return r == 0 ? 0 : 1 + (r - 1) * sectors + (s % sectors); };
  for(int s = 0; s < sectors; ++s)
    disk.faces.push_back({0, vertex(1, s), vertex(1, s + 1)});
  for(int r = 1; r < rings; ++r)
    for(int s = 0; s < sectors; ++s)
    {
      disk.faces.push_back({vertex(r, s), vertex(r + 1, s), vertex(r + 1, s + 1)});
      disk.faces.push_back({vertex(r, s), vertex(r + 1, s + 1), vertex(r, s + 1)});
    }
  // Odd rings are turned by half a sector: the two triangles of each quad must still be
  // positive, which the layout check below confirms.
  return disk;
}

/// A strip of `columns` x `rows` quads, each split in two; vertex (i, j) is j (columns + 1) + i.
/// Faces are counter-clockwise in the (i, j) plane.
struct Strip
{
  int columns, rows;
  int vertex(int i, int j) const { return j * (columns + 1) + i; }
  int column(int v) const { return v % (columns + 1); }

  Mesh_index index() const
  {
    std::vector<Uv> plane;
    for(int j = 0; j <= rows; ++j)
      for(int i = 0; i <= columns; ++i)
        plane.push_back({double(i), double(j)});
    std::vector<std::array<int, 3>> faces;
    for(int j = 0; j < rows; ++j)
      for(int i = 0; i < columns; ++i)
      {
        faces.push_back({vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1)});
        faces.push_back({vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1)});
      }
    return make_index(plane, faces);
  }

  /// The strip wound along a spiral through `total_degrees`: column i at angle
  /// i total / columns, row j at radius 2 + 0.6 angle / 2 pi - 0.5 j. The strip is 1 wide and
  /// climbs 0.6 per turn, so past one turn it lies over its first turn; rows running inwards
  /// keep every face counter-clockwise.
  std::vector<Uv> spiral(double total_degrees) const
  {
    std::vector<Uv> uv((columns + 1) * (rows + 1));
    for(int j = 0; j <= rows; ++j)
      for(int i = 0; i <= columns; ++i)
      {
        const double angle = total_degrees * pi / 180 * i / columns;
        const double radius = 2 + 0.6 * angle / (2 * pi) - 1.0 * j / rows;
        uv[vertex(i, j)] = {radius * std::cos(angle), radius * std::sin(angle)};
      }
    return uv;
  }

  bool is_cap_edge(const Mesh_index& index, int e) const
  {
    const int a = column(index.edges[e][0]), b = column(index.edges[e][1]);
    return a == b && (a == 0 || a == columns);
  }
};

/// A fan of triangles from an extra centre vertex (the last one) to the closed polygon `loop`:
/// a disk whose border is exactly `loop`, whatever the polygon looks like.
Mesh_index fan(const std::vector<Uv>& loop, std::vector<Uv>& uv)
{
  const int n = static_cast<int>(loop.size());
  std::vector<std::array<int, 3>> faces;
  for(int i = 0; i < n; ++i)
    faces.push_back({i, (i + 1) % n, n});
  uv = loop;
  Uv centre{0.0, 0.0};
  for(const Uv& p : loop)
    centre = {centre[0] + p[0] / n, centre[1] + p[1] / n};
  uv.push_back(centre);
  return make_index(uv, faces);
}

/// The ids of the border edges of a fan, edge i running from loop vertex i to i + 1.
std::vector<int> fan_border_edges(const Mesh_index& index)
{
  return index.boundary_loop_edges.at(0);
}

/// All pairs of non-adjacent polygon edges that cross properly, with plain floating point:
/// enough for random points, which are in general position with probability one.
int brute_force_crossings(const std::vector<Uv>& loop)
{
  const int n = static_cast<int>(loop.size());
  auto side = [](const Uv& a, const Uv& b, const Uv& c) {
    const double d = signed_area(a, b, c);
    return (d > 0) - (d < 0);
  };
  int count = 0;
  for(int i = 0; i < n; ++i)
    for(int j = i + 1; j < n; ++j)
    {
      if(j == i + 1 || (i == 0 && j == n - 1))
        continue;
      const Uv &a = loop[i], &b = loop[(i + 1) % n], &c = loop[j], &d = loop[(j + 1) % n];
      if(side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0)
        ++count;
    }
  return count;
}

double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

// ------------------------------------------------------------------------------------------
// Border overlaps

TEST(BorderOverlaps, DiskLaidOutAsItselfHasNone)
{
  const Polar_disk disk = polar_disk(6, 24);
  const Mesh_index index = make_index(disk.plane, disk.faces);
  ASSERT_TRUE(index.is_disk());
  ASSERT_EQ(non_positive_faces(index, disk.plane), 0);

  const ICM::Border_overlaps overlaps = ICM::count_border_overlaps(index, disk.plane);
  EXPECT_EQ(overlaps.crossing_pairs, 0);
  EXPECT_TRUE(overlaps.pairs.empty());
  EXPECT_TRUE(overlaps.empty());
  EXPECT_TRUE(ICM::overlapping_face_pairs(index, disk.plane).empty());
}

TEST(BorderOverlaps, SpiralStripBelowOneTurnHasNone)
{
  const Strip strip{40, 2};
  const Mesh_index index = strip.index();
  for(double degrees : {90.0, 300.0, 350.0})
  {
    const std::vector<Uv> uv = strip.spiral(degrees);
    ASSERT_EQ(non_positive_faces(index, uv), 0) << degrees;
    EXPECT_EQ(ICM::count_border_overlaps(index, uv).crossing_pairs, 0) << degrees;
    EXPECT_TRUE(ICM::overlapping_face_pairs(index, uv).empty()) << degrees;
  }
}

// Past one turn, the start cap (column 0, radii [1, 2]) is crossed by the inner border of the
// second turn (radius 1.6 at 360 degrees) and the end cap by the outer border of the first
// turn (0.6 below the end's outer radius, inside the cap): exactly two pairs, each made of a
// cap edge and a long border edge. The totals avoid a vertex landing on the 360-degree ray.
TEST(BorderOverlaps, SpiralStripPastOneTurnCrossesItself)
{
  const Strip strip{40, 2};
  const Mesh_index index = strip.index();
  for(double degrees : {440.0, 500.0, 610.0, 700.0})
  {
    const std::vector<Uv> uv = strip.spiral(degrees);
    ASSERT_EQ(non_positive_faces(index, uv), 0) << degrees;

    const ICM::Border_overlaps overlaps = ICM::count_border_overlaps(index, uv);
    EXPECT_EQ(overlaps.crossing_pairs, 2) << degrees;
    ASSERT_EQ(overlaps.pairs.size(), 2u);
    for(const auto& pair : overlaps.pairs)
    {
      EXPECT_LT(pair.first, pair.second);
      EXPECT_LT(index.edge_faces[pair.first][1], 0);
      EXPECT_LT(index.edge_faces[pair.second][1], 0);
      EXPECT_NE(strip.is_cap_edge(index, pair.first), strip.is_cap_edge(index, pair.second))
        << degrees << ": edges " << pair.first << ", " << pair.second;
    }
    // The face test sees the same fold, which no flipped face reveals.
    EXPECT_TRUE(ICM::has_overlapping_faces(index, uv, [&] {
      std::vector<int> all(index.number_of_faces());
      for(int f = 0; f < index.number_of_faces(); ++f)
        all[f] = f;
      return all;
    }()));
  }
}

TEST(BorderOverlaps, FaceSubsetOfOneTurnDoesNotOverlap)
{
  const Strip strip{40, 2};
  const Mesh_index index = strip.index();
  const std::vector<Uv> uv = strip.spiral(500.0);
  // Faces are listed column by column per row; keep the columns of the first 300 degrees.
  std::vector<int> first_turn, whole;
  for(int f = 0; f < index.number_of_faces(); ++f)
  {
    whole.push_back(f);
    if(f % (2 * strip.columns) < 2 * 24) // 24 of 40 columns = 300 degrees
      first_turn.push_back(f);
  }
  EXPECT_FALSE(ICM::has_overlapping_faces(index, uv, first_turn));
  EXPECT_TRUE(ICM::has_overlapping_faces(index, uv, whole));
  for(const auto& pair : ICM::overlapping_face_pairs(index, uv, whole))
    EXPECT_LT(pair.first, pair.second);
}

TEST(BorderOverlaps, FoldedInteriorVertexIsAFaceOverlapOnly)
{
  const Polar_disk disk = polar_disk(3, 12);
  const Mesh_index index = make_index(disk.plane, disk.faces);
  std::vector<Uv> uv = disk.plane;
  uv[0] = {1.6, 0.2}; // the centre dragged past its ring: flipped faces, border untouched
  ASSERT_GT(non_positive_faces(index, uv), 0);
  EXPECT_EQ(ICM::count_border_overlaps(index, uv).crossing_pairs, 0);
  EXPECT_FALSE(ICM::overlapping_face_pairs(index, uv).empty());
}

// The overlap removal's shortcut: with every face positive, a simple border means no two
// faces overlap (the degree argument), so the face test is skipped; it must agree with the
// face test wherever no face is flipped, and decline wherever one is.
TEST(OverlapRemoval, PiecesJoinAgainWhereNothingOverlapsAcrossThem)
{
  // A strip of 10 columns, two faces each (faces 2i and 2i + 1 in column i), cut into
  // columns 0-3, column 4 (a sliver of two faces) and columns 5-9.
  using ICM::internal::overlaps::join_pieces_that_do_not_overlap;
  const Strip strip{10, 1};
  const Mesh_index index = strip.index();
  const std::vector<int> cut = [] {
    std::vector<int> piece(20);
    for(int f = 0; f < 20; ++f)
      piece[f] = f < 8 ? 0 : f < 10 ? 1 : 2;
    return piece;
  }();
  auto joined = [&](const std::vector<std::pair<int, int>>& pairs) {
    std::vector<int> piece = cut;
    join_pieces_that_do_not_overlap(index, pairs, piece);
    for(const auto& [f, g] : pairs)
      EXPECT_NE(piece[f], piece[g]) << f << " and " << g << " overlap and share a piece";
    const int pieces = 1 + *std::max_element(piece.begin(), piece.end());
    for(int p = 0; p < pieces; ++p)
      EXPECT_NE(std::find(piece.begin(), piece.end(), p), piece.end()) << "piece numbers are not contiguous";
    for(int f = 1; f < 20; ++f) // joined along the strip: every piece stays a run of columns
      EXPECT_TRUE(piece[f] == piece[f - 1] ||
                  std::find(piece.begin(), piece.begin() + f, piece[f]) == piece.begin() + f);
    return piece;
  };
  // Only the ends overlap: the sliver joins a neighbour, the ends stay apart.
  std::vector<int> piece = joined({{0, 19}});
  EXPECT_EQ(*std::max_element(piece.begin(), piece.end()), 1);
  EXPECT_TRUE(piece[8] == piece[0] || piece[8] == piece[19]);
  // The sliver overlaps the first piece: it can join only the last one.
  piece = joined({{0, 19}, {8, 0}});
  EXPECT_EQ(*std::max_element(piece.begin(), piece.end()), 1);
  EXPECT_EQ(piece[8], piece[19]);
  EXPECT_EQ(piece[9], piece[19]);
  // It overlaps both: nothing joins.
  piece = joined({{0, 19}, {8, 0}, {9, 19}});
  EXPECT_EQ(piece, cut);
  // Nothing overlaps: one piece again.
  piece = joined({});
  EXPECT_EQ(piece, std::vector<int>(20, 0));
}

TEST(BorderOverlaps, InjectiveByItsBorderExactlyWhenNoFacesOverlap)
{
  using ICM::internal::overlaps::is_injective_by_its_border;
  const Polar_disk disk = polar_disk(6, 24);
  const Mesh_index index = make_index(disk.plane, disk.faces);
  EXPECT_TRUE(is_injective_by_its_border(index, disk.plane));
  const Strip strip{40, 2};
  const Mesh_index strip_index = strip.index();
  for(double degrees : {300.0, 350.0, 440.0, 700.0})
  {
    const std::vector<Uv> uv = strip.spiral(degrees);
    EXPECT_EQ(is_injective_by_its_border(strip_index, uv), ICM::overlapping_face_pairs(strip_index, uv).empty())
      << degrees;
  }
  // Interior vertices jittered at random: some layouts flip faces (declined), the others
  // agree with the face test.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int without_flips = 0, declined_with_flips = 0;
  for(int trial = 0; trial < 200; ++trial)
  {
    const double spread = 0.05 + 0.25 * trial / 200.0; // from no flip to many
    auto jitter = [&](std::mt19937& r) { return spread * unit(r); };
    std::vector<Uv> uv = disk.plane;
    for(int v = 0; v < index.number_of_vertices(); ++v)
      if(!index.is_boundary_vertex[v])
        uv[v] = {uv[v][0] + jitter(random), uv[v][1] + jitter(random)};
    const bool injective = is_injective_by_its_border(index, uv);
    if(non_positive_faces(index, uv) == 0)
    {
      ++without_flips;
      EXPECT_EQ(injective, ICM::overlapping_face_pairs(index, uv).empty()) << trial;
    }
    else
      declined_with_flips += !injective;
    EXPECT_TRUE(!injective || ICM::overlapping_face_pairs(index, uv).empty()) << trial;
  }
  EXPECT_GT(without_flips, 10);
  EXPECT_GT(declined_with_flips, 10);
}

// Loop 0 -> 1 -> 2 -> 3 with edge 30 leaving vertex 0 almost along edge 01: a needle at
// vertex 0, one unit long and 1e-12 thin.
TEST(BorderOverlaps, EdgesMeetingAtTheirSharedVertexDoNotCount)
{
  auto count_with = [](double y3) {
    std::vector<Uv> uv;
    const Mesh_index index = fan({{0, 0}, {2, 0}, {2, 1}, {1, y3}}, uv);
    return ICM::count_border_overlaps(index, uv).crossing_pairs;
  };
  EXPECT_EQ(count_with(1e-12), 0);  // 30 and 01 meet only at vertex 0
  EXPECT_EQ(count_with(0.0), 2);    // 30 lies along 01, and 23 ends on it
  EXPECT_EQ(count_with(-1e-12), 1); // 23 crosses 01; 30 leaves below it

  // A single triangle: three border edges, every pair sharing a vertex.
  const Mesh_index triangle = make_index({{0, 0}, {1, 0}, {0, 1}}, {{0, 1, 2}});
  EXPECT_EQ(ICM::count_border_overlaps(triangle, {{0, 0}, {1, 0}, {0, 1}}).crossing_pairs, 0);
}

TEST(BorderOverlaps, EdgesSharingAVertexCountWhenCollinearAndOverlapping)
{
  const Mesh_index triangle = make_index({{0, 0}, {1, 0}, {0, 1}}, {{0, 1, 2}});
  // Flattened with vertex 2 between 0 and 1: edge 01 overlaps both 02 and 12, which meet
  // each other only at vertex 2, where they leave in opposite directions.
  const ICM::Border_overlaps between = ICM::count_border_overlaps(triangle, {{0, 0}, {2, 0}, {1, 0}});
  EXPECT_EQ(between.crossing_pairs, 2);
  // Flattened with vertex 2 beyond vertex 1: 02 overlaps 01 and 12; 01 and 12 only touch.
  const ICM::Border_overlaps beyond = ICM::count_border_overlaps(triangle, {{0, 0}, {2, 0}, {3, 0}});
  EXPECT_EQ(beyond.crossing_pairs, 2);
}

// Loop 0 -> 1 -> 2 -> 3 -> 4 with vertex 3 on, just above, or just below edge 01, and the
// edges 23 and 34 above that edge: they touch it, miss it by one ulp, or cross it.
TEST(BorderOverlaps, TouchingIsDecidedExactly)
{
  auto count_with = [](double y3) {
    std::vector<Uv> uv;
    const Mesh_index index = fan({{0, 0}, {3, 1}, {3, 4}, {1.5, y3}, {0, 4}}, uv);
    return ICM::count_border_overlaps(index, uv).crossing_pairs;
  };
  EXPECT_EQ(count_with(0.5), 2);                      // on the edge: touches
  EXPECT_EQ(count_with(std::nextafter(0.5, 1.0)), 0); // one ulp above: clear
  EXPECT_EQ(count_with(std::nextafter(0.5, 0.0)), 2); // one ulp below: crosses
}

TEST(BorderOverlaps, DistinctVerticesAtOneUvOverlap)
{
  // A square with vertex 3 put on top of vertex 1. The two pairs of edges without a common
  // vertex (01, 23) and (12, 30) meet at that point; edges 12 and 23 now run over one
  // segment, and so do 30 and 01: four pairs.
  std::vector<Uv> uv;
  const Mesh_index index = fan({{0, 0}, {1, 0}, {1, 1}, {1, 0}}, uv);
  const ICM::Border_overlaps overlaps = ICM::count_border_overlaps(index, uv);
  EXPECT_EQ(overlaps.crossing_pairs, 4);
}

TEST(BorderOverlaps, MatchesAllPairsOnRandomPolygons)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for(int n : {5, 40, 300})
  {
    std::vector<Uv> loop(n);
    for(Uv& p : loop)
      p = {coordinate(random), coordinate(random)};
    std::vector<Uv> uv;
    const Mesh_index index = fan(loop, uv);
    const ICM::Border_overlaps overlaps = ICM::count_border_overlaps(index, uv);
    EXPECT_EQ(overlaps.crossing_pairs, brute_force_crossings(loop)) << n;
    EXPECT_TRUE(std::is_sorted(overlaps.pairs.begin(), overlaps.pairs.end()));
    EXPECT_TRUE(std::adjacent_find(overlaps.pairs.begin(), overlaps.pairs.end()) == overlaps.pairs.end());
  }
}

TEST(BorderOverlaps, SeveralBoundaryLoopsAreCheckedTogether)
{
  // An annulus: the inner loop pushed outside the outer one crosses it.
  const int sectors = 16;
  std::vector<Uv> plane;
  for(int r = 1; r <= 2; ++r)
    for(int s = 0; s < sectors; ++s)
      plane.push_back({r * std::cos(2 * pi * s / sectors), r * std::sin(2 * pi * s / sectors)});
  std::vector<std::array<int, 3>> faces;
  for(int s = 0; s < sectors; ++s)
  {
    const int a = s, b = (s + 1) % sectors, c = sectors + s, d = sectors + (s + 1) % sectors;
    faces.push_back({a, c, d});
    faces.push_back({a, d, b});
  }
  const Mesh_index index = make_index(plane, faces);
  ASSERT_EQ(index.number_of_boundary_loops(), 2);
  EXPECT_EQ(ICM::count_border_overlaps(index, plane).crossing_pairs, 0);

  std::vector<Uv> shifted = plane;
  for(int s = 0; s < sectors; ++s)
    shifted[s][0] += 2.5; // the inner circle now straddles the outer one's right side
  EXPECT_GT(ICM::count_border_overlaps(index, shifted).crossing_pairs, 0);
}

TEST(BorderOverlaps, RejectsBadInput)
{
  const Mesh_index triangle = make_index({{0, 0}, {1, 0}, {0, 1}}, {{0, 1, 2}});
  EXPECT_THROW(ICM::count_border_overlaps(triangle, {{0, 0}, {1, 0}}), std::invalid_argument);
  EXPECT_THROW(ICM::count_border_overlaps(triangle, {{0, 0}, {1, 0}, {0, std::nan("")}}), std::invalid_argument);
  EXPECT_THROW(ICM::overlapping_face_pairs(triangle, {{0, 0}, {1, 0}, {0, 1}}, {3}), std::invalid_argument);
}

namespace {

/// The sign of (q - p) x (r - p) in GMP's rationals, which hold every double exactly.
int exact_orientation(const Uv& p, const Uv& q, const Uv& r)
{
  const mpq_class d = (mpq_class(q[0]) - mpq_class(p[0])) * (mpq_class(r[1]) - mpq_class(p[1])) -
                      (mpq_class(q[1]) - mpq_class(p[1])) * (mpq_class(r[0]) - mpq_class(p[0]));
  return sgn(d);
}

} // namespace

// Points on a line and one ulp off it, at unit size and at 1e-200 and 1e+200: the filter
// cannot decide these, the expansion arithmetic must. Every answer against GMP's rationals.
TEST(ExactPredicates, OrientationAgreesWithExactArithmeticOnNearlyCollinearPoints)
{
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int collinear = 0, rounded_wrong = 0;
  for(double scale : {1.0, 1e-200, 1e200, 3.0e-5})
    for(int trial = 0; trial < 4000; ++trial)
    {
      const Uv p = {scale * unit(random), scale * unit(random)};
      const Uv q = {scale * unit(random), scale * unit(random)};
      const double t = trial % 4 == 0 ? 0.5 : unit(random) * 3; // midpoints are often exact
      Uv r = {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])};
      if(trial % 3 == 1)
        r[1] = std::nextafter(r[1], HUGE_VAL);
      else if(trial % 3 == 2)
        r[0] = std::nextafter(r[0], -HUGE_VAL);
      const int expected = exact_orientation(p, q, r);
      ASSERT_EQ(ICM::internal::orientation(p, q, r), expected) << "scale " << scale << " trial " << trial;
      ASSERT_EQ(ICM::internal::orientation(q, p, r), -expected);
      const double rounded = ICM::internal::twice_signed_area(p, q, r);
      collinear += expected == 0;
      rounded_wrong += (rounded > 0) - (rounded < 0) != expected;
    }
  EXPECT_GT(collinear, 100);      // the exactly collinear case occurs,
  EXPECT_GT(rounded_wrong, 1000); // and the rounded determinant gets many cases wrong
}

TEST(ExactPredicates, OrientationOfRandomAndExtremePoints)
{
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for(int trial = 0; trial < 20000; ++trial)
  {
    const Uv p = {unit(random), unit(random)}, q = {unit(random), unit(random)}, r = {unit(random), unit(random)};
    ASSERT_EQ(ICM::internal::orientation(p, q, r), exact_orientation(p, q, r));
  }
  // Coordinates whose differences overflow a double, and points spread over 600 decades.
  const double big = 1.7e308;
  EXPECT_EQ(ICM::internal::orientation({-big, -big}, {big, -big}, {0, big}), 1);
  EXPECT_EQ(ICM::internal::orientation({-big, -big}, {big, big}, {0, 0}), 0);
  EXPECT_EQ(ICM::internal::orientation({1e-300, 0}, {1e300, 0}, {1, 1e-300}), 1);
  EXPECT_EQ(ICM::internal::orientation({0, 0}, {1, 0}, {2, 0}), 0);
  EXPECT_EQ(ICM::internal::orientation({0, 0}, {0, 0}, {2, 3}), 0);
}

// The box tree's pairs are exactly the pairs an all-pairs test finds: random boxes, flat
// and point boxes (axis-parallel edges, vertices), boxes that only touch, duplicates, and
// clusters a millionfold smaller than the rest.
TEST(BoxPairs, TreeFindsExactlyTheMeetingPairs)
{
  using ICM::internal::Box2;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for(int n : {0, 1, 2, 9, 17, 300, 2000})
  {
    std::vector<Box2> boxes;
    for(int i = 0; i < n; ++i)
    {
      const double size = (i % 5 == 0) ? 1e-6 : 0.05;
      const Uv corner =
        i % 5 == 0 ? Uv{0.5 + 1e-4 * unit(random), 0.5 + 1e-4 * unit(random)} : Uv{unit(random), unit(random)};
      Box2 box = Box2::around(corner);
      box.extend(
        Uv{corner[0] + (i % 7 == 1 ? 0.0 : size * unit(random)), corner[1] + (i % 7 == 2 ? 0.0 : size * unit(random))});
      boxes.push_back(box);
      if(i % 11 == 3)
        boxes.push_back(box); // a duplicate
      if(i % 13 == 4)
        boxes.push_back({{box.high[0], box.low[1]}, {box.high[0] + 0.01, box.high[1]}}); // touches
    }
    std::vector<std::pair<int, int>> expected, found;
    for(int i = 0; i < static_cast<int>(boxes.size()); ++i)
      for(int j = i + 1; j < static_cast<int>(boxes.size()); ++j)
        if(boxes[i].meets(boxes[j]))
          expected.emplace_back(i, j);
    ICM::internal::Box_tree(boxes).for_each_meeting_pair([&](int i, int j) {
      found.emplace_back(i, j);
      return true;
    });
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, expected) << n << " boxes";
    if(expected.size() > 1)
    {
      int visits = 0;
      ICM::internal::Box_tree(boxes).for_each_meeting_pair([&](int, int) { return ++visits < 2; });
      EXPECT_EQ(visits, 2) << "stopped at the second pair";
    }
  }
}

// Not a pass/fail figure: prints how long a 100k-edge border takes (see the report).
TEST(BorderOverlaps, LargeCircleBorderTiming)
{
  const int n = 100000;
  std::vector<Uv> loop(n);
  for(int i = 0; i < n; ++i)
    loop[i] = {std::cos(2 * pi * i / n), std::sin(2 * pi * i / n)};
  std::vector<Uv> uv;
  const Mesh_index index = fan(loop, uv);
  ASSERT_EQ(static_cast<int>(fan_border_edges(index).size()), n);

  const auto start = std::chrono::steady_clock::now();
  const ICM::Border_overlaps overlaps = ICM::count_border_overlaps(index, uv);
  const double seconds = seconds_since(start);
  EXPECT_EQ(overlaps.crossing_pairs, 0);

  // A square of the same number of edges: its sides' boxes are flat and share one abscissa
  // (or ordinate) along a whole side, the case a sweep over one axis makes quadratic.
  std::vector<Uv> square(n);
  for(int i = 0; i < n; ++i)
  {
    const int side = 4 * i / n;
    const double t = 4.0 * i / n - side;
    square[i] = side == 0 ? Uv{t, 0} : side == 1 ? Uv{1, t} : side == 2 ? Uv{1 - t, 1} : Uv{0, 1 - t};
  }
  std::vector<Uv> square_uv;
  const Mesh_index square_index = fan(square, square_uv);
  const auto start_square = std::chrono::steady_clock::now();
  EXPECT_EQ(ICM::count_border_overlaps(square_index, square_uv).crossing_pairs, 0);
  const double seconds_square = seconds_since(start_square);

  // The same circle with a slit folded over: one vertex pushed across the far side.
  std::vector<Uv> folded = uv;
  folded[0] = {-1.5, 0.0};
  const auto start_folded = std::chrono::steady_clock::now();
  const int folded_pairs = ICM::count_border_overlaps(index, folded).crossing_pairs;
  const double seconds_folded = seconds_since(start_folded);
  EXPECT_EQ(folded_pairs, 2); // its two long edges cross the circle's left side once each

  // Faces of a 100k-face disk (the fan above would make every box a candidate pair).
  const Polar_disk disk = polar_disk(100, 500);
  const Mesh_index disk_index = make_index(disk.plane, disk.faces);
  const auto start_faces = std::chrono::steady_clock::now();
  const bool faces_overlap = !ICM::overlapping_face_pairs(disk_index, disk.plane).empty();
  const double seconds_faces = seconds_since(start_faces);
  EXPECT_FALSE(faces_overlap);

  std::cout << "[ timing ] count_border_overlaps, " << n << " border edges: " << seconds * 1e3
            << " ms (folded: " << seconds_folded * 1e3 << " ms, square: " << seconds_square * 1e3
            << " ms); overlapping_face_pairs, " << disk_index.number_of_faces() << " faces: " << seconds_faces * 1e3
            << " ms\n";
  RecordProperty("border_overlaps_100k_ms", static_cast<int>(seconds * 1e3));
}

// ------------------------------------------------------------------------------------------
// Chart packing

namespace {

bool boxes_apart(const ICM::Chart_box& a, const ICM::Chart_box& b, double gap)
{
  const double slack = 1e-9 * (1 + gap);
  return a[2] + gap <= b[0] + slack || b[2] + gap <= a[0] + slack || a[3] + gap <= b[1] + slack ||
         b[3] + gap <= a[1] + slack;
}

/// Checks the contract of a packing: sizes kept, boxes a gap apart, extent from (0, 0).
void expect_valid_packing(const std::vector<ICM::Chart_box>& boxes, const ICM::Chart_packing& packing)
{
  ASSERT_EQ(packing.placements.size(), boxes.size());
  std::vector<ICM::Chart_box> placed;
  double xmin = HUGE_VAL, ymin = HUGE_VAL, xmax = -HUGE_VAL, ymax = -HUGE_VAL;
  for(std::size_t i = 0; i < boxes.size(); ++i)
  {
    if(ICM::is_empty_box(boxes[i]))
      continue;
    const ICM::Chart_box p = ICM::placed_box(boxes[i], packing.placements[i]);
    const double w = boxes[i][2] - boxes[i][0], h = boxes[i][3] - boxes[i][1];
    const double pw = p[2] - p[0], ph = p[3] - p[1];
    const double tolerance = 1e-9 * (1 + std::max(w, h));
    if(packing.placements[i].rotated)
    {
      EXPECT_NEAR(pw, h, tolerance);
      EXPECT_NEAR(ph, w, tolerance);
    }
    else
    {
      EXPECT_NEAR(pw, w, tolerance);
      EXPECT_NEAR(ph, h, tolerance);
    }
    xmin = std::min(xmin, p[0]);
    ymin = std::min(ymin, p[1]);
    xmax = std::max(xmax, p[2]);
    ymax = std::max(ymax, p[3]);
    placed.push_back(p);
  }
  for(std::size_t i = 0; i < placed.size(); ++i)
    for(std::size_t j = i + 1; j < placed.size(); ++j)
      EXPECT_TRUE(boxes_apart(placed[i], placed[j], packing.gap)) << i << " " << j;
  if(!placed.empty())
  {
    EXPECT_NEAR(xmin, 0.0, 1e-9 * (1 + packing.width));
    EXPECT_NEAR(ymin, 0.0, 1e-9 * (1 + packing.height));
    EXPECT_NEAR(xmax, packing.width, 1e-9 * (1 + packing.width));
    EXPECT_NEAR(ymax, packing.height, 1e-9 * (1 + packing.height));
  }
}

std::vector<ICM::Chart_box> random_boxes(int n, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> position(-50.0, 50.0), size(0.1, 10.0);
  std::vector<ICM::Chart_box> boxes;
  for(int i = 0; i < n; ++i)
  {
    const double x = position(random), y = position(random);
    boxes.push_back({x, y, x + size(random), y + size(random)});
  }
  return boxes;
}

double aspect(const ICM::Chart_packing& packing)
{
  return std::max(packing.width, packing.height) / std::min(packing.width, packing.height);
}

} // namespace

TEST(ChartPacking, RandomBoxesDoNotOverlapAndKeepTheirSize)
{
  for(unsigned seed : {1u, 2u, 3u})
  {
    const std::vector<ICM::Chart_box> boxes = random_boxes(200, seed);
    const ICM::Chart_packing packing = ICM::shelf_pack_charts(boxes);
    expect_valid_packing(boxes, packing);
    double largest = 0, area = 0;
    for(const auto& b : boxes)
    {
      largest = std::max({largest, b[2] - b[0], b[3] - b[1]});
      area += (b[2] - b[0]) * (b[3] - b[1]);
    }
    EXPECT_DOUBLE_EQ(packing.gap, 0.02 * largest);
    for(const auto& placement : packing.placements)
      EXPECT_FALSE(placement.rotated);
    // Shelves of random heights waste space, but not most of it.
    EXPECT_LT(packing.width * packing.height, 2.0 * area);
    EXPECT_LE(aspect(packing), 1.5);
  }
}

TEST(ChartPacking, ManyEqualBoxesPackIntoASquare)
{
  for(int n = 2; n <= 120; ++n)
  {
    const std::vector<ICM::Chart_box> boxes(n, ICM::Chart_box{3, 4, 5, 5}); // 2 x 1 each
    const ICM::Chart_packing packing = ICM::shelf_pack_charts(boxes);
    expect_valid_packing(boxes, packing);
    EXPECT_LE(aspect(packing), 3.0) << n << " boxes: " << packing.width << " x " << packing.height;
  }
  const std::vector<ICM::Chart_box> squares(100, ICM::Chart_box{0, 0, 1, 1});
  const ICM::Chart_packing packing = ICM::shelf_pack_charts(squares);
  EXPECT_LE(aspect(packing), 1.25);
}

TEST(ChartPacking, ShelfPackOffsetsTranslateInInputOrder)
{
  const std::vector<ICM::Chart_box> boxes = random_boxes(30, 11);
  const std::vector<Uv> offsets = ICM::shelf_pack(boxes);
  const ICM::Chart_packing packing = ICM::shelf_pack_charts(boxes);
  ASSERT_EQ(offsets.size(), boxes.size());
  for(std::size_t i = 0; i < boxes.size(); ++i)
  {
    EXPECT_EQ(offsets[i], packing.placements[i].offset);
    EXPECT_EQ(packing.placements[i]({1.0, 2.0}), (Uv{1.0 + offsets[i][0], 2.0 + offsets[i][1]}));
  }
  // Tallest first: the tallest box sits on the first shelf, at the origin.
  std::size_t tallest = 0;
  for(std::size_t i = 0; i < boxes.size(); ++i)
    if(boxes[i][3] - boxes[i][1] > boxes[tallest][3] - boxes[tallest][1])
      tallest = i;
  EXPECT_NEAR(boxes[tallest][0] + offsets[tallest][0], 0.0, 1e-12);
  EXPECT_NEAR(boxes[tallest][1] + offsets[tallest][1], 0.0, 1e-12);
}

TEST(ChartPacking, RotationLaysTallChartsFlatWhenItHelps)
{
  // Ten wide and ten tall boxes: turning the tall ones makes all twenty alike.
  std::vector<ICM::Chart_box> boxes;
  for(int i = 0; i < 10; ++i)
  {
    boxes.push_back({0, 0, 5, 1});
    boxes.push_back({0, 0, 1, 5});
  }
  ICM::Shelf_packing_options options;
  const ICM::Chart_packing plain = ICM::shelf_pack_charts(boxes, options);
  options.allow_rotation = true;
  const ICM::Chart_packing turned = ICM::shelf_pack_charts(boxes, options);
  expect_valid_packing(boxes, turned);
  EXPECT_LE(std::max(turned.width, turned.height), std::max(plain.width, plain.height));
  int rotated = 0;
  for(const auto& placement : turned.placements)
    rotated += placement.rotated;
  EXPECT_TRUE(rotated == 0 || rotated == 10) << rotated;

  // Equal squares never gain from a turn, so none is turned.
  const std::vector<ICM::Chart_box> squares(9, ICM::Chart_box{0, 0, 1, 1});
  for(const auto& placement : ICM::shelf_pack_charts(squares, options).placements)
    EXPECT_FALSE(placement.rotated);
}

TEST(ChartPacking, PackChartsMovesPointSetsRigidly)
{
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  std::vector<std::vector<Uv>> charts(12);
  for(std::size_t c = 0; c < charts.size(); ++c)
    for(int k = 0; k < 20; ++k)
      // Charts of different sizes, all around the origin, many tall: they overlap at first.
      charts[c].push_back({0.3 * (c + 1) * coordinate(random), coordinate(random) * (1 + c % 3)});
  charts.push_back({}); // an empty chart stays empty and does not disturb the others
  const std::vector<std::vector<Uv>> original = charts;

  ICM::Shelf_packing_options options;
  options.allow_rotation = true;
  const ICM::Chart_packing packing = ICM::pack_charts(charts, options);

  std::vector<ICM::Chart_box> before;
  for(const auto& chart : original)
    before.push_back(ICM::chart_bounding_box(chart));
  expect_valid_packing(before, packing);
  ASSERT_EQ(charts.size(), original.size());
  EXPECT_TRUE(charts.back().empty());
  for(std::size_t c = 0; c + 1 < charts.size(); ++c)
  {
    ASSERT_EQ(charts[c].size(), original[c].size());
    for(std::size_t k = 1; k < charts[c].size(); ++k)
    {
      const double d_before = std::hypot(original[c][k][0] - original[c][0][0], original[c][k][1] - original[c][0][1]);
      const double d_after = std::hypot(charts[c][k][0] - charts[c][0][0], charts[c][k][1] - charts[c][0][1]);
      EXPECT_NEAR(d_after, d_before, 1e-12 * (1 + d_before));
      // Orientation is kept too: a quarter turn is a rotation, not a reflection.
      if(k >= 2)
      {
        EXPECT_EQ(signed_area(original[c][0], original[c][1], original[c][k]) > 0,
                  signed_area(charts[c][0], charts[c][1], charts[c][k]) > 0);
      }
    }
    const ICM::Chart_box now = ICM::chart_bounding_box(charts[c]);
    const ICM::Chart_box expected = ICM::placed_box(before[c], packing.placements[c]);
    for(int k = 0; k < 4; ++k)
      EXPECT_NEAR(now[k], expected[k], 1e-12 * (1 + std::abs(expected[k])));
  }
}

TEST(ChartPacking, EdgeCases)
{
  EXPECT_TRUE(ICM::shelf_pack({}).empty());
  const ICM::Chart_packing one = ICM::shelf_pack_charts({{2, 3, 4, 7}});
  EXPECT_EQ(one.placements[0].offset, (Uv{-2.0, -3.0}));
  EXPECT_DOUBLE_EQ(one.width, 2.0);
  EXPECT_DOUBLE_EQ(one.height, 4.0);

  // Single-point charts still end up apart.
  const std::vector<ICM::Chart_box> points(4, ICM::Chart_box{1, 1, 1, 1});
  const ICM::Chart_packing packed_points = ICM::shelf_pack_charts(points);
  EXPECT_GT(packed_points.gap, 0.0);
  expect_valid_packing(points, packed_points);

  EXPECT_THROW(ICM::shelf_pack({{0, 0, std::nan(""), 1}}), std::invalid_argument);
  EXPECT_THROW(ICM::shelf_pack({{0, 0, HUGE_VAL, 1}}), std::invalid_argument);
}

// Two copies of a disk, laid out on top of each other in one UV map, overlap; packed, they
// do not: the two headers together check an atlas.
TEST(ChartPacking, PackedChartsHaveNoBorderOverlap)
{
  const Polar_disk disk = polar_disk(4, 16);
  const int nv = static_cast<int>(disk.plane.size());
  std::vector<Uv> plane = disk.plane;
  plane.insert(plane.end(), disk.plane.begin(), disk.plane.end());
  std::vector<std::array<int, 3>> faces = disk.faces;
  for(const auto& f : disk.faces)
    faces.push_back({f[0] + nv, f[1] + nv, f[2] + nv});
  const Mesh_index index = make_index(plane, faces);
  ASSERT_EQ(index.number_of_boundary_loops(), 2);

  std::vector<Uv> uv = plane;
  uv.resize(nv);
  std::vector<std::vector<Uv>> charts{uv, uv};
  for(Uv& p : charts[1])
    p = {0.5 * p[0] + 0.3, 0.5 * p[1]}; // the second chart smaller, inside the first
  std::vector<Uv> stacked = charts[0];
  stacked.insert(stacked.end(), charts[1].begin(), charts[1].end());
  EXPECT_TRUE(ICM::count_border_overlaps(index, stacked).empty());   // nested: borders apart
  EXPECT_FALSE(ICM::overlapping_face_pairs(index, stacked).empty()); // ... but faces overlap

  ICM::pack_charts(charts);
  std::vector<Uv> packed = charts[0];
  packed.insert(packed.end(), charts[1].begin(), charts[1].end());
  EXPECT_TRUE(ICM::count_border_overlaps(index, packed).empty());
  EXPECT_TRUE(ICM::overlapping_face_pairs(index, packed).empty());

  std::vector<Uv> shifted = stacked; // half way across: the borders now cross
  for(int v = nv; v < 2 * nv; ++v)
    shifted[v][0] += 3.0;
  EXPECT_GT(ICM::count_border_overlaps(index, shifted).crossing_pairs, 0);
}

TEST(Layout, PropagationAndHarmonicReproduceTheMetric)
{
  const ICM::internal::Mesh_index index = icm_test::index_file("three_peaks.off");
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(index);
  ICM::Inverse_curvature_map<> solver(index, metric, icm_test::interior_of(index));
  Eigen::VectorXd u;
  ASSERT_TRUE(ICM::free_boundary_optimum(solver, metric, u).converged);
  Eigen::VectorXd k;
  std::vector<double> w;
  solver.curvature_map().evaluate(u, k, &w);
  const std::vector<double> lengths = solver.curvature_map().lengths();

  const std::vector<ICM::Uv> propagated =
    ICM::layout_by_propagation(index, lengths, solver.curvature_map().face_angles());
  const ICM::Layout_check a = ICM::check_layout(index, lengths, propagated);
  EXPECT_EQ(a.flipped_faces, 0);
  EXPECT_LT(a.max_relative_length_error, 1e-8);

  std::vector<ICM::Uv> harmonic;
  std::string message;
  ASSERT_TRUE(ICM::layout_harmonic(index, lengths, k, w, solver.laplacian(), harmonic, message)) << message;
  const ICM::Layout_check b = ICM::check_layout(index, lengths, harmonic);
  EXPECT_EQ(b.flipped_faces, 0);
  EXPECT_LT(b.max_relative_length_error, 1e-8);

  // That layout refined Newton's last factorization; a fresh factorization of the final
  // Laplacian gives the same coordinates.
  ASSERT_TRUE(solver.laplacian().has_factorization());
  ICM::Dynamic_laplacian<> fresh(index, icm_test::interior_of(index));
  ASSERT_FALSE(fresh.has_factorization());
  std::vector<ICM::Uv> direct;
  ASSERT_TRUE(ICM::layout_harmonic(index, lengths, k, w, fresh, direct, message)) << message;
  ASSERT_TRUE(fresh.has_factorization());
  double largest_difference = 0, extent = 0;
  for(int v = 0; v < index.number_of_vertices(); ++v)
    for(int c = 0; c < 2; ++c)
    {
      largest_difference = std::max(largest_difference, std::abs(direct[v][c] - harmonic[v][c]));
      extent = std::max(extent, std::abs(direct[v][c]));
    }
  EXPECT_LT(largest_difference, 1e-12 * extent);
}

TEST(Layout, CutChartLaidOutHarmonicallyOrByPropagationReproducesTheMetric)
{
  // sphere966 with four cones of free angle, cut through them: both layouts of the cut disk
  // keep the metric's lengths and give the two sides of every seam one length.
  const ICM::internal::Mesh_index index = icm_test::index_file("sphere966.off");
  std::vector<char> is_cone(index.number_of_vertices(), 0);
  for(int v : {0, 231, 462, 693})
    is_cone[v] = 1;
  const std::vector<double> free_angles(index.number_of_vertices(), std::nan(""));
  ICM::internal::Chart_problem problem = ICM::internal::singular_set_problem(index, is_cone, free_angles);
  const ICM::Cut_graph_result graph = ICM::cut_graph(index, is_cone);
  ASSERT_TRUE(graph.ok()) << graph.status.message;
  const ICM::Cut_mesh cut = ICM::cut_mesh(index, graph.is_seam);
  ASSERT_TRUE(cut.ok()) << cut.status.message;
  problem.seams = graph.is_seam;
  problem.cut = &cut;
  for(ICM::Layout_method layout : {ICM::Layout_method::Harmonic, ICM::Layout_method::Propagation})
  {
    ICM::internal::Chart_method method;
    method.layout = layout;
    ICM::Chart_solve_report report;
    std::vector<ICM::Uv> uv;
    const ICM::Status status = ICM::internal::solve_chart<ICM::Intrinsic_delaunay_metric, ICM::Default_sparse_solver>(
      problem, ICM::Chart_options(), method, ICM::Curvature_entropy(), report, uv);
    ASSERT_TRUE(status.ok()) << status.message;
    EXPECT_EQ(report.layout, layout == ICM::Layout_method::Harmonic ? "harmonic" : "propagation");
    EXPECT_EQ(report.metric, std::string("intrinsic-delaunay"));
    EXPECT_EQ(report.flipped_faces, 0);
    EXPECT_LT(report.max_layout_length_error, 1e-8);
    EXPECT_LT(report.seam_length_error, 1e-8);
    EXPECT_EQ(uv.size(), cut.surface_vertex.size());
  }
}

TEST(Layout, EquilateralGridLaysOutAsItself)
{
  // A planar mesh reproduced exactly by its packing is already flat: the optimum is u0
  // and the layout is the input up to a rigid motion.
  const ICM::internal::Mesh_index grid = icm_test::equilateral_grid(5);
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(grid);
  Eigen::VectorXd u;
  const ICM::Newton_report report = ICM::free_boundary_optimum(grid, metric, ICM::boundary_singular_set(grid), u);
  ASSERT_TRUE(report.converged);
  EXPECT_EQ(report.iterations, 0);
  ICM::Curvature_map<> curvature(grid, metric);
  const std::vector<double>& lengths = curvature.compute_lengths(u);
  const std::vector<ICM::Uv> uv = ICM::layout_by_propagation(grid, lengths, curvature.face_angles());
  for(int i = 0; i < grid.number_of_vertices(); ++i)
    for(int j = i + 1; j < grid.number_of_vertices(); j += 5)
    {
      const auto& p = grid.points[i];
      const auto& q = grid.points[j];
      EXPECT_NEAR(std::hypot(uv[i][0] - uv[j][0], uv[i][1] - uv[j][1]), std::hypot(p[0] - q[0], p[1] - q[1]), 1e-12);
    }
}

TEST(Layout, LongStripLaysOutAsItselfInLinearTime)
{
  // 6000 faces in a row: 3000 hops from the central root to either end, where the error
  // estimate has overflowed to infinity long before. The layout is still every face once
  // (a strip of 1 x 550 squares used to offer its faces again without end) and isometric.
  const ICM::internal::Mesh_index strip = icm_test::equilateral_strip(3000);
  const ICM::Circle_packing_metric metric = ICM::initial_circle_packing_metric(strip);
  ICM::Curvature_map<> curvature(strip, metric);
  const std::vector<double>& lengths = curvature.compute_lengths(metric.u0);
  const std::vector<ICM::Uv> uv = ICM::layout_by_propagation(strip, lengths, curvature.face_angles());
  const ICM::Layout_check check = ICM::check_layout(strip, lengths, uv);
  EXPECT_EQ(check.flipped_faces, 0);
  EXPECT_LT(check.max_relative_length_error, 1e-9);
  const int last = strip.number_of_vertices() - 1;
  EXPECT_NEAR(std::hypot(uv[last][0] - uv[0][0], uv[last][1] - uv[0][1]),
              std::hypot(strip.points[last][0] - strip.points[0][0], strip.points[last][1] - strip.points[0][1]),
              1e-9 * strip.points[last][0]);
}

/// Unflips `uv` with vertex 0 alone movable; returns how many moves were made.
int unflip_moving_vertex_0(const ICM::internal::Mesh_index& index, std::vector<ICM::Uv>& uv)
{
  std::vector<char> movable(index.number_of_vertices(), 0);
  movable[0] = 1;
  return ICM::unflip_by_moving_vertices(index, uv, movable);
}

TEST(Unflip, MovesAVertexBackIntoItsRing)
{
  // A hexagon fan whose centre was placed outside the ring: its faces flip; moving the
  // centre alone repairs them.
  ICM::internal::Mesh_index index;
  index.points.push_back({0, 0, 0});
  std::vector<ICM::Uv> uv = {{1.5, 0.2}};
  for(int i = 0; i < 6; ++i)
  {
    index.points.push_back({std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), 0});
    uv.push_back({index.points.back()[0], index.points.back()[1]});
  }
  for(int i = 0; i < 6; ++i)
    index.faces.push_back({0, 1 + i, 1 + (i + 1) % 6});
  ASSERT_TRUE(ICM::internal::build_connectivity(index).ok());
  ASSERT_GT(ICM::count_flipped_faces(index, uv), 0);
  const std::vector<ICM::Uv> ring(uv.begin() + 1, uv.end());
  EXPECT_GE(unflip_moving_vertex_0(index, uv), 1);
  EXPECT_EQ(ICM::count_flipped_faces(index, uv), 0);
  EXPECT_TRUE(std::equal(ring.begin(), ring.end(), uv.begin() + 1)); // only the centre moved
  // To where the star is most conformal: the ring is the mesh's own, so the centre.
  EXPECT_NEAR(uv[0][0], 0.0, 1e-12);
  EXPECT_NEAR(uv[0][1], 0.0, 1e-12);
}

TEST(Unflip, KeepsTheStarAwayFromSlivers)
{
  // An obtuse face (0, 1, 2) whose far corner 0 was drawn just across its long edge, as a
  // mesh face the intrinsic triangulation does not have comes out of a layout. The star of
  // 0 is a square fan; its most conformal position is far from the long edge, and the
  // repaired faces are not slivers.
  ICM::internal::Mesh_index index;
  index.points = {{0, 0.2, 0}, {-1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 1, 0}};
  std::vector<ICM::Uv> uv = {{0, -0.01}, {-1, 0}, {1, 0}, {1, 1}, {-1, 1}};
  index.faces = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};
  ASSERT_TRUE(ICM::internal::build_connectivity(index).ok());
  ASSERT_EQ(ICM::count_flipped_faces(index, uv), 1);
  EXPECT_EQ(unflip_moving_vertex_0(index, uv), 1);
  EXPECT_EQ(ICM::count_flipped_faces(index, uv), 0);
  // The 3D star is the UV ring itself, so its most conformal position is (0, 0.2), where
  // vertex 0 is in 3D and every face is similar to its shape (the first unflipping stopped
  // at twice the distance needed to unflip: y = 0.01, a sliver).
  EXPECT_NEAR(uv[0][0], 0.0, 1e-12);
  EXPECT_NEAR(uv[0][1], 0.2, 1e-12);
}

TEST(Unflip, KeepsABorderVertexNearItsOpenFan)
{
  // A border vertex 0 with an open fan of four faces, drawn above its ring: three faces
  // flip. Moving it down grows every face without end, so the largest smallest area is
  // sought only over the disc around its neighbours; from there it goes to its most
  // conformal position, where it is in 3D (the ring is the mesh's own). Sought over the
  // whole plane, with a move towards the most conformal point that kept half that area, the
  // point sent it to (-1.9, -2.9), 2.5 ring radii below the border, and magnified a face
  // 3.9 times (horse: 30 star radii, 629 times).
  ICM::internal::Mesh_index index;
  index.points = {{0, 0, 0}, {0.65, 0, 0}, {1.05, 0.84, 0}, {0.18, 1.2, 0}, {-0.5, 0.4, 0}, {-0.95, 0, 0}};
  std::vector<ICM::Uv> uv = {{0.5, 1.7}};
  for(int i = 1; i < 6; ++i)
    uv.push_back({index.points[i][0], index.points[i][1]});
  for(int i = 0; i < 4; ++i)
    index.faces.push_back({0, 1 + i, 2 + i});
  ASSERT_TRUE(ICM::internal::build_connectivity(index).ok());
  ASSERT_TRUE(index.is_boundary_vertex[0]);
  ASSERT_EQ(ICM::count_flipped_faces(index, uv), 3);
  EXPECT_EQ(unflip_moving_vertex_0(index, uv), 1);
  EXPECT_EQ(ICM::count_flipped_faces(index, uv), 0);
  EXPECT_NEAR(uv[0][0], 0.0, 1e-12);
  EXPECT_NEAR(uv[0][1], 0.0, 1e-12);
}

// ------------------------------------------------------------------------------------------
// Atlas packing

namespace {

std::vector<ICM::Atlas_packer> available_packers()
{
  std::vector<ICM::Atlas_packer> packers = {ICM::Atlas_packer::Shelf};
  if(ICM::atlas_packer_available(ICM::Atlas_packer::Skyline))
    packers.push_back(ICM::Atlas_packer::Skyline);
  return packers;
}

/// A chart of 2 n^2 triangles filling the box [x, x + w] x [y, y + h], counterclockwise.
struct Grid_chart
{
  std::vector<Uv> uv;
  std::vector<std::array<int, 3>> triangles;
};

Grid_chart grid_chart(double x, double y, double w, double h, int n)
{
  Grid_chart chart;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
      chart.uv.push_back({x + w * i / n, y + h * j / n});
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i)
    {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      chart.triangles.push_back({a, b, d});
      chart.triangles.push_back({a, d, c});
    }
  return chart;
}

/// The charts moved by `packing`, as triangles in the atlas.
std::vector<std::vector<icm_test::Uv_triangle>> packed_triangles(const std::vector<Grid_chart>& charts,
                                                                 const ICM::Atlas_packing& packing)
{
  std::vector<std::vector<icm_test::Uv_triangle>> out(charts.size());
  for(std::size_t c = 0; c < charts.size(); ++c)
    for(const auto& t : charts[c].triangles)
    {
      icm_test::Uv_triangle placed;
      for(int k = 0; k < 3; ++k)
      {
        const Uv& p = charts[c].uv[t[k]];
        placed[k] = packing.placements[c]({packing.scale * p[0], packing.scale * p[1]});
      }
      out[c].push_back(placed);
    }
  return out;
}

/// Every triangle inside the padded square, counterclockwise, any two charts `padding`
/// texels apart (triangles and boxes); returns the covered area.
double expect_valid_atlas(const std::vector<std::vector<icm_test::Uv_triangle>>& charts,
                          const ICM::Atlas_options& options)
{
  const double texel = 1.0 / options.size, tolerance = 1e-9;
  double area = 0;
  for(const auto& chart : charts)
  {
    const std::array<double, 4> b = icm_test::box_of(chart);
    EXPECT_GE(std::min(b[0], b[1]), options.padding * texel - tolerance);
    EXPECT_LE(std::max(b[2], b[3]), 1 - options.padding * texel + tolerance);
    for(const auto& t : chart)
    {
      EXPECT_GT(icm_test::signed_area_of(t), 0.0);
      area += icm_test::signed_area_of(t);
    }
  }
  for(std::size_t i = 0; i < charts.size(); ++i)
    for(std::size_t j = i + 1; j < charts.size(); ++j)
    {
      const double boxes = icm_test::box_distance(icm_test::box_of(charts[i]), icm_test::box_of(charts[j]));
      const double triangles = icm_test::chart_distance(charts[i], charts[j], 2 * options.padding * texel);
      EXPECT_GE(boxes * options.size, options.padding - 1e-6) << i << " " << j;
      EXPECT_GE(triangles * options.size, options.padding - 1e-6) << i << " " << j;
    }
  return area;
}

} // namespace

TEST(AtlasPacking, ChartsFitInTheSquarePaddedApartWithoutFlips)
{
  // Wide, tall and square charts of many sizes: the tall ones are worth a quarter turn.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> side(0.2, 3.0), position(-20, 20);
  std::vector<Grid_chart> charts;
  std::vector<ICM::Chart_box> boxes;
  for(int c = 0; c < 40; ++c)
  {
    const double a = side(random), b = c % 3 == 0 ? a : 4 * side(random);
    const double w = c % 3 == 1 ? b : a, h = c % 3 == 2 ? b : a;
    charts.push_back(grid_chart(position(random), position(random), w, h, 3));
    boxes.push_back(ICM::chart_bounding_box(charts.back().uv));
  }
  for(ICM::Atlas_packer packer : available_packers())
    for(int padding : {0, 2, 8})
    {
      SCOPED_TRACE(std::string(ICM::atlas_packer_name(packer)) + ", padding " + std::to_string(padding));
      ICM::Atlas_options options;
      options.size = 512;
      options.padding = padding;
      options.packer = packer;
      ICM::Atlas_packing packing;
      ASSERT_TRUE(ICM::pack_atlas(boxes, options, packing).ok());
      EXPECT_GT(packing.rotated_charts, 0);
      const auto placed = packed_triangles(charts, packing);
      const double area = expect_valid_atlas(placed, options);
      // One scale: every chart's area is the same multiple of its own.
      double before = 0;
      for(const auto& b : boxes)
        before += (b[2] - b[0]) * (b[3] - b[1]);
      EXPECT_NEAR(area, packing.scale * packing.scale * before, 1e-9);
      std::vector<std::vector<Uv>> uvs;
      std::vector<std::vector<std::array<int, 3>>> triangles;
      for(std::size_t c = 0; c < charts.size(); ++c)
      {
        uvs.push_back({});
        for(const Uv& p : charts[c].uv)
          uvs.back().push_back(packing.placements[c]({packing.scale * p[0], packing.scale * p[1]}));
        triangles.push_back(charts[c].triangles);
      }
      EXPECT_NEAR(ICM::atlas_utilization(uvs, triangles), area, 1e-12);
      // Boxes of random shapes: a packer wastes some of the square, not most of it.
      EXPECT_GT(area, 0.4);
      // Without turns the charts keep their orientation and still fit.
      options.allow_rotation = false;
      ASSERT_TRUE(ICM::pack_atlas(boxes, options, packing).ok());
      EXPECT_EQ(packing.rotated_charts, 0);
      for(const auto& placement : packing.placements)
        EXPECT_FALSE(placement.rotated);
      expect_valid_atlas(packed_triangles(charts, packing), options);
    }
}

TEST(AtlasPacking, OneChartSpansTheSquareWithItsLongerSide)
{
  for(ICM::Atlas_packer packer : available_packers())
    for(const ICM::Chart_box& box :
        {ICM::Chart_box{2, 3, 4, 10}, ICM::Chart_box{-5, 0, 5, 1}, ICM::Chart_box{0, 0, 1, 1}})
    {
      ICM::Atlas_options options;
      options.size = 256;
      options.padding = 5;
      options.packer = packer;
      ICM::Atlas_packing packing;
      ASSERT_TRUE(ICM::pack_atlas({box}, options, packing).ok());
      const ICM::Chart_box scaled{packing.scale * box[0], packing.scale * box[1], packing.scale * box[2],
                                  packing.scale * box[3]};
      const ICM::Chart_box placed = ICM::placed_box(scaled, packing.placements[0]);
      EXPECT_NEAR(std::max(placed[2] - placed[0], placed[3] - placed[1]), (256 - 10) / 256.0, 1e-12);
      EXPECT_NEAR(std::min(placed[0], placed[1]), 5 / 256.0, 1e-12);
    }
}

TEST(AtlasPacking, BadOptionsAndTooManyChartsAreRefusedByName)
{
  const std::vector<ICM::Chart_box> boxes(3, ICM::Chart_box{0, 0, 1, 1});
  ICM::Atlas_packing packing;
  const auto refusal = [&](int size, int padding) {
    ICM::Atlas_options options;
    options.size = size;
    options.padding = padding;
    const ICM::Status status = ICM::pack_atlas(boxes, options, packing);
    EXPECT_EQ(status.code, CGAL::Surface_mesh_parameterization::ERROR_WRONG_PARAMETER);
    return status.message;
  };
  EXPECT_EQ(refusal(0, 4), "option atlas.size = 0: must be >= 1");
  EXPECT_EQ(refusal(-3, 4), "option atlas.size = -3: must be >= 1");
  EXPECT_EQ(refusal(70000, 4), "option atlas.size = 70000: must be <= 65536");
  EXPECT_EQ(refusal(64, -1), "option atlas.padding = -1: must be >= 0");
  EXPECT_EQ(refusal(64, 32),
            "option atlas.padding = 32: must be <= 31 so that a 64-texel square keeps at least one texel inside its "
            "border");
  // With 7 texels of padding a 16-texel square holds one chart of one or two texels, not three.
  EXPECT_EQ(refusal(16, 7),
            "option atlas.padding = 7: 3 charts of one texel each, 7 texels apart, do not fit in a 16 x 16 atlas");
  // The same options through parameterize's own check, before any work.
  ICM::Surface_parameterization_options options;
  options.atlas = ICM::Atlas_options();
  options.atlas->size = 0;
  EXPECT_EQ(ICM::check_options(options).message, "option atlas.size = 0: must be >= 1");
  options.atlas.reset();
  EXPECT_TRUE(ICM::check_options(options).ok());
}
