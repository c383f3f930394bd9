// Tests of ICM/Distortion.h: analytic maps with closed-form measures, counting of flipped and
// degenerate faces, and the FaceGraph front ends agreeing with the flat core.
#include <ICM/measures/Distortion.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Seam_mesh.h>
#include <CGAL/boost/graph/graph_traits_Polyhedron_3.h>
#include <CGAL/boost/graph/properties_Polyhedron_3.h>

#include <boost/property_map/property_map.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point_2 = Kernel::Point_2;
using Point_3 = Kernel::Point_3;
using Surface_mesh = CGAL::Surface_mesh<Point_3>;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;

using Xyz = std::vector<std::array<double, 3>>;
using Uv = std::vector<std::array<double, 2>>;
using Planar = std::array<double, 2>;
using Planar_map = std::function<Planar(const Planar&)>;

const double pi = std::acos(-1.0);
constexpr double tolerance = 1e-9;
constexpr int grid_size = 4; // squares per side

// --- a planar grid placed in general position in 3D ----------------------------------------

struct Grid
{
  std::vector<Planar> vertices;                      // planar coordinates
  std::vector<std::array<std::size_t, 3>> triangles; // counterclockwise in the plane
};

std::size_t grid_vertex(int i, int j, int n)
{
  return static_cast<std::size_t>(j * (n + 1) + i);
}

// n x n unit squares on [0, n]^2, each split along its diagonal (i, j)-(i+1, j+1) into
// A = (i,j) (i+1,j) (i+1,j+1) and B = (i,j) (i+1,j+1) (i,j+1).
Grid make_grid(int n)
{
  Grid grid;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
      grid.vertices.push_back({double(i), double(j)});
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i)
    {
      grid.triangles.push_back({grid_vertex(i, j, n), grid_vertex(i + 1, j, n), grid_vertex(i + 1, j + 1, n)});
      grid.triangles.push_back({grid_vertex(i, j, n), grid_vertex(i + 1, j + 1, n), grid_vertex(i, j + 1, n)});
    }
  return grid;
}

// A fixed rigid motion, so that no face's frame is the plane's own: the measures must not see it.
std::array<double, 3> embed_in_space(const Planar& p)
{
  const double a = 0.3, b = 1.1; // rotation about x by a, then about z by b
  const double x = p[0], y = std::cos(a) * p[1], z = std::sin(a) * p[1];
  return {std::cos(b) * x - std::sin(b) * y + 1.5, std::sin(b) * x + std::cos(b) * y - 2.0, z + 0.25};
}

Planar identity(const Planar& p)
{
  return p;
}

void flatten(const Grid& grid, const Planar_map& uv_of, Xyz& xyz, Uv& uv)
{
  xyz.clear();
  uv.clear();
  for(const auto& t : grid.triangles)
    for(std::size_t v : t)
    {
      xyz.push_back(embed_in_space(grid.vertices[v]));
      uv.push_back(uv_of(grid.vertices[v]));
    }
}

ICM::Distortion_measures measure_grid(const Planar_map& uv_of, int n = grid_size)
{
  Xyz xyz;
  Uv uv;
  flatten(make_grid(n), uv_of, xyz, uv);
  return ICM::measure_distortion_of_triangles(xyz, uv);
}

// --- expectations ------------------------------------------------------------------------------

void expect_undistorted(const ICM::Distortion_measures& m, std::size_t faces)
{
  EXPECT_EQ(m.faces, faces);
  EXPECT_EQ(m.flipped_faces, 0u);
  EXPECT_EQ(m.degenerate_uv_faces, 0u);
  EXPECT_EQ(m.degenerate_3d_faces, 0u);
  EXPECT_NEAR(m.conformality, 0, tolerance);
  EXPECT_NEAR(m.angle_distortion, 0, tolerance);
  EXPECT_NEAR(m.l2_shear, 0, tolerance);
  EXPECT_NEAR(m.l2_stretch, 1, tolerance);
  EXPECT_NEAR(m.log_area_distortion, 0, tolerance);
  EXPECT_NEAR(m.qc_mean, 1, tolerance);
  EXPECT_NEAR(m.qc_max, 1, tolerance);
  EXPECT_NEAR(m.area_ratio_min, 1, tolerance);
  EXPECT_NEAR(m.area_ratio_max, 1, tolerance);
}

void expect_same_measures(const ICM::Distortion_measures& a, const ICM::Distortion_measures& b)
{
  auto near = [](double, double expected) { return 1e-12 * std::max(1.0, std::abs(expected)); };
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.flipped_faces, b.flipped_faces);
  EXPECT_EQ(a.degenerate_uv_faces, b.degenerate_uv_faces);
  EXPECT_EQ(a.degenerate_3d_faces, b.degenerate_3d_faces);
  EXPECT_NEAR(a.conformality, b.conformality, near(a.conformality, b.conformality));
  EXPECT_NEAR(a.angle_distortion, b.angle_distortion, near(a.angle_distortion, b.angle_distortion));
  EXPECT_NEAR(a.l2_shear, b.l2_shear, near(a.l2_shear, b.l2_shear));
  EXPECT_NEAR(a.l2_stretch, b.l2_stretch, near(a.l2_stretch, b.l2_stretch));
  EXPECT_NEAR(a.log_area_distortion, b.log_area_distortion, near(a.log_area_distortion, b.log_area_distortion));
  EXPECT_NEAR(a.qc_mean, b.qc_mean, near(a.qc_mean, b.qc_mean));
  EXPECT_NEAR(a.qc_max, b.qc_max, near(a.qc_max, b.qc_max));
  EXPECT_NEAR(a.area_ratio_min, b.area_ratio_min, near(a.area_ratio_min, b.area_ratio_min));
  EXPECT_NEAR(a.area_ratio_max, b.area_ratio_max, near(a.area_ratio_max, b.area_ratio_max));
}

void expect_all_finite(const ICM::Distortion_measures& m)
{
  for(double x : {m.conformality, m.angle_distortion, m.l2_shear, m.l2_stretch, m.log_area_distortion, m.qc_mean,
                  m.qc_max, m.area_ratio_min, m.area_ratio_max})
    EXPECT_TRUE(std::isfinite(x)) << x;
}

// Mean over the six corners of one grid square of (theta_uv - theta_3d)^2, for the image
// angles of triangle A (at (0,0), (1,0), (1,1)) and B (at (0,0), (1,1), (0,1)).
double mean_squared_angle_error(const std::array<double, 3>& image_a, const std::array<double, 3>& image_b)
{
  const std::array<double, 3> original_a = {pi / 4, pi / 2, pi / 4}, original_b = {pi / 4, pi / 4, pi / 2};
  double sum = 0;
  for(int k = 0; k < 3; ++k)
    sum += std::pow(image_a[k] - original_a[k], 2) + std::pow(image_b[k] - original_b[k], 2);
  return sum / 6;
}

// --- analytic maps -----------------------------------------------------------------------------

TEST(Distortion, IdentityHasNoDistortion)
{
  expect_undistorted(measure_grid(identity), 2 * grid_size * grid_size);
}

TEST(Distortion, SimilarityHasNoDistortion)
{
  const double angle = 0.7, scale = 3.5;
  const auto similarity = [&](const Planar& p) -> Planar {
    return {scale * (std::cos(angle) * p[0] - std::sin(angle) * p[1]) + 10.0,
            scale * (std::sin(angle) * p[0] + std::cos(angle) * p[1]) - 4.0};
  };
  expect_undistorted(measure_grid(similarity), 2 * grid_size * grid_size);
}

TEST(Distortion, MirroredLayoutIsNotFlipped)
{
  const auto mirror = [](const Planar& p) -> Planar { return {-2.0 * p[0] + 1.0, 2.0 * p[1]}; };
  expect_undistorted(measure_grid(mirror), 2 * grid_size * grid_size);
}

// (x, y) -> (x + s y, y): J = [[1, s], [0, 1]], det 1 (no rescaling), s1 s2 = 1,
// s1^2 + s2^2 = 2 + s^2, (s1 - s2)^2 = s^2.
TEST(Distortion, PureShearMatchesClosedForms)
{
  for(double s : {0.6, -1.3})
  {
    const auto shear = [s](const Planar& p) -> Planar { return {p[0] + s * p[1], p[1]}; };
    const ICM::Distortion_measures m = measure_grid(shear);

    const double s1_over_s2 = (2 + s * s + std::abs(s) * std::sqrt(4 + s * s)) / 2; // = s1^2
    // Image of A: (0,0) (1,0) (1+s,1); of B: (0,0) (1+s,1) (s,1).
    const double a0 = std::atan2(1.0, 1 + s), a1 = std::atan2(1.0, -s);
    const double b0 = std::atan2(1.0, 1 + s + s * s), b1 = std::atan2(1.0, 1 + s);
    const double expected_angle = mean_squared_angle_error({a0, a1, pi - a0 - a1}, {b0, b1, pi - b0 - b1});

    EXPECT_EQ(m.flipped_faces, 0u);
    EXPECT_EQ(m.degenerate_uv_faces, 0u);
    EXPECT_NEAR(m.conformality, s * s / 2, tolerance);
    EXPECT_NEAR(m.angle_distortion, expected_angle, tolerance);
    EXPECT_NEAR(m.l2_shear, std::abs(s), tolerance);
    EXPECT_NEAR(m.l2_stretch, std::sqrt(1 + s * s / 2), tolerance);
    EXPECT_NEAR(m.log_area_distortion, 0, tolerance);
    EXPECT_NEAR(m.qc_mean, s1_over_s2, tolerance);
    EXPECT_NEAR(m.qc_max, s1_over_s2, tolerance);
    EXPECT_NEAR(m.area_ratio_min, 1, tolerance);
    EXPECT_NEAR(m.area_ratio_max, 1, tolerance);
  }
}

// (x, y) -> (a x, b y): after the area normalisation J = diag(sqrt(a/b), sqrt(b/a)),
// so s1/s2 = a/b (a > b) and every figure depends on a/b only.
TEST(Distortion, NonUniformScaleMatchesClosedForms)
{
  const double a = 3.0, b = 0.75; // a b != 1: exercises the area normalisation
  const auto scale = [&](const Planar& p) -> Planar { return {a * p[0], b * p[1]}; };
  const ICM::Distortion_measures m = measure_grid(scale);

  const double ratio = a / b;
  // Image of A: (0,0) (a,0) (a,b); of B: (0,0) (a,b) (0,b).
  const double t = std::atan2(b, a);
  const double expected_angle = mean_squared_angle_error({t, pi / 2, pi / 2 - t}, {pi / 2 - t, t, pi / 2});

  EXPECT_EQ(m.flipped_faces, 0u);
  EXPECT_NEAR(m.conformality, (ratio + 1 / ratio - 2) / 2, tolerance);
  EXPECT_NEAR(m.angle_distortion, expected_angle, tolerance);
  EXPECT_NEAR(m.angle_distortion, 2.0 / 3.0 * std::pow(t - pi / 4, 2), tolerance);
  EXPECT_NEAR(m.l2_shear, std::abs(a - b) / std::sqrt(a * b), tolerance);
  EXPECT_NEAR(m.l2_stretch, std::sqrt((ratio + 1 / ratio) / 2), tolerance);
  EXPECT_NEAR(m.log_area_distortion, 0, tolerance);
  EXPECT_NEAR(m.qc_mean, ratio, tolerance);
  EXPECT_NEAR(m.qc_max, ratio, tolerance);
  EXPECT_NEAR(m.area_ratio_min, 1, tolerance);
  EXPECT_NEAR(m.area_ratio_max, 1, tolerance);
}

TEST(Distortion, ScalingTheLayoutChangesNothing)
{
  const auto shear = [](const Planar& p) -> Planar { return {p[0] + 0.4 * p[1], p[1] + 0.1 * p[0] * p[0]}; };
  const auto scaled_shear = [&](const Planar& p) -> Planar {
    const Planar q = shear(p);
    return {1e3 * q[0], 1e3 * q[1]};
  };
  expect_same_measures(measure_grid(scaled_shear), measure_grid(shear));
}

TEST(Distortion, CornerOrderOfAFaceDoesNotMatter)
{
  const auto warp = [](const Planar& p) -> Planar { return {p[0] + 0.1 * p[1] * p[1], p[1] + 0.05 * p[0] * p[1]}; };
  Xyz xyz, rotated_xyz;
  Uv uv, rotated_uv;
  flatten(make_grid(grid_size), warp, xyz, uv);
  for(std::size_t c = 0; c < xyz.size(); c += 3)
    for(std::size_t k = 0; k < 3; ++k)
    {
      rotated_xyz.push_back(xyz[c + (k + 1) % 3]);
      rotated_uv.push_back(uv[c + (k + 1) % 3]);
    }
  expect_same_measures(ICM::measure_distortion_of_triangles(rotated_xyz, rotated_uv),
                       ICM::measure_distortion_of_triangles(xyz, uv));
}

// --- flipped and degenerate faces ----------------------------------------------------------------

// The grid corner (n, 0) belongs to one triangle only: (n-1,0) (n,0) (n,1).
bool is_lonely_corner(const Planar& p)
{
  return p[0] == grid_size && p[1] == 0;
}

TEST(Distortion, OneFoldedFaceIsCountedOnce)
{
  const double n2 = grid_size * grid_size;
  // Move the corner across the opposite edge: signed area 0.5 -> -0.25.
  const auto fold = [](const Planar& p) -> Planar { return is_lonely_corner(p) ? Planar{grid_size - 1.0, 0.5} : p; };
  const ICM::Distortion_measures m = measure_grid(fold);
  const double c2 = n2 / (n2 - 0.25); // area normalisation: total |UV area| = n^2 - 0.25

  EXPECT_EQ(m.flipped_faces, 1u);
  EXPECT_EQ(m.degenerate_uv_faces, 0u);
  EXPECT_NEAR(m.area_ratio_min, 0.5 * c2, tolerance);
  EXPECT_NEAR(m.area_ratio_max, c2, tolerance);
  EXPECT_NEAR(m.log_area_distortion,
              ((2 * n2 - 1) * std::pow(std::log(c2), 2) + std::pow(std::log(0.5 * c2), 2)) / (2 * n2), tolerance);
  EXPECT_GT(m.conformality, 0);
  expect_all_finite(m);

  // The same fold inside a mirrored layout: the whole is mirrored back, the fold stays one flip.
  const auto mirrored_fold = [&](const Planar& p) -> Planar {
    const Planar q = fold(p);
    return {q[0], -q[1]};
  };
  expect_same_measures(measure_grid(mirrored_fold), m);
}

TEST(Distortion, DegenerateUvFaceIsCountedAndExcluded)
{
  const double n = grid_size, n2 = n * n;
  // The corner onto the opposite edge's line: (n-1,0) (n-1/2,1/2) (n,1) are collinear.
  const auto collapse = [&](const Planar& p) -> Planar { return is_lonely_corner(p) ? Planar{n - 0.5, 0.5} : p; };
  const ICM::Distortion_measures m = measure_grid(collapse);
  const double c2 = n2 / (n2 - 0.5); // every other face is scaled by c

  EXPECT_EQ(m.flipped_faces, 0u);
  EXPECT_EQ(m.degenerate_uv_faces, 1u);
  // The collapsed face keeps its conformal terms: J = c [[1/2, 1/2], [1/2, 1/2]] in the plane's
  // frame, (s1 - s2)^2 / 2 = c^2 / 2 on area 1/2; its UV angles are 0, pi, 0 for pi/4, pi/2, pi/4.
  EXPECT_NEAR(m.conformality, c2 / (4 * n2), tolerance);
  EXPECT_NEAR(m.angle_distortion, (3 * pi * pi / 8) / (6 * n2), tolerance);
  // The others are similarities with area ratio c^2.
  EXPECT_NEAR(m.l2_shear, 0, tolerance);
  EXPECT_NEAR(m.l2_stretch, 1 / std::sqrt(c2), tolerance);
  EXPECT_NEAR(m.log_area_distortion, std::pow(std::log(c2), 2), tolerance); // mean over 2n^2 - 1 faces
  EXPECT_NEAR(m.qc_mean, 1, tolerance);
  EXPECT_NEAR(m.qc_max, 1, tolerance);
  EXPECT_NEAR(m.area_ratio_min, c2, tolerance);
  EXPECT_NEAR(m.area_ratio_max, c2, tolerance);
}

TEST(Distortion, Degenerate3dFaceIsCountedAndExcluded)
{
  Xyz xyz;
  Uv uv;
  flatten(make_grid(grid_size), identity, xyz, uv);
  for(int k = 0; k < 3; ++k) // third corner of face 0 onto the midpoint of its first edge
    xyz[2][k] = 0.5 * (xyz[0][k] + xyz[1][k]);
  const ICM::Distortion_measures m = ICM::measure_distortion_of_triangles(xyz, uv);
  const double n2 = grid_size * grid_size, c2 = (n2 - 0.5) / n2;

  EXPECT_EQ(m.degenerate_3d_faces, 1u);
  EXPECT_EQ(m.degenerate_uv_faces, 0u);
  EXPECT_EQ(m.flipped_faces, 0u);
  EXPECT_NEAR(m.conformality, 0, tolerance);
  EXPECT_NEAR(m.angle_distortion, 0, tolerance);
  EXPECT_NEAR(m.qc_max, 1, tolerance);
  EXPECT_NEAR(m.area_ratio_min, c2, tolerance);
  EXPECT_NEAR(m.area_ratio_max, c2, tolerance);
}

TEST(Distortion, EmptyInputGivesZeros)
{
  const ICM::Distortion_measures m = ICM::measure_distortion_of_triangles({}, {});
  EXPECT_EQ(m.faces, 0u);
  EXPECT_EQ(m.l2_stretch, 0);
  EXPECT_EQ(m.qc_max, 0);
}

TEST(Distortion, MalformedInputThrows)
{
  Xyz xyz;
  Uv uv;
  flatten(make_grid(1), identity, xyz, uv);
  EXPECT_THROW(ICM::measure_distortion_of_triangles(xyz, Uv(uv.begin(), uv.end() - 3)), std::invalid_argument);
  EXPECT_THROW(ICM::measure_distortion_of_triangles(Xyz(xyz.begin(), xyz.end() - 1), Uv(uv.begin(), uv.end() - 1)),
               std::invalid_argument);
  uv[4][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ICM::measure_distortion_of_triangles(xyz, uv), std::invalid_argument);
}

// --- the FaceGraph front ends ----------------------------------------------------------------

Planar warp(const Planar& p)
{
  return {p[0] + 0.1 * p[1] * p[1], p[1] + 0.05 * p[0] * p[1]};
}

std::vector<Point_3> grid_points(const Grid& grid)
{
  std::vector<Point_3> points;
  for(const auto& v : grid.vertices)
  {
    const auto p = embed_in_space(v);
    points.emplace_back(p[0], p[1], p[2]);
  }
  return points;
}

std::vector<std::vector<std::size_t>> grid_polygons(const Grid& grid)
{
  std::vector<std::vector<std::size_t>> polygons;
  for(const auto& t : grid.triangles)
    polygons.push_back({t[0], t[1], t[2]});
  return polygons;
}

// Planar coordinates of a mesh vertex, found back from its (exactly reproduced) 3D point.
class Planar_lookup
{
public:
  explicit Planar_lookup(const Grid& grid)
  {
    for(const auto& v : grid.vertices)
      planar_[embed_in_space(v)] = v;
  }
  Planar operator()(const Point_3& p) const { return planar_.at({p.x(), p.y(), p.z()}); }

private:
  std::map<std::array<double, 3>, Planar> planar_;
};

ICM::Distortion_measures flat_reference(const Grid& grid)
{
  Xyz xyz;
  Uv uv;
  flatten(grid, warp, xyz, uv);
  return ICM::measure_distortion_of_triangles(xyz, uv);
}

TEST(DistortionFrontEnds, SurfaceMeshVertexUvAgreesWithFlatCore)
{
  const Grid grid = make_grid(grid_size);
  Surface_mesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(grid_points(grid), grid_polygons(grid), mesh);
  const Planar_lookup planar(grid);
  auto uvmap = mesh.add_property_map<Surface_mesh::Vertex_index, Point_2>("v:uv").first;
  for(auto v : vertices(mesh))
  {
    const Planar q = warp(planar(mesh.point(v)));
    put(uvmap, v, Point_2(q[0], q[1]));
  }
  const ICM::Distortion_measures reference = flat_reference(grid);
  EXPECT_GT(reference.conformality, 1e-4); // a real distortion, not a trivial agreement
  expect_same_measures(ICM::measure_distortion(mesh, uvmap), reference);
  expect_same_measures(ICM::measure_distortion(mesh, uvmap, mesh.points()), reference);
}

TEST(DistortionFrontEnds, PolyhedronVertexUvAgreesWithFlatCore)
{
  const Grid grid = make_grid(grid_size);
  Polyhedron mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(grid_points(grid), grid_polygons(grid), mesh);
  const Planar_lookup planar(grid);
  using vertex_descriptor = boost::graph_traits<Polyhedron>::vertex_descriptor;
  std::unordered_map<vertex_descriptor, Point_2> uv;
  for(auto v : vertices(mesh))
  {
    const Planar q = warp(planar(v->point()));
    uv[v] = Point_2(q[0], q[1]);
  }
  boost::associative_property_map<std::unordered_map<vertex_descriptor, Point_2>> uvmap(uv);
  expect_same_measures(ICM::measure_distortion(mesh, uvmap), flat_reference(grid));
}

// A slit along y = 2 from x = 0 to x = 2, opened in UV: the copies on the faces above the slit
// move up. The corner UV is a function of the vertex and of the side of the face it is seen from.
bool on_slit(const Planar& p)
{
  return p[1] == 2 && p[0] < 2;
}

Planar slit_corner_uv(const Planar& vertex, bool face_above_slit)
{
  Planar q = warp(vertex);
  if(face_above_slit && on_slit(vertex))
    q[1] += 0.3;
  return q;
}

bool above_slit(const Grid& grid, const std::array<std::size_t, 3>& t)
{
  return grid.vertices[t[0]][1] + grid.vertices[t[1]][1] + grid.vertices[t[2]][1] > 3 * 2.0;
}

ICM::Distortion_measures slit_flat_reference(const Grid& grid)
{
  Xyz xyz;
  Uv uv;
  for(const auto& t : grid.triangles)
    for(std::size_t v : t)
    {
      xyz.push_back(embed_in_space(grid.vertices[v]));
      uv.push_back(slit_corner_uv(grid.vertices[v], above_slit(grid, t)));
    }
  return ICM::measure_distortion_of_triangles(xyz, uv);
}

TEST(DistortionFrontEnds, SeamMeshAndCornerUvAgreeWithFlatCore)
{
  const Grid grid = make_grid(grid_size);
  Surface_mesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(grid_points(grid), grid_polygons(grid), mesh);
  const Planar_lookup planar(grid);
  auto face_above_slit = [&](Surface_mesh::Face_index f) {
    double y = 0;
    for(auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      y += planar(mesh.point(v))[1];
    return y > 3 * 2.0;
  };
  const ICM::Distortion_measures reference = slit_flat_reference(grid);

  // Corner UVs on the uncut mesh.
  auto corner_uv = mesh.add_property_map<Surface_mesh::Halfedge_index, Point_2>("h:uv").first;
  for(auto f : faces(mesh))
    for(auto h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh))
    {
      const Planar q = slit_corner_uv(planar(mesh.point(mesh.target(h))), face_above_slit(f));
      put(corner_uv, h, Point_2(q[0], q[1]));
    }
  expect_same_measures(ICM::measure_distortion_corner_uv(mesh, corner_uv), reference);

  // Vertex UVs on the seam mesh cut along the slit.
  auto seam_edges = mesh.add_property_map<Surface_mesh::Edge_index, bool>("e:on_seam", false).first;
  auto seam_vertices = mesh.add_property_map<Surface_mesh::Vertex_index, bool>("v:on_seam", false).first;
  using Seam_mesh = CGAL::Seam_mesh<Surface_mesh, decltype(seam_edges), decltype(seam_vertices)>;
  Seam_mesh seam_mesh(mesh, seam_edges, seam_vertices);
  auto grid_index = [](int i, int j) {
    return Surface_mesh::Vertex_index(Surface_mesh::size_type(j * (grid_size + 1) + i));
  };
  for(int i = 0; i < 2; ++i)
  {
    // polygon_soup_to_polygon_mesh keeps the soup's point order on a fresh Surface_mesh.
    ASSERT_EQ(planar(mesh.point(grid_index(i, 2)))[0], i);
    ASSERT_TRUE(seam_mesh.add_seam(grid_index(i, 2), grid_index(i + 1, 2)));
  }
  EXPECT_EQ(num_vertices(seam_mesh), num_vertices(mesh) + 2); // (0,2) and (1,2) are doubled

  using seam_vertex = boost::graph_traits<Seam_mesh>::vertex_descriptor;
  std::unordered_map<seam_vertex, Point_2> uv;
  for(auto f : faces(seam_mesh))
    for(auto h : CGAL::halfedges_around_face(halfedge(f, seam_mesh), seam_mesh))
    {
      const Planar q = slit_corner_uv(planar(mesh.point(mesh.target(h.tmhd))), face_above_slit(f));
      const Point_2 value(q[0], q[1]);
      const auto inserted = uv.emplace(target(h, seam_mesh), value);
      ASSERT_EQ(inserted.first->second, value) << "a seam vertex seen with two UVs";
    }
  boost::associative_property_map<std::unordered_map<seam_vertex, Point_2>> uvmap(uv);
  expect_same_measures(ICM::measure_distortion(seam_mesh, uvmap), reference);
}

TEST(DistortionFrontEnds, NonTriangleFaceThrows)
{
  Surface_mesh mesh;
  const auto a = mesh.add_vertex(Point_3(0, 0, 0)), b = mesh.add_vertex(Point_3(1, 0, 0)),
             c = mesh.add_vertex(Point_3(1, 1, 0)), d = mesh.add_vertex(Point_3(0, 1, 0)),
             e = mesh.add_vertex(Point_3(2, 0, 0));
  mesh.add_face(a, b, c, d);
  mesh.add_face(b, e, c);
  auto uvmap = mesh.add_property_map<Surface_mesh::Vertex_index, Point_2>("v:uv").first;
  for(auto v : vertices(mesh))
    put(uvmap, v, Point_2(mesh.point(v).x(), mesh.point(v).y()));
  EXPECT_THROW(ICM::measure_distortion(mesh, uvmap), std::invalid_argument);
}

// A real mesh, UV = its xy projection: the figures are finite and the front ends agree.
TEST(DistortionFrontEnds, NefertitiProjectionAgreesAcrossFrontEnds)
{
  const std::string file = ICM_TEST_DATA_DIR "/nefertiti.off";
  std::vector<Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  ASSERT_TRUE(CGAL::IO::read_polygon_soup(file, points, polygons)) << file;

  Xyz xyz;
  Uv uv;
  for(const auto& polygon : polygons)
  {
    ASSERT_EQ(polygon.size(), 3u);
    for(std::size_t v : polygon)
    {
      xyz.push_back({points[v].x(), points[v].y(), points[v].z()});
      uv.push_back({points[v].x(), points[v].y()});
    }
  }
  const ICM::Distortion_measures reference = ICM::measure_distortion_of_triangles(xyz, uv);
  EXPECT_EQ(reference.faces, polygons.size());
  EXPECT_EQ(reference.degenerate_3d_faces, 0u);
  expect_all_finite(reference);
  EXPECT_GE(reference.qc_max, reference.qc_mean);
  EXPECT_GE(reference.qc_mean, 1);
  EXPECT_GE(reference.l2_stretch, 1); // Sander's L2 stretch is >= 1 once areas are normalised

  Surface_mesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  auto uvmap = mesh.add_property_map<Surface_mesh::Vertex_index, Point_2>("v:uv").first;
  for(auto v : vertices(mesh))
    put(uvmap, v, Point_2(mesh.point(v).x(), mesh.point(v).y()));
  auto corner_uv = mesh.add_property_map<Surface_mesh::Halfedge_index, Point_2>("h:uv").first;
  for(auto h : halfedges(mesh))
    put(corner_uv, h, get(uvmap, mesh.target(h)));
  expect_same_measures(ICM::measure_distortion(mesh, uvmap), reference);
  expect_same_measures(ICM::measure_distortion_corner_uv(mesh, corner_uv), reference);

  Polyhedron polyhedron;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, polyhedron);
  using vertex_descriptor = boost::graph_traits<Polyhedron>::vertex_descriptor;
  std::unordered_map<vertex_descriptor, std::array<double, 2>> array_uv; // [0]/[1] access
  for(auto v : vertices(polyhedron))
    array_uv[v] = {v->point().x(), v->point().y()};
  expect_same_measures(
    ICM::measure_distortion(
      polyhedron,
      boost::associative_property_map<std::unordered_map<vertex_descriptor, std::array<double, 2>>>(array_uv)),
    reference);
}

TEST(SeamLength, IsTheSeamsLengthOverTheRootOfTheArea)
{
  // A 2 x 2 square of two triangles (area 4) cut along its diagonal (length 2 sqrt 2): sqrt 2,
  // whatever the scale; no seam, 0.
  for(double scale : {1., 1e-6, 1e6})
  {
    Surface_mesh mesh;
    const auto a = mesh.add_vertex(Point_3(0, 0, 0)), b = mesh.add_vertex(Point_3(2 * scale, 0, 0));
    const auto c = mesh.add_vertex(Point_3(2 * scale, 2 * scale, 0)), d = mesh.add_vertex(Point_3(0, 2 * scale, 0));
    mesh.add_face(a, b, c);
    mesh.add_face(a, c, d);
    const std::vector<Surface_mesh::Edge_index> diagonal = {mesh.edge(mesh.halfedge(a, c))};
    EXPECT_NEAR(ICM::seam_length_over_root_area(mesh, diagonal), std::sqrt(2.), 1e-12) << scale;
    EXPECT_EQ(ICM::seam_length_over_root_area(mesh, std::vector<Surface_mesh::Edge_index>()), 0.);
  }
}

} // namespace
