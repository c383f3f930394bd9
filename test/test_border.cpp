// Border conditions (Border_conditions.h) through CGAL's own entry point,
// CGAL::Surface_mesh_parameterization::parameterize(mesh, parameterizer, bhd, uvmap):
// a square border gives a rectangle (right corners, straight sides), a circular border a
// disk, a prescribed curvature is reproduced, circle domains are laid out without a cut
// with every loop a circle and the outer one around the others; bad combinations are
// refused with their reason. Every geometric check is made on the UVs written, not on the
// report.

#include <ICM/border/Border_conditions.h>
#include <ICM/border/Border_shape.h>

#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Square_border_parameterizer_3.h>
#include <ICM/Inverse_curvature_map_parameterizer_3.h>
#include <ICM/optimum/Energies.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/io.h>

#include <Eigen/Dense>

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point_2 = Kernel::Point_2;
using Surface_mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using vertex_descriptor = Surface_mesh::Vertex_index;
using halfedge_descriptor = Surface_mesh::Halfedge_index;
namespace SMP = CGAL::Surface_mesh_parameterization;

template <class Condition, class Energy = CGAL::Default>
using Parameterizer =
  ICM::Inverse_curvature_map_parameterizer_3<Surface_mesh, CGAL::Default, CGAL::Default, Energy, Condition>;

/// The mesh of `examples/data` or of the shared directory; false when the latter is absent.
bool read_mesh(const std::string& name, Surface_mesh& mesh)
{
  const std::string bundled = icm_test::data_path(name);
  if(icm_test::fs::exists(bundled))
    return CGAL::IO::read_polygon_mesh(bundled, mesh);
  if(!icm_test::shared_dir_exists())
    return false;
  return CGAL::IO::read_polygon_mesh(icm_test::shared_path(name), mesh);
}

halfedge_descriptor some_border_halfedge(const Surface_mesh& mesh)
{
  for(halfedge_descriptor h : halfedges(mesh))
    if(is_border(h, mesh))
      return h;
  return Surface_mesh::null_halfedge();
}

/// The border loops, each as its vertices in the order of its border halfedges.
std::vector<std::vector<vertex_descriptor>> border_loops(const Surface_mesh& mesh)
{
  std::vector<std::vector<vertex_descriptor>> loops;
  std::map<halfedge_descriptor, bool> seen;
  for(halfedge_descriptor h : halfedges(mesh))
  {
    if(!is_border(h, mesh) || seen[h])
      continue;
    loops.emplace_back();
    for(halfedge_descriptor g : CGAL::halfedges_around_face(h, mesh))
    {
      seen[g] = true;
      loops.back().push_back(target(g, mesh));
    }
  }
  return loops;
}

template <class UvMap>
double signed_area(const Surface_mesh& mesh, Surface_mesh::Face_index f, const UvMap& uv)
{
  std::vector<Point_2> p;
  for(vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, mesh), mesh))
    p.push_back(get(uv, v));
  return CGAL::area(p[0], p[1], p[2]);
}

/// Faces with negative UV area, and faces with exactly zero UV area.
template <class UvMap>
std::pair<int, int> negative_and_zero_faces(const Surface_mesh& mesh, const UvMap& uv)
{
  int negative = 0, zero = 0;
  for(auto f : faces(mesh))
  {
    const double a = signed_area(mesh, f, uv);
    negative += a < 0;
    zero += a == 0;
  }
  return {negative, zero};
}

/// Per vertex, the sum of its UV corner angles over its faces.
template <class UvMap>
std::map<vertex_descriptor, double> uv_angle_sums(const Surface_mesh& mesh, const UvMap& uv)
{
  std::map<vertex_descriptor, double> sum;
  for(auto f : faces(mesh))
    for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, mesh), mesh))
    {
      const Point_2 a = get(uv, source(h, mesh)), b = get(uv, target(h, mesh)),
                    c = get(uv, target(next(h, mesh), mesh));
      const Kernel::Vector_2 ba = a - b, bc = c - b;
      sum[target(h, mesh)] += std::atan2(std::abs(ba.x() * bc.y() - ba.y() * bc.x()), ba * bc);
    }
  return sum;
}

/// A least-squares circle through UV points (Kasa fit, centred first): centre, radius, and
/// the largest relative deviation of a point's distance to the centre from the radius.
struct Circle_fit
{
  Point_2 centre;
  double radius = 0, deviation = 0;
};

template <class UvMap>
Circle_fit fit_circle(const std::vector<vertex_descriptor>& loop, const UvMap& uv)
{
  double mx = 0, my = 0;
  for(vertex_descriptor v : loop)
  {
    mx += get(uv, v).x() / loop.size();
    my += get(uv, v).y() / loop.size();
  }
  Eigen::MatrixXd a(loop.size(), 3);
  Eigen::VectorXd b(loop.size());
  for(std::size_t i = 0; i < loop.size(); ++i)
  {
    const double x = get(uv, loop[i]).x() - mx, y = get(uv, loop[i]).y() - my;
    a.row(i) << x, y, 1.0;
    b[i] = -(x * x + y * y);
  }
  const Eigen::Vector3d d = a.colPivHouseholderQr().solve(b);
  Circle_fit fit;
  fit.centre = Point_2(mx - d[0] / 2, my - d[1] / 2);
  fit.radius = std::sqrt(d[0] * d[0] / 4 + d[1] * d[1] / 4 - d[2]);
  for(vertex_descriptor v : loop)
    fit.deviation = std::max(
      fit.deviation, std::abs(std::sqrt(CGAL::squared_distance(get(uv, v), fit.centre)) - fit.radius) / fit.radius);
  return fit;
}

struct Outcome
{
  SMP::Error_code status;
  ICM::Parameterization_report report;
};

template <class P>
Outcome parameterize(Surface_mesh& mesh, P parameterizer, Surface_mesh::Property_map<vertex_descriptor, Point_2> uv,
                     halfedge_descriptor bhd = Surface_mesh::null_halfedge())
{
  if(bhd == Surface_mesh::null_halfedge())
    bhd = some_border_halfedge(mesh);
  Outcome run{SMP::parameterize(mesh, parameterizer, bhd, uv), parameterizer.report()};
  return run;
}

auto add_uv_map(Surface_mesh& mesh)
{
  return mesh.add_property_map<vertex_descriptor, Point_2>("v:uv").first;
}

} // namespace

TEST(BorderConditionMath, InscribedCircleOnBothBranches)
{
  // A square of side sqrt(2) is inscribed in the unit circle.
  const ICM::internal::Inscribed_circle square =
    ICM::internal::inscribed_circle({std::sqrt(2.0), std::sqrt(2.0), std::sqrt(2.0), std::sqrt(2.0)});
  ASSERT_TRUE(square.exists);
  EXPECT_NEAR(square.radius, 1.0, 1e-15);
  EXPECT_EQ(square.long_side, -1);
  // Points of the unit circle at 0, 0.3, 0.7, 1.0 rad: the closing side subtends 2 pi - 1,
  // more than pi, so the centre is beyond it (the far branch).
  const double angles[] = {0.0, 0.3, 0.7, 1.0};
  std::vector<double> sides;
  for(int i = 0; i < 4; ++i)
  {
    const double a = angles[i], b = angles[(i + 1) % 4];
    sides.push_back(std::hypot(std::cos(b) - std::cos(a), std::sin(b) - std::sin(a)));
  }
  const ICM::internal::Inscribed_circle far = ICM::internal::inscribed_circle(sides);
  ASSERT_TRUE(far.exists);
  EXPECT_NEAR(far.radius, 1.0, 1e-14);
  EXPECT_EQ(far.long_side, 3);
  EXPECT_NEAR(ICM::internal::subtended_angle_sum(sides, far.radius, far.long_side), 2 * M_PI, 1e-13);
  // No polygon has a side as long as all the others together.
  EXPECT_FALSE(ICM::internal::inscribed_circle({1.0, 1.0, 2.0}).exists);
}

/// The border of `uv` is a rectangle: four corners of right angles and straight sides, to
/// 1e-9 rad; no face is negative and the zero ones are those the report says are degenerate.
void expect_rectangle(const Surface_mesh& mesh, Surface_mesh::Property_map<vertex_descriptor, Point_2> uv,
                      const Outcome& run, const std::string& name)
{
  EXPECT_EQ(run.report.border_condition, "square") << name;
  EXPECT_EQ(run.report.flipped_faces, 0) << name;
  const auto [negative, zero] = negative_and_zero_faces(mesh, uv);
  EXPECT_EQ(negative, 0) << name;
  EXPECT_EQ(zero, run.report.degenerate_faces) << name;

  const std::map<vertex_descriptor, double> angle = uv_angle_sums(mesh, uv);
  int corners = 0;
  double worst_corner = 0, worst_side = 0;
  const std::vector<std::vector<vertex_descriptor>> loops = border_loops(mesh);
  for(vertex_descriptor v : loops[0])
  {
    const double turning = M_PI - angle.at(v);
    if(std::abs(turning) > 1e-3)
    {
      ++corners;
      worst_corner = std::max(worst_corner, std::abs(turning - M_PI / 2));
    }
    else
      worst_side = std::max(worst_side, std::abs(turning));
  }
  EXPECT_EQ(corners, 4) << name;
  EXPECT_LE(worst_corner, 1e-9) << name;
  EXPECT_LE(worst_side, 1e-9) << name;
  std::cout << name << " square: corner angle error " << worst_corner << ", side turning " << worst_side
            << ", degenerate faces " << run.report.degenerate_faces << ", " << run.report.newton_iterations
            << " Newton steps, " << run.report.seconds_total << " s\n";
}

TEST(BorderConditionSquare, ThreePeaksIsARectangle)
{
  Surface_mesh mesh;
  ASSERT_TRUE(read_mesh("three_peaks.off", mesh));
  auto uv = add_uv_map(mesh);
  const Outcome run = parameterize(mesh, Parameterizer<ICM::Square_border<Surface_mesh>>(), uv);
  ASSERT_EQ(run.status, SMP::OK) << run.report.message;
  // Three faces have all corners on one side (ears): exactly flat, and said so.
  EXPECT_EQ(run.report.degenerate_faces, 3);
  expect_rectangle(mesh, uv, run, "three_peaks");
}

// A vertex whose neighbours all lie on one straight side lies on it too in any layout
// without flipped faces, and so do its faces: vertex 6 below, inside the fan 0-1-2-3.
//
//   5 ------ 4       faces (6,0,1) (6,1,2) (6,2,3) (6,3,0) (0,3,4) (0,4,5);
//   |  .     |       the border runs 0 1 2 3 4 5.
//   |     .  |
//   0 ------ 3
//    \  6   /
//     1 -- 2
TEST(BorderConditionSquare, VertexAmongPointsOfOneSideIsHeldOnIt)
{
  ICM::internal::Mesh_index index;
  index.points = {{0, 0, 0}, {0.3, -0.6, 0}, {0.7, -0.6, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, -0.3, 0}};
  index.faces = {{6, 0, 1}, {6, 1, 2}, {6, 2, 3}, {6, 3, 0}, {0, 3, 4}, {0, 4, 5}};
  ASSERT_TRUE(ICM::internal::build_connectivity(index).ok());
  ASSERT_EQ(index.boundary_loops.size(), 1u);
  Eigen::VectorXd k = Eigen::VectorXd::Zero(7);
  for(int corner : {0, 3, 4, 5})
    k[corner] = M_PI / 2;
  std::vector<std::array<int, 2>> stretches = ICM::internal::straight_stretches(index, k);
  EXPECT_GE(stretches[6][0], 0);
  EXPECT_EQ(stretches[1], stretches[6]); // the side from 0 to 3
  EXPECT_EQ(ICM::internal::faces_on_a_straight_stretch(index, stretches), (std::vector<int>{0, 1, 2, 3}));

  // A corner at 1 instead of 0 breaks that side: 6 is free and no face is flat.
  k[0] = 0;
  k[1] = M_PI / 2;
  stretches = ICM::internal::straight_stretches(index, k);
  EXPECT_EQ(stretches[6], (std::array<int, 2>{-1, -1}));
  EXPECT_TRUE(ICM::internal::faces_on_a_straight_stretch(index, stretches).empty());
}

// The horse's border has 58 ears, and vertices whose angle sums run from 0.37 to 6.5 rad
// (the ends of its cut); CGAL puts a square corner at one of 5.9 rad. The intrinsic
// Delaunay metric reaches the rectangle in 12 Newton steps. Vertex 700 is interior, but its
// six neighbours are border vertices of one side: its faces are segments like the ears
// (one came out inverted by 1e-8 before the vertex was held on the side).
TEST(BorderConditionSquare, HorseIsARectangle)
{
  Surface_mesh mesh;
  if(!read_mesh("horse.obj", mesh))
    GTEST_SKIP() << "shared mesh directory " << ICM_SHARED_MESH_DIR << " not found";
  auto uv = add_uv_map(mesh);
  const Outcome run = parameterize(mesh, Parameterizer<ICM::Square_border<Surface_mesh>>(), uv);
  ASSERT_EQ(run.status, SMP::OK) << run.report.message;
  EXPECT_EQ(run.report.metric, "intrinsic-delaunay");
  expect_rectangle(mesh, uv, run, "horse");
}

TEST(BorderConditionCircle, DiskBorderIsACircle)
{
  for(const std::string name : {"three_peaks.off", "mushroom.off"})
  {
    Surface_mesh mesh;
    ASSERT_TRUE(read_mesh(name, mesh));
    auto uv = add_uv_map(mesh);
    const Outcome run = parameterize(mesh, Parameterizer<ICM::Circular_border<Surface_mesh>>(), uv);
    ASSERT_EQ(run.status, SMP::OK) << name << ": " << run.report.message;
    EXPECT_EQ(run.report.border_condition, "circle");
    EXPECT_EQ(negative_and_zero_faces(mesh, uv), std::make_pair(0, 0)) << name;
    const Circle_fit fit = fit_circle(border_loops(mesh)[0], uv);
    EXPECT_LE(fit.deviation, 1e-8) << name;
    std::cout << name << " circle: deviation " << fit.deviation << ", " << run.report.border_iterations
              << " outer iterations, " << run.report.newton_iterations << " Newton steps, " << run.report.seconds_total
              << " s\n";
  }
}

/// The UV area of `mesh`'s faces over their 3D area.
double uv_area_over_3d_area(const Surface_mesh& mesh, Surface_mesh::Property_map<vertex_descriptor, Point_2> uv)
{
  double uv_area = 0, area = 0;
  for(auto f : faces(mesh))
  {
    const halfedge_descriptor h = halfedge(f, mesh);
    const vertex_descriptor a = source(h, mesh), b = target(h, mesh), c = target(next(h, mesh), mesh);
    uv_area += CGAL::area(uv[a], uv[b], uv[c]);
    area += std::sqrt(CGAL::squared_area(mesh.point(a), mesh.point(b), mesh.point(c)));
  }
  return uv_area / area;
}

TEST(BorderConditionArea, PrescribedBordersKeepTheThreeDArea)
{
  // A prescribed border fixes the shape, not the size: the chart comes at its 3D scale, as
  // a free border's and every chart of ICM::parameterize do (the vertex pinned for the scale
  // used to leave a circle's disk hundreds of times too large).
  Surface_mesh disk, pig;
  ASSERT_TRUE(read_mesh("three_peaks.off", disk));
  ASSERT_TRUE(read_mesh("pig.off", pig));
  auto uv = add_uv_map(disk);
  Outcome run = parameterize(disk, Parameterizer<ICM::Circular_border<Surface_mesh>>(), uv);
  ASSERT_EQ(run.status, SMP::OK) << run.report.message;
  EXPECT_NEAR(uv_area_over_3d_area(disk, uv), 1.0, 1e-9) << "circle";
  EXPECT_LE(run.report.circle_deviation, 1e-8);
  run = parameterize(disk, Parameterizer<ICM::Square_border<Surface_mesh>>(), uv);
  ASSERT_EQ(run.status, SMP::OK) << run.report.message;
  EXPECT_NEAR(uv_area_over_3d_area(disk, uv), 1.0, 1e-9) << "square";
  expect_rectangle(disk, uv, run, "three_peaks, scaled");
  auto pig_uv = add_uv_map(pig);
  run = parameterize(pig, Parameterizer<ICM::Circle_domain>(), pig_uv);
  ASSERT_EQ(run.status, SMP::OK) << run.report.message;
  EXPECT_NEAR(uv_area_over_3d_area(pig, pig_uv), 1.0, 1e-9) << "circle domain";
}

TEST(BorderConditionPrescribed, RegularPolygonAnglesAreReproduced)
{
  Surface_mesh mesh;
  ASSERT_TRUE(read_mesh("nefertiti.off", mesh));
  const std::vector<vertex_descriptor> loop = border_loops(mesh)[0];
  // Equal turning everywhere (an equiangular polygon), except that every fourth vertex
  // turns twice as much and its neighbours half as much: still 2 pi in all.
  auto k = mesh.add_property_map<vertex_descriptor, double>("v:k", 0.0).first;
  const double step = 2 * M_PI / loop.size();
  for(std::size_t i = 0; i < loop.size(); ++i)
    k[loop[i]] = step;
  for(std::size_t i = 0; i + 2 < loop.size(); i += 4)
  {
    k[loop[i]] = step / 2;
    k[loop[i + 1]] = 2 * step;
    k[loop[i + 2]] = step / 2;
  }
  using Condition = ICM::Prescribed_border_curvature<decltype(k)>;
  auto uv = add_uv_map(mesh);
  const Outcome run =
    parameterize(mesh, Parameterizer<Condition>(ICM::Parameterization_options(), {}, Condition(k)), uv);
  ASSERT_EQ(run.status, SMP::OK) << run.report.message;
  EXPECT_EQ(run.report.border_condition, "prescribed-curvature");
  EXPECT_EQ(negative_and_zero_faces(mesh, uv), std::make_pair(0, 0));
  EXPECT_LE(run.report.max_curvature_error, 1e-10);
  const std::map<vertex_descriptor, double> angle = uv_angle_sums(mesh, uv);
  double worst = 0;
  for(vertex_descriptor v : loop)
    worst = std::max(worst, std::abs(M_PI - angle.at(v) - k[v]));
  EXPECT_LE(worst, 1e-9);

  // One vertex turning a little more breaks Gauss-Bonnet: refused, with the sum.
  k[loop[0]] += 0.01;
  const Outcome refused =
    parameterize(mesh, Parameterizer<Condition>(ICM::Parameterization_options(), {}, Condition(k)), uv);
  EXPECT_EQ(refused.status, SMP::ERROR_WRONG_PARAMETER);
  EXPECT_NE(refused.report.message.find("Gauss-Bonnet"), std::string::npos) << refused.report.message;
}

class BorderConditionCircleDomain : public ::testing::TestWithParam<std::string>
{};

TEST_P(BorderConditionCircleDomain, LoopsAreNestedCirclesWithoutCut)
{
  const std::string name = GetParam();
  Surface_mesh mesh;
  if(!read_mesh(name, mesh))
    GTEST_SKIP() << "shared mesh directory " << ICM_SHARED_MESH_DIR << " not found";
  auto uv = add_uv_map(mesh);
  const Outcome run = parameterize(mesh, Parameterizer<ICM::Circle_domain>(), uv);
  ASSERT_EQ(run.status, SMP::OK) << name << ": " << run.report.message;
  EXPECT_EQ(run.report.border_condition, "circle-domain");
  EXPECT_EQ(negative_and_zero_faces(mesh, uv), std::make_pair(0, 0)) << name;
  EXPECT_EQ(icm_test::crossing_border_edges(mesh, uv), 0) << name;

  const std::vector<std::vector<vertex_descriptor>> loops = border_loops(mesh);
  ASSERT_EQ(static_cast<int>(loops.size()), run.report.boundary_loops);
  std::vector<Circle_fit> circles;
  for(const auto& loop : loops)
  {
    circles.push_back(fit_circle(loop, uv));
    EXPECT_LE(circles.back().deviation, 1e-8) << name << ", a loop of " << loop.size() << " vertices";
  }
  // The outer circle holds every other one, and no two holes overlap.
  const auto outer = std::max_element(circles.begin(), circles.end(),
                                      [](const Circle_fit& a, const Circle_fit& b) { return a.radius < b.radius; });
  double worst = 0;
  for(auto c = circles.begin(); c != circles.end(); ++c)
  {
    worst = std::max(worst, c->deviation);
    if(c == outer)
      continue;
    EXPECT_LT(std::sqrt(CGAL::squared_distance(c->centre, outer->centre)) + c->radius, outer->radius) << name;
    for(auto d = c + 1; d != circles.end(); ++d)
    {
      if(d == outer)
        continue;
      EXPECT_GT(std::sqrt(CGAL::squared_distance(c->centre, d->centre)), c->radius + d->radius) << name;
    }
  }
  std::cout << name << " circle domain: " << loops.size() << " loops, circle deviation " << worst << ", "
            << run.report.border_iterations << " outer iterations, " << run.report.newton_iterations
            << " Newton steps, metric " << run.report.metric << ", " << run.report.seconds_total << " s\n";
}

INSTANTIATE_TEST_SUITE_P(Meshes, BorderConditionCircleDomain,
                         ::testing::Values("pig.off", "head.off", "mech-holes-shark.off"),
                         icm_test::Mesh_file_test_name());

TEST(BorderConditionCircleDomain, OuterLoopOfTheGivenHalfedge)
{
  Surface_mesh mesh;
  ASSERT_TRUE(read_mesh("pig.off", mesh));
  // The shortest loop in 3D, made the outer one by passing its halfedge.
  halfedge_descriptor shortest;
  double shortest_length = HUGE_VAL;
  std::map<halfedge_descriptor, bool> seen;
  for(halfedge_descriptor h : halfedges(mesh))
  {
    if(!is_border(h, mesh) || seen[h])
      continue;
    double length = 0;
    for(halfedge_descriptor g : CGAL::halfedges_around_face(h, mesh))
    {
      seen[g] = true;
      length += std::sqrt(CGAL::squared_distance(mesh.point(source(g, mesh)), mesh.point(target(g, mesh))));
    }
    if(length < shortest_length)
    {
      shortest_length = length;
      shortest = h;
    }
  }
  auto uv = add_uv_map(mesh);
  const ICM::Circle_domain condition(ICM::Circle_domain::Outer_loop::Of_border_halfedge);
  const Outcome run =
    parameterize(mesh, Parameterizer<ICM::Circle_domain>(ICM::Parameterization_options(), {}, condition), uv, shortest);
  ASSERT_EQ(run.status, SMP::OK) << run.report.message;
  EXPECT_EQ(negative_and_zero_faces(mesh, uv), std::make_pair(0, 0));
  std::vector<vertex_descriptor> given;
  for(halfedge_descriptor g : CGAL::halfedges_around_face(shortest, mesh))
    given.push_back(target(g, mesh));
  const Circle_fit outer = fit_circle(given, uv);
  for(const auto& loop : border_loops(mesh))
  {
    const Circle_fit c = fit_circle(loop, uv);
    EXPECT_LE(c.deviation, 1e-8);
    EXPECT_LE(c.radius, outer.radius);
  }
}

TEST(BorderConditionRefusals, BadCombinationsSayWhy)
{
  Surface_mesh pig;
  ASSERT_TRUE(read_mesh("pig.off", pig));
  auto uv = add_uv_map(pig);
  // Several loops: only the circle domain takes them.
  const Outcome free = parameterize(pig, Parameterizer<CGAL::Default>(), uv);
  EXPECT_EQ(free.status, SMP::ERROR_NO_TOPOLOGICAL_DISC);
  EXPECT_NE(free.report.message.find("not a disk"), std::string::npos) << free.report.message;
  const Outcome square = parameterize(pig, Parameterizer<ICM::Square_border<Surface_mesh>>(), uv);
  EXPECT_EQ(square.status, SMP::ERROR_NO_TOPOLOGICAL_DISC);
  EXPECT_NE(square.report.message.find("one border loop"), std::string::npos) << square.report.message;
  // A prescribed border leaves no choice to another energy.
  const Outcome energy = parameterize(pig, Parameterizer<ICM::Circle_domain, ICM::Log_area_distortion>(), uv);
  EXPECT_EQ(energy.status, SMP::ERROR_WRONG_PARAMETER);
  EXPECT_NE(energy.report.message.find("only the default entropy"), std::string::npos) << energy.report.message;

  // Genus 2 with a border: not a circle domain.
  Surface_mesh eight;
  ASSERT_TRUE(read_mesh("eight.off", eight));
  CGAL::Euler::remove_face(halfedge(*faces(eight).begin(), eight), eight);
  auto uv8 = add_uv_map(eight);
  const Outcome genus = parameterize(eight, Parameterizer<ICM::Circle_domain>(), uv8);
  EXPECT_EQ(genus.status, SMP::ERROR_NO_TOPOLOGICAL_DISC);
  EXPECT_NE(genus.report.message.find("needs genus 0"), std::string::npos) << genus.report.message;
}

TEST(BorderConditionRefusals, AFaceWithEveryCornerOnAHoleIsRefusedByName)
{
  // A hole where an interior vertex's star was, but for one face: that face's corners are all
  // on the hole's loop, so on the hole's circle it would lie in the hole. Refused by name
  // before any solve (it used to fail as flipped faces, then in the circle packing's Newton).
  Surface_mesh mesh;
  ASSERT_TRUE(read_mesh("nefertiti.off", mesh));
  vertex_descriptor centre = Surface_mesh::null_vertex();
  for(vertex_descriptor v : vertices(mesh))
    if(!is_border(v, mesh) && degree(v, mesh) >= 5 &&
       std::none_of(CGAL::vertices_around_target(v, mesh).begin(), CGAL::vertices_around_target(v, mesh).end(),
                    [&](vertex_descriptor w) { return is_border(w, mesh); }))
    {
      centre = v;
      break;
    }
  ASSERT_NE(centre, Surface_mesh::null_vertex());
  std::vector<Surface_mesh::Face_index> star;
  for(auto f : CGAL::faces_around_target(halfedge(centre, mesh), mesh))
    star.push_back(f);
  for(std::size_t i = 1; i < star.size(); ++i)
    CGAL::Euler::remove_face(halfedge(star[i], mesh), mesh);
  mesh.collect_garbage();
  auto uv = add_uv_map(mesh);
  const Outcome run = parameterize(mesh, Parameterizer<ICM::Circle_domain>(), uv);
  EXPECT_EQ(run.status, SMP::ERROR_NO_1_TO_1_MAPPING) << run.report.message;
  EXPECT_NE(run.report.message.find("all three corners on one hole's border"), std::string::npos) << run.report.message;
  EXPECT_EQ(run.report.fallback_reason, "") << "refused before any solve";
}
