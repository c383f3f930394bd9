// The one call for any mesh, `ICM::parameterize`, on every topology: closed genus 0 (cones
// and a seam tree), torus (no cone needed), genus 2 and 3 (homology generators), several
// boundaries, several components; user cones; the refusals; the result read back through a
// `CGAL::Seam_mesh` and on `Polyhedron_3`; energies other than the entropy on every topology.

#include <ICM/IO/read_seam_selection.h>
#include <ICM/measures/Distortion.h>
#include <ICM/Inverse_curvature_map_parameterizer_3.h>
#include <ICM/parameterize.h>

#include <CGAL/Polyhedron_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <CGAL/boost/graph/Seam_mesh.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/io.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point_2 = Kernel::Point_2;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;

Mesh read(const std::string& path)
{
  Mesh mesh;
  EXPECT_TRUE(CGAL::IO::read_polygon_mesh(path, mesh)) << path;
  return mesh;
}

struct Result
{
  ICM::Surface_parameterization_report report;
  ICM::Distortion_measures measures;
  std::vector<Mesh::Edge_index> seams;
};

/// Parameterizes (with `Energy`, the entropy by default) and checks what every result must
/// satisfy: success, every chart without flipped faces, crossing borders or unequal seam
/// sides, every corner with a finite UV.
template <class Energy = CGAL::Default>
Result run(Mesh& mesh, const std::string& what, const ICM::Surface_parameterization_options& options = {},
           const std::map<Mesh::Vertex_index, double>& cones = {}, const std::vector<Mesh::Edge_index>& user_seams = {},
           const typename CGAL::Default::Get<Energy, ICM::Curvature_entropy>::type& energy =
             typename CGAL::Default::Get<Energy, ICM::Curvature_entropy>::type())
{
  auto uv = mesh.add_property_map<Mesh::Halfedge_index, Point_2>("h:test_uv", Point_2(NAN, NAN)).first;
  Result r;
  r.report =
    ICM::parameterize<CGAL::Default, CGAL::Default, Energy>(mesh, uv, options, cones, &r.seams, user_seams, energy);
  EXPECT_EQ(r.report.status, CGAL::Surface_mesh_parameterization::OK) << what << ": " << r.report.message;
  if(r.report.status != CGAL::Surface_mesh_parameterization::OK)
    return r;
  for(const ICM::Chart_report& c : r.report.charts)
  {
    EXPECT_EQ(c.flipped_faces, 0) << what;
    EXPECT_LT(c.seam_length_error, 1e-9) << what;
    EXPECT_LT(c.max_curvature_error, 1e-9) << what;
    EXPECT_EQ(c.overlapping_border_edges, 0) << what;
  }
  for(Mesh::Halfedge_index h : halfedges(mesh))
  {
    if(!is_border(h, mesh))
    {
      EXPECT_TRUE(std::isfinite(uv[h].x()) && std::isfinite(uv[h].y())) << what;
    }
  }
  r.measures = ICM::measure_distortion_corner_uv(mesh, uv);
  EXPECT_EQ(r.measures.flipped_faces, 0u) << what;
  return r;
}

/// Sum of the cone curvatures plus the border's: Gauss-Bonnet over the whole surface.
double total_cone_curvature(const ICM::Chart_report& c)
{
  double sum = 0;
  for(double k : c.cone_curvatures)
    sum += k;
  return sum;
}

/// Cones of 270 degrees (curvature pi/2) at the six extremes of the mesh's axes.
std::map<Mesh::Vertex_index, double> cones_at_axis_extremes(const Mesh& mesh)
{
  std::map<Mesh::Vertex_index, double> cones;
  for(int axis = 0; axis < 3; ++axis)
    for(int sign : {-1, 1})
    {
      Mesh::Vertex_index best;
      double extreme = -HUGE_VAL;
      for(Mesh::Vertex_index v : vertices(mesh))
        if(sign * mesh.point(v)[axis] > extreme)
        {
          extreme = sign * mesh.point(v)[axis];
          best = v;
        }
      cones[best] = M_PI / 2;
    }
  return cones;
}

TEST(Surfaces, BothEntryPointsSolveADiskAlike)
{
  // One chart solver serves both: a disk without cones gets the same optimum from the disk
  // parameterizer and from ICM::parameterize, laid out alike up to a rigid motion and the
  // packing's scale (every UV edge length in one ratio), with the same figures.
  for(const std::string name : {"nefertiti.off", "three_peaks.off"})
  {
    Mesh mesh = read(icm_test::data_path(name));
    auto vertex_uv = mesh.add_property_map<Mesh::Vertex_index, Point_2>("v:uv").first;
    ICM::Inverse_curvature_map_parameterizer_3<Mesh> disk;
    const auto bhd = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
    ASSERT_EQ(CGAL::Surface_mesh_parameterization::parameterize(mesh, disk, bhd, vertex_uv),
              CGAL::Surface_mesh_parameterization::OK)
      << disk.report().message;
    ICM::Surface_parameterization_options no_cones;
    no_cones.automatic_cones = false;
    no_cones.remove_overlaps = false; // the disk parameterizer only counts them
    auto corner_uv = mesh.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
    const ICM::Surface_parameterization_report surface = ICM::parameterize(mesh, corner_uv, no_cones);
    ASSERT_EQ(surface.status, CGAL::Surface_mesh_parameterization::OK) << surface.message;
    ASSERT_EQ(surface.charts.size(), 1u);
    const ICM::Chart_report& chart = surface.charts[0];
    EXPECT_EQ(chart.metric, disk.report().metric) << name;
    EXPECT_EQ(chart.newton_iterations, disk.report().newton_iterations) << name;
    EXPECT_EQ(chart.moved_vertices, disk.report().moved_vertices) << name;
    EXPECT_EQ(chart.overlapping_border_edges, disk.report().overlapping_border_edges) << name;
    EXPECT_NEAR(chart.max_curvature_error, disk.report().max_curvature_error, 1e-15) << name;
    double low = HUGE_VAL, high = 0;
    for(auto h : mesh.halfedges())
    {
      if(mesh.is_border(h))
        continue;
      const Point_2 a = get(corner_uv, mesh.prev(h)), b = get(corner_uv, h);
      const Point_2 p = get(vertex_uv, mesh.source(h)), q = get(vertex_uv, mesh.target(h));
      const double ratio = std::sqrt(CGAL::squared_distance(a, b) / CGAL::squared_distance(p, q));
      low = std::min(low, ratio);
      high = std::max(high, ratio);
    }
    EXPECT_LT(high / low - 1, 1e-9) << name << ": the two layouts are not one metric";
  }
}

TEST(Surfaces, ClosedSphereIsCutThroughItsCones)
{
  Mesh mesh = read(icm_test::data_path("sphere966.off"));
  const Result r = run(mesh, "sphere966");
  ASSERT_EQ(r.report.charts.size(), 1u);
  const ICM::Chart_report& c = r.report.charts[0];
  EXPECT_EQ(c.genus, 0);
  EXPECT_GE(c.cones.size(), 2u);
  // No border: all of 2 pi chi = 4 pi sits on the cones.
  EXPECT_NEAR(total_cone_curvature(c), 4 * M_PI, 1e-8);
  EXPECT_EQ(c.homology_generators, 0);
  EXPECT_GT(c.seam_edges, 0);
  EXPECT_EQ(static_cast<int>(r.seams.size()), c.seam_edges);
  EXPECT_EQ(c.overlapping_border_edges, 0);
  // Measured: 6 cones, qc mean 1.067.
  EXPECT_LT(r.measures.qc_mean, 1.2);
}

TEST(Surfaces, TorusNeedsNoConeAndTwoGenerators)
{
  Mesh mesh = read(icm_test::data_path("rotor.off"));
  ICM::Surface_parameterization_options options;
  options.automatic_cones = false;
  const Result r = run(mesh, "rotor", options);
  ASSERT_EQ(r.report.charts.size(), 1u);
  const ICM::Chart_report& c = r.report.charts[0];
  EXPECT_EQ(c.genus, 1);
  EXPECT_EQ(c.homology_generators, 2);
  // No cone: K^{-1}(0) is flat everywhere (one vertex pinned, flat by Gauss-Bonnet), and the
  // cut is the two generators alone.
  EXPECT_TRUE(c.cones.empty());
  EXPECT_GT(c.seam_edges, 0);
}

TEST(Surfaces, GenusTwoAndThreeGetTheirGenerators)
{
  std::vector<std::pair<std::string, int>> cases = {{icm_test::data_path("eight.off"), 2}};
  if(icm_test::shared_dir_exists())
    cases.push_back({icm_test::shared_path("elephant.off"), 3});
  for(const auto& [path, genus] : cases)
  {
    Mesh mesh = read(path);
    const Result r = run(mesh, path);
    ASSERT_EQ(r.report.charts.size(), 1u);
    const ICM::Chart_report& c = r.report.charts[0];
    EXPECT_EQ(c.genus, genus) << path;
    EXPECT_EQ(c.homology_generators, 2 * genus) << path;
    EXPECT_NEAR(total_cone_curvature(c), 2 * M_PI * (2 - 2 * genus), 1e-8) << path;
  }
}

TEST(Surfaces, SeveralBoundariesAreJoinedIntoOneDisk)
{
  Mesh mesh = read(icm_test::data_path("pig.off"));
  const Result r = run(mesh, "pig");
  ASSERT_EQ(r.report.charts.size(), 1u);
  const ICM::Chart_report& c = r.report.charts[0];
  EXPECT_EQ(c.boundary_loops, 7);
  EXPECT_GE(c.seam_edges, 6); // at least one path per extra loop
  EXPECT_EQ(c.overlapping_border_edges, 0);
  // The automatic count wants 8 cones here, and the map with all 8 folds over itself: the
  // default keeps the most cones that lay out in one piece (4 when measured) rather than
  // cutting the pig into charts. An exact count is the user's and is kept.
  EXPECT_EQ(c.pieces, 1);
  EXPECT_GT(c.cones_given_up, 0);
  EXPECT_GE(c.cones.size(), 1u);

  ICM::Surface_parameterization_options exact;
  exact.cones.max_cones = static_cast<int>(c.cones.size()) + c.cones_given_up;
  exact.cones.max_log_scale = 0;
  exact.border_max_log_scale = 0;
  const Result all = run(mesh, "pig, exact count", exact);
  ASSERT_EQ(all.report.charts.size(), 1u);
  EXPECT_EQ(all.report.charts[0].cones.size(), static_cast<std::size_t>(exact.cones.max_cones));
  EXPECT_EQ(all.report.charts[0].cones_given_up, 0);
  EXPECT_EQ(all.report.charts[0].overlapping_border_edges, 0);
  EXPECT_GT(all.report.charts[0].pieces, 1);
}

TEST(Surfaces, SeveralComponentsArePackedSideBySide)
{
  // A sphere and a disk in one mesh, both at their 3D scale, boxes apart.
  Mesh mesh = read(icm_test::data_path("sphere966.off"));
  Mesh disk = read(icm_test::data_path("nefertiti.off"));
  CGAL::copy_face_graph(disk, mesh);
  const Result r = run(mesh, "sphere + nefertiti");
  ASSERT_EQ(r.report.charts.size(), 2u);
  auto uv = mesh.property_map<Mesh::Halfedge_index, Point_2>("h:test_uv").first;
  // The two charts' UV boxes do not meet.
  std::vector<CGAL::Bbox_2> boxes(2);
  auto component = mesh.add_property_map<Mesh::Face_index, std::size_t>("f:cc").first;
  CGAL::Polygon_mesh_processing::connected_components(mesh, component);
  for(Mesh::Face_index f : faces(mesh))
    for(Mesh::Halfedge_index h : CGAL::halfedges_around_face(halfedge(f, mesh), mesh))
      boxes[component[f]] += uv[h].bbox();
  EXPECT_FALSE(CGAL::do_overlap(boxes[0], boxes[1]));
  EXPECT_EQ(r.report.charts[1].cones.size() + r.report.charts[0].cones.size() >= 2, true);
}

// Two copies of nefertiti, one 1e200 times the other: in one UV map at their 3D scales the
// small one would round to a point, so it is refused, and the reason says so (not that its
// faces have no area, which in its own frame they have).
TEST(Surfaces, AComponentTooSmallBesideTheRestIsRefusedByItsScale)
{
  Mesh mesh = read(icm_test::data_path("nefertiti.off"));
  Mesh big = mesh;
  for(Mesh::Vertex_index v : vertices(big))
    big.point(v) = Kernel::Point_3(1e200 * big.point(v).x(), 1e200 * big.point(v).y(), 1e200 * big.point(v).z());
  CGAL::copy_face_graph(big, mesh);
  auto uv = mesh.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
  const ICM::Surface_parameterization_report report = ICM::parameterize(mesh, uv);
  EXPECT_EQ(report.status, CGAL::Surface_mesh_parameterization::ERROR_WRONG_PARAMETER);
  EXPECT_NE(report.message.find("component 0: "), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("1e-200 times the size of the mesh, too small to share one UV map"), std::string::npos)
    << report.message;
}

TEST(Surfaces, UserConesWithPrescribedAndFreeAngles)
{
  // Six cones of 270 degrees at the extremes of the sphere's axes carry 6 x pi/2 = 3 pi...
  // not 4 pi: Gauss-Bonnet refuses them. With one more cone whose angle is free, the
  // optimum gives it the missing pi, and every prescribed angle is met.
  Mesh mesh = read(icm_test::data_path("sphere966.off"));
  std::map<Mesh::Vertex_index, double> cones = cones_at_axis_extremes(mesh);
  ASSERT_EQ(cones.size(), 6u);
  ICM::Surface_parameterization_options options;
  options.automatic_cones = false;
  auto uv = mesh.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
  const auto refused = ICM::parameterize(mesh, uv, options, cones);
  EXPECT_NE(refused.status, CGAL::Surface_mesh_parameterization::OK);
  EXPECT_NE(refused.message.find("Gauss-Bonnet"), std::string::npos) << refused.message;

  Mesh::Vertex_index free_cone(0);
  while(cones.count(free_cone))
    free_cone = Mesh::Vertex_index(std::size_t(free_cone) + 1);
  cones[free_cone] = std::nan("");
  const Result r = run(mesh, "user cones", options, cones);
  ASSERT_EQ(r.report.charts.size(), 1u);
  const ICM::Chart_report& c = r.report.charts[0];
  ASSERT_EQ(c.cones.size(), 7u);
  int prescribed_met = 0;
  for(double k : c.cone_curvatures)
    prescribed_met += std::abs(k - M_PI / 2) < 1e-8;
  EXPECT_EQ(prescribed_met, 6);
  EXPECT_NEAR(total_cone_curvature(c), 4 * M_PI, 1e-8);
}

TEST(Surfaces, BadConesAreRefusedWithAReason)
{
  Mesh disk = read(icm_test::data_path("nefertiti.off"));
  auto uv = disk.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
  Mesh::Vertex_index border;
  for(Mesh::Vertex_index v : vertices(disk))
    if(is_border(v, disk))
      border = v;
  auto r = ICM::parameterize(disk, uv, {}, {{border, 0.5}});
  EXPECT_EQ(r.status, CGAL::Surface_mesh_parameterization::ERROR_WRONG_PARAMETER);
  EXPECT_NE(r.message.find("boundary vertex"), std::string::npos) << r.message;

  Mesh sphere = read(icm_test::data_path("sphere966.off"));
  auto uv2 = sphere.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
  r = ICM::parameterize(sphere, uv2, {}, {{Mesh::Vertex_index(3), 2 * M_PI}}); // angle 0
  EXPECT_EQ(r.status, CGAL::Surface_mesh_parameterization::ERROR_WRONG_PARAMETER);
  EXPECT_NE(r.message.find("positive"), std::string::npos) << r.message;

  ICM::Surface_parameterization_options no_cones;
  no_cones.automatic_cones = false;
  r = ICM::parameterize(sphere, uv2, no_cones);
  EXPECT_NE(r.status, CGAL::Surface_mesh_parameterization::OK);
  EXPECT_NE(r.message.find("at least two cones"), std::string::npos) << r.message;

  Mesh empty;
  auto uv3 = empty.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
  EXPECT_EQ(ICM::parameterize(empty, uv3).status, CGAL::Surface_mesh_parameterization::ERROR_EMPTY_MESH);
}

TEST(Surfaces, UserSeamsFromASelectionFileAreTakenAsGiven)
{
  // A star of four shortest paths from the sphere's top to four far vertices (a CGAL
  // selection file): the cut is exactly these 44 edges, and its four ends and its centre
  // (seam degree 4) are the only cones, their angles left to the optimum.
  Mesh mesh = read(icm_test::data_path("sphere966.off"));
  std::vector<Mesh::Edge_index> user_seams;
  std::string error;
  ASSERT_TRUE(ICM::IO::read_seam_selection(icm_test::data_path("sphere966.selection.txt"), mesh, user_seams, error))
    << error;
  ASSERT_EQ(user_seams.size(), 44u);
  const Result r = run(mesh, "sphere966 with user seams", {}, {}, user_seams);
  ASSERT_EQ(r.report.charts.size(), 1u);
  const ICM::Chart_report& c = r.report.charts[0];
  EXPECT_EQ(std::set<Mesh::Edge_index>(r.seams.begin(), r.seams.end()),
            std::set<Mesh::Edge_index>(user_seams.begin(), user_seams.end()));
  EXPECT_EQ(c.cones.size(), 5u);
  EXPECT_NEAR(total_cone_curvature(c), 4 * M_PI, 1e-8);
  for(double k : c.cone_curvatures)
    EXPECT_LT(k, 2 * M_PI) << "a cone of angle <= 0";
  // The seam length is the seams' 3D length over the square root of the 3D area.
  double length = 0;
  for(Mesh::Edge_index e : user_seams)
    length += std::sqrt(CGAL::squared_distance(mesh.point(source(e, mesh)), mesh.point(target(e, mesh))));
  EXPECT_NEAR(c.seam_length, length / std::sqrt(CGAL::Polygon_mesh_processing::area(mesh)), 1e-12);
}

TEST(Surfaces, ConesFromASelectionFileAreTheConesOfTheMap)
{
  // CGAL's orbifold examples give the cones as a selection file's first line: read, they are
  // user cones whose angles the optimum chooses, and with automatic cones off they are the
  // map's only cones, the cut joining them.
  Mesh mesh = read(icm_test::data_path("sphere966.off"));
  icm_test::Scratch_directory dir("icm_cones");
  const std::string path = (dir.path() / "cones.selection.txt").string();
  icm_test::write_text(path, "458 198 166 484\n"); // the vertices farthest along a tetrahedron's directions
  std::vector<Mesh::Vertex_index> cones;
  std::vector<Mesh::Edge_index> seams;
  std::string error;
  ASSERT_TRUE(ICM::IO::read_selection(path, mesh, cones, seams, error)) << error;
  ASSERT_EQ(cones.size(), 4u);
  EXPECT_TRUE(seams.empty());
  std::map<Mesh::Vertex_index, double> user_cones;
  for(Mesh::Vertex_index v : cones)
    user_cones[v] = std::nan("");
  ICM::Surface_parameterization_options options;
  options.automatic_cones = false;
  const Result r = run(mesh, "sphere966 with the cones of a selection file", options, user_cones);
  ASSERT_EQ(r.report.charts.size(), 1u);
  const ICM::Chart_report& c = r.report.charts[0];
  ASSERT_EQ(c.cones.size(), 4u);
  EXPECT_NEAR(total_cone_curvature(c), 4 * M_PI, 1e-8);
  EXPECT_EQ(r.measures.flipped_faces, 0u);
  EXPECT_GT(r.seams.size(), 0u);
}

TEST(Surfaces, UserSeamsThatDoNotCutADiskAreRefused)
{
  Mesh eight = read(icm_test::data_path("eight.off"));
  auto uv = eight.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
  // One edge of a genus-2 surface: a slit, the genus stays.
  const auto slit = ICM::parameterize(eight, uv, {}, {}, nullptr, {*edges(eight).begin()});
  EXPECT_NE(slit.status, CGAL::Surface_mesh_parameterization::OK);
  EXPECT_NE(slit.message.find("genus"), std::string::npos) << slit.message;

  Mesh disk = read(icm_test::data_path("nefertiti.off"));
  auto uv2 = disk.add_property_map<Mesh::Halfedge_index, Point_2>("h:uv").first;
  Mesh::Edge_index border_edge;
  for(Mesh::Edge_index e : edges(disk))
    if(is_border(e, disk))
      border_edge = e;
  const auto border = ICM::parameterize(disk, uv2, {}, {}, nullptr, {border_edge});
  EXPECT_EQ(border.status, CGAL::Surface_mesh_parameterization::ERROR_WRONG_PARAMETER);
  EXPECT_NE(border.message.find("border edge"), std::string::npos) << border.message;
}

TEST(Surfaces, FlippedFacesOnASeamAreUnflippedWithTheirTwin)
{
  // cow and elk: with 32 cones, faces that the intrinsic Delaunay triangulation does not
  // have come out flipped next to a seam. Moving the seam vertex alone would part the seam's
  // sides; it moves with its twin by the seam's rigid motion, so the default metric keeps
  // its optimum (it fell back to the circle packing, QC 1.87 and 1.79, before).
  if(!icm_test::shared_dir_exists())
    GTEST_SKIP() << "shared meshes not found";
  ICM::Surface_parameterization_options exact_greedy; // the cones that showed the fault
  exact_greedy.cones.placement = ICM::Cone_placement::Exact_optimum;
  for(const char* name : {"cow.off", "elk.off"})
  {
    Mesh mesh = read(icm_test::shared_path(name));
    const Result r = run(mesh, name, exact_greedy);
    ASSERT_EQ(r.report.charts.size(), 1u) << name;
    const ICM::Chart_report& c = r.report.charts[0];
    EXPECT_EQ(c.metric, ICM::Intrinsic_delaunay_metric::name) << name << ": " << c.fallback_reason;
    EXPECT_GT(c.moved_vertices, 0) << name;
    EXPECT_LT(r.measures.qc_mean, 1.35) << name; // measured 1.173 and 1.297
  }
}

TEST(Surfaces, ResultReadsBackThroughASeamMesh)
{
  // The halfedge UV map and the seam edges are CGAL's own representation: a Seam_mesh over
  // the mesh with those seams sees one UV per seam-mesh vertex, and its distortion equals
  // the corner measure.
  Mesh mesh = read(icm_test::data_path("eight.off"));
  const Result r = run(mesh, "eight");
  auto uv = mesh.property_map<Mesh::Halfedge_index, Point_2>("h:test_uv").first;
  auto seam_edge = mesh.add_property_map<Mesh::Edge_index, bool>("e:seam", false).first;
  auto seam_vertex = mesh.add_property_map<Mesh::Vertex_index, bool>("v:seam", false).first;
  using Seam_mesh = CGAL::Seam_mesh<Mesh, decltype(seam_edge), decltype(seam_vertex)>;
  Seam_mesh seam_mesh(mesh, seam_edge, seam_vertex);
  for(Mesh::Edge_index e : r.seams)
    seam_mesh.add_seam(source(e, mesh), target(e, mesh));
  EXPECT_EQ(seam_mesh.number_of_seam_edges(), r.seams.size());
  const ICM::Distortion_measures through_seams = ICM::measure_distortion(seam_mesh, uv);
  EXPECT_EQ(through_seams.flipped_faces, 0u);
  EXPECT_NEAR(through_seams.qc_mean, r.measures.qc_mean, 1e-12);
  EXPECT_NEAR(through_seams.log_area_distortion, r.measures.log_area_distortion, 1e-12);
}

TEST(Surfaces, PolyhedronTakesTheSameCall)
{
  Polyhedron poly;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(icm_test::data_path("rotor.off"), poly));
  std::map<Polyhedron::Halfedge_handle, Point_2> corners;
  auto uv = boost::make_assoc_property_map(corners);
  const auto report = ICM::parameterize(poly, uv);
  ASSERT_EQ(report.status, CGAL::Surface_mesh_parameterization::OK) << report.message;
  ASSERT_EQ(report.charts.size(), 1u);
  EXPECT_EQ(report.charts[0].homology_generators, 2);
  EXPECT_EQ(report.charts[0].flipped_faces, 0);
  EXPECT_EQ(ICM::measure_distortion_corner_uv(poly, uv).flipped_faces, 0u);
}

TEST(Surfaces, OverlappingStripIsCutAtItsNarrowestRung)
{
  // A strip of 50 quads laid out on an annulus over 1.25 turns: its last quarter turn lies
  // on its first. The 3D strip is narrowest at rung 25, so the shortest seam that separates
  // the two layers is that one rung, and each half (1.25 pi) is free of overlaps.
  const int n = 50;
  ICM::internal::Mesh_index strip;
  std::vector<ICM::Uv> uv;
  for(int i = 0; i <= n; ++i)
  {
    const double width = 1 + std::abs(i - n / 2) / double(n / 2), angle = 2.5 * M_PI * i / n;
    strip.points.push_back({double(i), 0, 0});     // a_i, outer radius 3
    strip.points.push_back({double(i), width, 0}); // b_i, inner radius 2
    uv.push_back({3 * std::cos(angle), 3 * std::sin(angle)});
    uv.push_back({2 * std::cos(angle), 2 * std::sin(angle)});
  }
  for(int i = 0; i < n; ++i)
  {
    strip.faces.push_back({2 * i, 2 * i + 2, 2 * i + 3});
    strip.faces.push_back({2 * i, 2 * i + 3, 2 * i + 1});
  }
  ASSERT_TRUE(ICM::internal::build_connectivity(strip).ok());
  ICM::Cut_mesh cut = ICM::cut_mesh(strip, std::vector<char>(strip.number_of_edges(), 0));
  ASSERT_TRUE(cut.ok());
  ASSERT_GT(ICM::count_border_overlaps(cut.disk, uv).crossing_pairs, 0);
  const std::vector<ICM::Uv> before = uv;
  const ICM::internal::Mesh_index disk_before = cut.disk;

  const ICM::Overlap_removal removal = ICM::remove_overlaps(strip, cut, uv);
  ASSERT_TRUE(cut.ok()) << cut.status.message;
  EXPECT_EQ(removal.pieces, 2);
  EXPECT_EQ(removal.cut_edges, 1);
  EXPECT_EQ(removal.overlapping_face_pairs, 0);
  EXPECT_EQ(ICM::count_border_overlaps(cut.disk, uv).crossing_pairs, 0);
  EXPECT_TRUE(ICM::overlapping_face_pairs(cut.disk, uv).empty());
  // The seam is the rung between quads 24 and 25, with equal sides.
  int seams = 0;
  for(int e = 0; e < strip.number_of_edges(); ++e)
    if(cut.disk_edges[e][1] >= 0)
    {
      ++seams;
      EXPECT_EQ(strip.edges[e], (std::array<int, 2>{n, n + 1}));
      auto side = [&](int d) {
        const ICM::Uv &p = uv[cut.disk.edges[d][0]], &q = uv[cut.disk.edges[d][1]];
        return std::hypot(p[0] - q[0], p[1] - q[1]);
      };
      EXPECT_NEAR(side(cut.disk_edges[e][0]), side(cut.disk_edges[e][1]), 1e-12);
    }
  EXPECT_EQ(seams, 1);
  // Every face keeps its shape: its UV edges are those of the raw layout.
  for(int f = 0; f < strip.number_of_faces(); ++f)
    for(int c = 0; c < 3; ++c)
    {
      const int a = cut.disk.faces[f][c], b = cut.disk.faces[f][(c + 1) % 3];
      const int a0 = disk_before.faces[f][c], b0 = disk_before.faces[f][(c + 1) % 3];
      EXPECT_NEAR(uv[b][0] - uv[a][0], before[b0][0] - before[a0][0], 1e-12);
      EXPECT_NEAR(uv[b][1] - uv[a][1], before[b0][1] - before[a0][1], 1e-12);
    }
}

TEST(Surfaces, HorseOverlapIsRemovedByDefaultAndKeptOnRequest)
{
  // The shared horse's free-boundary optimum swings its legs over each other (16 pairs of
  // crossing border edges): by default the chart is cut into pieces that do not overlap,
  // with the same distortion; `remove_overlaps = false` keeps the raw optimum.
  if(!icm_test::shared_dir_exists())
    GTEST_SKIP() << "shared meshes not present";
  Mesh mesh = read(icm_test::shared_path("horse.obj"));
  ICM::Surface_parameterization_options free_border;
  free_border.automatic_cones = false;
  const Result removed = run(mesh, "horse", free_border);
  ASSERT_EQ(removed.report.charts.size(), 1u);
  const ICM::Chart_report& c = removed.report.charts[0];
  EXPECT_GT(c.raw_overlapping_border_edges, 0);
  EXPECT_GE(c.pieces, 2);
  EXPECT_GE(c.overlap_cut_edges, 1);
  EXPECT_EQ(c.seam_edges, c.overlap_cut_edges); // a disk: the only seams are the cuts

  ICM::Surface_parameterization_options keep = free_border;
  keep.remove_overlaps = false;
  auto uv = mesh.add_property_map<Mesh::Halfedge_index, Point_2>("h:raw_uv", Point_2(NAN, NAN)).first;
  const auto raw = ICM::parameterize(mesh, uv, keep);
  ASSERT_EQ(raw.status, CGAL::Surface_mesh_parameterization::OK) << raw.message;
  EXPECT_EQ(raw.charts[0].pieces, 1);
  EXPECT_EQ(raw.charts[0].overlapping_border_edges, c.raw_overlapping_border_edges);
  const ICM::Distortion_measures raw_measures = ICM::measure_distortion_corner_uv(mesh, uv);
  EXPECT_NEAR(raw_measures.qc_mean, removed.measures.qc_mean, 1e-9);
  EXPECT_NEAR(raw_measures.log_area_distortion, removed.measures.log_area_distortion, 1e-9);
}

// --- Energies other than the entropy ------------------------------------------------------

/// Two runs of one mesh with different energies placed the same cones: each chart keeps a
/// prefix of one greedy sequence, since whether cones are given up to lay a surface with a
/// border out in one piece is judged on each energy's own map (the pig's entropy map folds
/// with all 8 cones, its log-area map does not).
void expect_same_placement(const Result& a, const Result& b, const std::string& what)
{
  for(std::size_t i = 0; i < a.report.charts.size(); ++i)
  {
    const ICM::Chart_report& x = a.report.charts[i];
    const ICM::Chart_report& y = b.report.charts[i];
    EXPECT_EQ(x.cones.size() + x.cones_given_up, y.cones.size() + y.cones_given_up) << what;
    std::vector<int> fewer = x.cones.size() < y.cones.size() ? x.cones : y.cones;
    std::vector<int> more = x.cones.size() < y.cones.size() ? y.cones : x.cones;
    std::sort(fewer.begin(), fewer.end());
    std::sort(more.begin(), more.end());
    EXPECT_TRUE(std::includes(more.begin(), more.end(), fewer.begin(), fewer.end())) << what;
  }
}

TEST(Surfaces, LogAreaEnergyLowersAreaDistortionOnEveryTopology)
{
  // The log area distortion, minimised over the border and the cones the entropy's run
  // chose, measured by the independent evaluator of the output (Distortion.h): closed genus
  // 0, seven holes, torus, genus 2. Cut through the cones, the development it optimises is
  // the layout: 0 flipped faces, equal seam sides, flat off the cones (checked by `run`).
  for(const char* name : {"sphere966.off", "pig.off", "rotor.off", "eight.off"})
  {
    Mesh mesh = read(icm_test::data_path(name));
    const Result entropy = run(mesh, name);
    const Result log_area = run<ICM::Log_area_distortion>(mesh, std::string(name) + ", log-area");
    ASSERT_EQ(log_area.report.charts.size(), entropy.report.charts.size()) << name;
    expect_same_placement(log_area, entropy, name);
    for(const ICM::Chart_report& c : log_area.report.charts)
    {
      EXPECT_GT(c.energy_iterations, 0) << name;
      EXPECT_LT(c.final_energy, c.initial_energy) << name;
      // Gauss-Bonnet holds at the new metric: the cones and the border carry 2 pi chi.
      EXPECT_LT(c.max_curvature_error, 1e-9) << name;
    }
    EXPECT_LT(log_area.measures.log_area_distortion, entropy.measures.log_area_distortion) << name;
  }
  // Several components: each is optimised on its own (a sphere with its cones, a disk on its
  // border).
  Mesh mesh = read(icm_test::data_path("sphere966.off"));
  CGAL::copy_face_graph(read(icm_test::data_path("nefertiti.off")), mesh);
  const Result both = run<ICM::Log_area_distortion>(mesh, "sphere + nefertiti, log-area");
  ASSERT_EQ(both.report.charts.size(), 2u);
  for(const ICM::Chart_report& c : both.report.charts)
  {
    EXPECT_GT(c.energy_iterations, 0);
    EXPECT_LT(c.final_energy, c.initial_energy);
  }
}

TEST(Surfaces, EnergyOfTheCutDevelopmentIsTheLayoutsOwn)
{
  // With eq. 8's uniform weights the optimizer's final E is the mean log^2 area of the
  // faces the parameterization writes (one chart, nothing moved): the development cut
  // along the seams is the layout, to rounding.
  Mesh mesh = read(icm_test::data_path("sphere966.off"));
  const Result r = run<ICM::Log_area_distortion>(mesh, "sphere966, uniform log-area", {}, {}, {},
                                                 ICM::Log_area_distortion(ICM::Face_weighting::Uniform));
  ASSERT_EQ(r.report.charts.size(), 1u);
  const ICM::Chart_report& c = r.report.charts[0];
  ASSERT_GE(c.cones.size(), 2u);
  ASSERT_EQ(c.moved_vertices, 0);
  EXPECT_NEAR(c.final_energy, r.measures.log_area_distortion, 1e-7 * r.measures.log_area_distortion);
}

TEST(Surfaces, EnergyKeepsTheUserConesAngles)
{
  // Six cones with a fixed angle keep it while the angle energy moves the two whose angle is
  // free (they share the missing pi).
  Mesh mesh = read(icm_test::data_path("sphere966.off"));
  std::map<Mesh::Vertex_index, double> cones = cones_at_axis_extremes(mesh);
  ASSERT_EQ(cones.size(), 6u);
  for(std::size_t v = 0, added = 0; added < 2; v += 400)
    if(cones.emplace(Mesh::Vertex_index(v), std::nan("")).second)
      ++added;
  ICM::Surface_parameterization_options options;
  options.automatic_cones = false;
  const Result r = run<ICM::Angle_distortion>(mesh, "sphere966, angle energy, user cones", options, cones);
  ASSERT_EQ(r.report.charts.size(), 1u);
  const ICM::Chart_report& c = r.report.charts[0];
  ASSERT_EQ(c.cones.size(), 8u);
  EXPECT_GT(c.energy_iterations, 0);
  EXPECT_LT(c.final_energy, c.initial_energy);
  int prescribed_met = 0;
  for(double k : c.cone_curvatures)
    prescribed_met += std::abs(k - M_PI / 2) < 1e-9;
  EXPECT_EQ(prescribed_met, 6);
  EXPECT_NEAR(total_cone_curvature(c), 4 * M_PI, 1e-8);
}

/// A strip one quad wide between the polylines `a` and `b` (a_i b_i is rung i), each quad
/// split in two. Such a strip has no interior vertex, so it is intrinsically flat: its
/// development is an isometric map.
Mesh ribbon(const std::vector<Kernel::Point_3>& a, const std::vector<Kernel::Point_3>& b)
{
  Mesh mesh;
  std::vector<Mesh::Vertex_index> va, vb;
  for(std::size_t i = 0; i < a.size(); ++i)
  {
    va.push_back(mesh.add_vertex(a[i]));
    vb.push_back(mesh.add_vertex(b[i]));
  }
  for(std::size_t i = 0; i + 1 < a.size(); ++i)
  {
    mesh.add_face(va[i], va[i + 1], vb[i + 1]);
    mesh.add_face(va[i], vb[i + 1], vb[i]);
  }
  return mesh;
}

/// The cells of a 2^order x 2^order grid in the order a Hilbert curve visits them.
std::vector<std::array<int, 2>> hilbert_cells(int order)
{
  const int n = 1 << order;
  std::vector<std::array<int, 2>> cells;
  for(int d = 0; d < n * n; ++d)
  {
    int x = 0, y = 0;
    for(int s = 1, t = d; s < n; s *= 2, t /= 4)
    {
      const int rx = 1 & (t / 2), ry = 1 & (t ^ rx);
      if(ry == 0)
      {
        if(rx == 1)
        {
          x = s - 1 - x;
          y = s - 1 - y;
        }
        std::swap(x, y);
      }
      x += s * rx;
      y += s * ry;
    }
    cells.push_back({x, y});
  }
  return cells;
}

/// A planar strip of width `width` centred on the polyline `path` (unit steps along the axes),
/// each step split in `pieces`: the rungs at a corner run along its bisector (mitred).
Mesh strip_along(const std::vector<std::array<int, 2>>& path, double width, int pieces)
{
  std::vector<Kernel::Point_3> a, b;
  auto left_normal = [&](std::size_t k) { // of the step from path[k] to path[k + 1]
    return std::array<double, 2>{double(path[k][1] - path[k + 1][1]), double(path[k + 1][0] - path[k][0])};
  };
  for(std::size_t k = 0; k + 1 < path.size(); ++k)
  {
    EXPECT_EQ(std::abs(path[k + 1][0] - path[k][0]) + std::abs(path[k + 1][1] - path[k][1]), 1) << "step " << k;
    for(int piece = 0; piece < pieces; ++piece)
    {
      const double t = double(piece) / pieces;
      std::array<double, 2> m = left_normal(k);
      if(piece == 0 && k > 0) // the corner's mitre: n_in + n_out over 1 + n_in . n_out
      {
        const std::array<double, 2> n_in = left_normal(k - 1), n_out = m;
        const double scale = 1 / (1 + n_in[0] * n_out[0] + n_in[1] * n_out[1]);
        m = {(n_in[0] + n_out[0]) * scale, (n_in[1] + n_out[1]) * scale};
      }
      const double x = path[k][0] + t * (path[k + 1][0] - path[k][0]);
      const double y = path[k][1] + t * (path[k + 1][1] - path[k][1]);
      a.emplace_back(x - width / 2 * m[0], y - width / 2 * m[1], 0);
      b.emplace_back(x + width / 2 * m[0], y + width / 2 * m[1], 0);
    }
  }
  const std::array<double, 2> m = left_normal(path.size() - 2);
  a.emplace_back(path.back()[0] - width / 2 * m[0], path.back()[1] - width / 2 * m[1], 0);
  b.emplace_back(path.back()[0] + width / 2 * m[0], path.back()[1] + width / 2 * m[1], 0);
  return ribbon(a, b);
}

/// Checks that `mesh` maps to one chart without cones, isometrically (up to the scale).
void expect_isometric_single_chart(Mesh mesh, const std::string& what)
{
  const Result r = run(mesh, what);
  ASSERT_EQ(r.report.charts.size(), 1u) << what;
  EXPECT_TRUE(r.report.charts[0].cones.empty()) << what;
  EXPECT_EQ(r.report.charts[0].metric, "intrinsic-delaunay") << what;
  EXPECT_LT(r.measures.log_area_distortion, 1e-12) << what;
  EXPECT_LT(r.measures.qc_max, 1 + 1e-9) << what;
}

TEST(Surfaces, FlatStripsOfEveryShapeMapToThemselves)
{
  // A strip one quad wide is flat, however it winds: the map is its development. The layout's
  // error estimate overflows some 1200 hops from its root (a 1 x 550 strip used to hang, and so
  // did spirals, helices and a Hilbert-curve strip).
  const int n = 2000; // a 1 x 2000 rectangle of unit squares
  std::vector<Kernel::Point_3> a, b;
  for(int i = 0; i <= n; ++i)
  {
    a.emplace_back(i, 0, 0);
    b.emplace_back(i, 1, 0);
  }
  expect_isometric_single_chart(ribbon(a, b), "1 x 2000 strip");

  // A planar Archimedean spiral of 12 turns, 1 wide and 2 apart: 3072 faces.
  a.clear();
  b.clear();
  for(int i = 0; i <= 12 * 128; ++i)
  {
    const double angle = 2 * M_PI * i / 128, radius = 3 + 2 * angle / (2 * M_PI);
    a.emplace_back((radius - 0.5) * std::cos(angle), (radius - 0.5) * std::sin(angle), 0);
    b.emplace_back((radius + 0.5) * std::cos(angle), (radius + 0.5) * std::sin(angle), 0);
  }
  expect_isometric_single_chart(ribbon(a, b), "12-turn spiral");

  // A helix ribbon of 12 turns on a cylinder of radius 3, 1 wide, climbing 2 per turn.
  a.clear();
  b.clear();
  for(int i = 0; i <= 12 * 64; ++i)
  {
    const double angle = 2 * M_PI * i / 64, height = 2 * angle / (2 * M_PI);
    a.emplace_back(3 * std::cos(angle), 3 * std::sin(angle), height);
    b.emplace_back(3 * std::cos(angle), 3 * std::sin(angle), height + 1);
  }
  expect_isometric_single_chart(ribbon(a, b), "helix ribbon");

  // A strip wound 6 times around a cone of half-angle 30 degrees, 1 wide along the slant,
  // moving 1.5 up the slant per turn: its development is a spiral in a 3 pi sector.
  a.clear();
  b.clear();
  const double sin_half_angle = 0.5, cos_half_angle = std::sqrt(0.75);
  for(int i = 0; i <= 6 * 64; ++i)
  {
    const double angle = 2 * M_PI * i / 64, slant = 4 + 1.5 * angle / (2 * M_PI);
    for(double s : {slant, slant + 1})
      (s == slant ? a : b)
        .emplace_back(s * sin_half_angle * std::cos(angle), s * sin_half_angle * std::sin(angle), s * cos_half_angle);
  }
  expect_isometric_single_chart(ribbon(a, b), "strip wound on a cone");

  // A strip 0.5 wide along the Hilbert curve through 32 x 32 cells: 4092 faces, 512 corners.
  expect_isometric_single_chart(strip_along(hilbert_cells(5), 0.5, 2), "Hilbert-curve strip");
}

TEST(Surfaces, HorseGetsConesByDefaultAndLessAreaDistortion)
{
  // The horse's free-boundary optimum shrinks some areas 230-fold (max |u - u0| = 2.2):
  // by default it gets cones and its area distortion drops below half the free border's
  // (0.115 against 0.296 mean log^2 area by the shared evaluator; BFF's is 0.284).
  if(!icm_test::shared_dir_exists())
    GTEST_SKIP() << "shared meshes not present";
  Mesh mesh = read(icm_test::shared_path("horse.obj"));
  const Result with_cones = run(mesh, "horse");
  ICM::Surface_parameterization_options free_border;
  free_border.automatic_cones = false;
  const Result without = run(mesh, "horse, free border", free_border);
  ASSERT_EQ(with_cones.report.charts.size(), 1u);
  const ICM::Chart_report& c = with_cones.report.charts[0];
  EXPECT_GE(c.cones.size(), 2u);
  EXPECT_EQ(c.overlapping_border_edges, 0);
  EXPECT_LT(with_cones.measures.log_area_distortion, 0.5 * without.measures.log_area_distortion);
  EXPECT_LT(with_cones.measures.qc_mean, 1.05);
}

/// A closed slab with `holes` square holes in a row: a grid of (2 holes + 1) x 3 unit cells,
/// every other middle cell open, top and bottom joined by walls; genus `holes`.
Mesh slab_with_holes(int holes)
{
  Mesh mesh;
  const int nx = 2 * holes + 1, ny = 3;
  const auto solid = [&](int x, int y) { return x >= 0 && x < nx && y >= 0 && y < ny && !(y == 1 && x % 2 == 1); };
  std::map<std::array<int, 3>, Mesh::Vertex_index> at;
  const auto vertex = [&](int x, int y, int z) {
    auto [it, added] = at.emplace(std::array<int, 3>{x, y, z}, Mesh::Vertex_index());
    if(added)
      it->second = mesh.add_vertex(Kernel::Point_3(x, y, 0.5 * z));
    return it->second;
  };
  const auto quad = [&](Mesh::Vertex_index a, Mesh::Vertex_index b, Mesh::Vertex_index c, Mesh::Vertex_index d) {
    mesh.add_face(a, b, c);
    mesh.add_face(a, c, d);
  };
  for(int x = 0; x < nx; ++x)
    for(int y = 0; y < ny; ++y)
    {
      if(!solid(x, y))
        continue;
      quad(vertex(x, y, 1), vertex(x + 1, y, 1), vertex(x + 1, y + 1, 1), vertex(x, y + 1, 1));
      quad(vertex(x, y, 0), vertex(x, y + 1, 0), vertex(x + 1, y + 1, 0), vertex(x + 1, y, 0));
      // A wall on each side of the cell that faces an open cell or the outside, p to q
      // counter-clockwise around the cell seen from above.
      const int sides[4][6] = {{x, y, x + 1, y, x, y - 1},
                               {x + 1, y, x + 1, y + 1, x + 1, y},
                               {x + 1, y + 1, x, y + 1, x, y + 1},
                               {x, y + 1, x, y, x - 1, y}};
      for(const auto& s : sides)
        if(!solid(s[4], s[5]))
          quad(vertex(s[0], s[1], 0), vertex(s[2], s[3], 0), vertex(s[2], s[3], 1), vertex(s[0], s[1], 1));
    }
  return mesh;
}

TEST(Surfaces, HighGenusSlabsMapWithoutFlipsOrOverlaps)
{
  // A closed surface of genus g needs cones of total curvature 2 pi (2 - 2g) < 0. With the
  // 32 cones of the default limit each would carry about -12 pi at genus 100, beyond what
  // any metric's exact optimum reaches (Newton was blocked, then the circle packing failed):
  // the placement gives such a surface 2g - 2 cones whatever the limit.
  for(int genus : {9, 150})
  {
    Mesh mesh = slab_with_holes(genus);
    ASSERT_TRUE(CGAL::is_closed(mesh));
    ASSERT_EQ(static_cast<int>(num_vertices(mesh) - num_edges(mesh) + num_faces(mesh)), 2 - 2 * genus);
    const std::string what = "slab of genus " + std::to_string(genus);
    const Result r = run(mesh, what);
    ASSERT_EQ(r.report.charts.size(), 1u) << what;
    const int cones = static_cast<int>(r.report.charts[0].cones.size());
    EXPECT_GE(cones, 2 * genus - 2) << what;
    EXPECT_LE(cones, std::max(2 * genus - 2, ICM::Cone_options().max_cones)) << what;
    EXPECT_NEAR(total_cone_curvature(r.report.charts[0]), 2 * M_PI * (2 - 2 * genus), 1e-6) << what;
  }
}

TEST(Surfaces, ConeCountIsExactAndLinearizedPlacementBeatsTheExactGreedy)
{
  // At a count of 8 (BFF's default) on cow and bull: exactly 8 cones, and the linearized
  // greedy's cones leave far less area distortion than the exact greedy's from Algorithm 3's
  // seeds (all eight of them seeds there): the area-weighted mean log^2 area measured was
  // 6.7 against 43.5 on cow, 13.5 against 137 on bull (doc/benchmarks.md, Cones); asked
  // here: a factor 2.
  if(!icm_test::shared_dir_exists())
    GTEST_SKIP() << "shared meshes not found";
  for(const char* name : {"cow.off", "bull.off"})
  {
    double log_area[2] = {0, 0};
    for(ICM::Cone_placement placement : {ICM::Cone_placement::Linearized, ICM::Cone_placement::Exact_optimum})
    {
      Mesh mesh = read(icm_test::shared_path(name));
      ICM::Surface_parameterization_options eight;
      eight.cones.max_cones = 8;
      eight.cones.max_log_scale = 0;
      eight.cones.placement = placement;
      const Result r = run(mesh, name, eight);
      ASSERT_FALSE(r.report.charts.empty()) << name;
      EXPECT_EQ(r.report.charts[0].cones.size(), 8u) << name;
      log_area[placement == ICM::Cone_placement::Exact_optimum] = r.measures.log_area_distortion;
    }
    EXPECT_LT(2 * log_area[0], log_area[1]) << name;
  }
}

TEST(Surfaces, ConeSweepsSpreadTheSpheresCones)
{
  // The greedy's first cones are placed before the others exist; one sweep that moves each
  // to where the linearized |u - u0| is largest without it spreads 8 cones on a round sphere
  // more evenly (the evaluator's area-weighted mean log^2 area 0.071 -> 0.044, BFF 0.065).
  double log_area[2] = {0, 0};
  for(int sweeps : {0, 1})
  {
    Mesh mesh = read(icm_test::data_path("sphere966.off"));
    ICM::Surface_parameterization_options eight;
    eight.cones.max_cones = 8;
    eight.cones.max_log_scale = 0;
    eight.cones.sweeps = sweeps;
    eight.cones.angles = ICM::Cone_angles::Entropy; // the linearized placement alone
    eight.cones.exact_sweeps = false;
    const Result r = run(mesh, "sphere966, sweeps " + std::to_string(sweeps), eight);
    ASSERT_EQ(r.report.charts.size(), 1u);
    EXPECT_EQ(r.report.charts[0].cones.size(), 8u);
    log_area[sweeps] = r.measures.log_area_distortion;
  }
  EXPECT_LT(log_area[1], 0.8 * log_area[0]);
}

} // namespace
