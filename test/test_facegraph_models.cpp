// The pipeline on the FaceGraph models CGAL ships graph traits for: Surface_mesh, Polyhedron_3
// (default items, items with ids), OpenMesh's TriMesh and PolyMesh, the Linear_cell_complex for
// BGL, a Face_filtered_graph leaving a component out, and a Seam_mesh over those it takes. Each
// is built from one polygon soup read from the files, and gives Surface_mesh's UVs to 1e-9, per
// vertex (by its index in the file) or per corner (by its halfedge's ends): the disk
// parameterizer through CGAL's `parameterize()`, `ICM::parameterize` on a closed mesh, holes,
// components, user seams and user cones, and the measures, the UVs in CGAL's dynamic maps or
// in a boost::associative_property_map over a std::map.

#include <ICM/IO/read_seam_selection.h>
#include <ICM/Inverse_curvature_map_parameterizer_3.h>
#include <ICM/measures/Distortion.h>
#include <ICM/parameterize.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Polyhedron_items_with_id_3.h>
#include <CGAL/boost/graph/graph_traits_Polyhedron_3.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Linear_cell_complex_for_combinatorial_map.h>
#include <CGAL/boost/graph/graph_traits_Linear_cell_complex_for_combinatorial_map.h>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <CGAL/boost/graph/graph_traits_PolyMesh_ArrayKernelT.h>
#include <CGAL/boost/graph/graph_traits_TriMesh_ArrayKernelT.h>
#include <CGAL/boost/graph/Face_filtered_graph.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
// After the graph traits of the meshes under it.
#include <CGAL/boost/graph/Seam_mesh.h>

#include <boost/property_map/property_map.hpp>

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace {

namespace SMP = CGAL::Surface_mesh_parameterization;
using Kernel = CGAL::Simple_cartesian<double>;
using Point_2 = Kernel::Point_2;
using Xyz = std::array<double, 3>;

// OpenMesh's default traits store floats, which would not be the file's points: double ones.
struct Double_traits : public OpenMesh::DefaultTraits
{
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};

using Surface_mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;
using Polyhedron_with_ids = CGAL::Polyhedron_3<Kernel, CGAL::Polyhedron_items_with_id_3>;
using Tri_mesh = OpenMesh::TriMesh_ArrayKernelT<Double_traits>;
using Poly_mesh = OpenMesh::PolyMesh_ArrayKernelT<Double_traits>;
using Lcc = CGAL::Linear_cell_complex_for_bgl_combinatorial_map_helper<2, 3>::type;
using Filtered_mesh = CGAL::Face_filtered_graph<Surface_mesh>;

/// Points and faces as read from the files, the points as doubles (every model's point type
/// is built from them).
struct Soup
{
  std::vector<Xyz> points;
  std::vector<std::vector<std::size_t>> faces;
  std::map<Xyz, int> index_of; // the soup's points are distinct: a vertex is found by its point
};

/// Appends `points` and `faces` to `soup`, moved along x beyond the soup's points.
void append_beside(Soup& soup, const std::vector<Xyz>& points, std::vector<std::vector<std::size_t>> faces)
{
  double end = -HUGE_VAL, low = HUGE_VAL, high = -HUGE_VAL;
  for(const Xyz& p : soup.points)
    end = std::max(end, p[0]);
  for(const Xyz& p : points)
  {
    low = std::min(low, p[0]);
    high = std::max(high, p[0]);
  }
  const double shift = soup.points.empty() ? 0 : end + (high - low) - low;
  for(std::vector<std::size_t>& f : faces)
    for(std::size_t& i : f)
      i += soup.points.size();
  for(const Xyz& p : points)
    soup.points.push_back({p[0] + shift, p[1], p[2]});
  soup.faces.insert(soup.faces.end(), faces.begin(), faces.end());
}

/// The soups of `names` side by side in one soup.
Soup read_soup(const std::vector<std::string>& names)
{
  Soup soup;
  for(const std::string& name : names)
  {
    std::vector<Kernel::Point_3> points;
    std::vector<std::vector<std::size_t>> faces;
    EXPECT_TRUE(CGAL::IO::read_polygon_soup(icm_test::data_path(name), points, faces)) << name;
    std::vector<Xyz> xyz;
    for(const Kernel::Point_3& p : points)
      xyz.push_back({p.x(), p.y(), p.z()});
    append_beside(soup, xyz, faces);
  }
  for(std::size_t i = 0; i < soup.points.size(); ++i)
    soup.index_of[soup.points[i]] = static_cast<int>(i);
  EXPECT_EQ(soup.index_of.size(), soup.points.size()) << "two vertices at one point";
  return soup;
}

/// Writes the soup's double points into an OpenMesh mesh: CGAL's own point map for OpenMesh
/// rounds what it writes to float.
template <class OpenMesh_mesh>
struct Open_mesh_point_writer
{
  using key_type = typename boost::graph_traits<OpenMesh_mesh>::vertex_descriptor;
  using value_type = Kernel::Point_3;
  using reference = value_type;
  using category = boost::writable_property_map_tag;
  OpenMesh_mesh* mesh;
  friend void put(const Open_mesh_point_writer& map, key_type v, const Kernel::Point_3& p)
  {
    map.mesh->set_point(v, typename OpenMesh_mesh::Point(p.x(), p.y(), p.z()));
  }
};

template <class Mesh>
void build(const Soup& soup, Mesh& mesh)
{
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(soup.points, soup.faces, mesh);
}
template <class OpenMesh_mesh>
void build_open_mesh(const Soup& soup, OpenMesh_mesh& mesh)
{
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(
    soup.points, soup.faces, mesh, CGAL::parameters::default_values(),
    CGAL::parameters::vertex_point_map(Open_mesh_point_writer<OpenMesh_mesh>{&mesh}));
}
void build(const Soup& soup, Tri_mesh& mesh)
{
  build_open_mesh(soup, mesh);
}
void build(const Soup& soup, Poly_mesh& mesh)
{
  build_open_mesh(soup, mesh);
}
void build(const Soup& soup, Polyhedron_with_ids& mesh)
{
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(soup.points, soup.faces, mesh);
  CGAL::set_halfedgeds_items_id(mesh); // what CGAL asks of a user of these items
}

/// A model that is a mesh type itself.
template <class Mesh_>
struct Plain_model
{
  using Mesh = Mesh_;
  Mesh mesh;
  explicit Plain_model(const Soup& soup) { build(soup, mesh); }
  Mesh& graph() { return mesh; }
};

/// A Face_filtered_graph of a Surface_mesh that holds the soup and a moved copy of it, the
/// copy filtered out: the graph is the soup's faces alone.
struct Filtered_model
{
  using Mesh = Filtered_mesh;
  Surface_mesh whole;
  std::unique_ptr<Filtered_mesh> filtered;
  explicit Filtered_model(const Soup& soup)
  {
    Soup twice = soup;
    append_beside(twice, soup.points, soup.faces);
    build(twice, whole);
    std::vector<Surface_mesh::Face_index> selected; // the soup's faces are the first ones built
    for(std::size_t f = 0; f < soup.faces.size(); ++f)
      selected.push_back(Surface_mesh::Face_index(static_cast<Surface_mesh::size_type>(f)));
    filtered = std::make_unique<Filtered_mesh>(whole, selected);
  }
  Filtered_mesh& graph() { return *filtered; }
};

/// The models' names in the tests' names, in the order of `Models`.
struct Model_names
{
  template <class Model>
  static std::string GetName(int i)
  {
    static const char* const names[] = {"Surface_mesh",       "Polyhedron_3",      "Polyhedron_3_items_with_id",
                                        "OpenMesh_TriMesh",   "OpenMesh_PolyMesh", "Linear_cell_complex",
                                        "Face_filtered_graph"};
    return names[i];
  }
};

/// The file index of a vertex of `mesh` (found by its point).
template <class Mesh>
int input_index(const Mesh& mesh, typename boost::graph_traits<Mesh>::vertex_descriptor v, const Soup& soup)
{
  const auto& p = get(get(CGAL::vertex_point, mesh), v);
  const auto found = soup.index_of.find({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  EXPECT_NE(found, soup.index_of.end()) << "a vertex that is not a point of the file";
  return found == soup.index_of.end() ? -1 : found->second;
}

/// The vertex of `mesh` for every file index (null where the graph has none).
template <class Mesh>
std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor> vertices_by_input(const Mesh& mesh, const Soup& soup)
{
  std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor> by_input(soup.points.size(),
                                                                              boost::graph_traits<Mesh>::null_vertex());
  for(auto v : vertices(mesh))
    by_input[input_index(mesh, v, soup)] = v;
  return by_input;
}

using Uv_table = std::map<std::pair<int, int>, Point_2>; // by vertex (i, -1) or by corner (i, j)

/// What a run gives, in file indices.
struct Result
{
  SMP::Error_code status = SMP::ERROR_EMPTY_MESH;
  Uv_table uvs;
  ICM::Distortion_measures measures;
  std::size_t charts = 0, cones = 0, seam_edges = 0;
};

/// The UV of every corner: the corner at `target(h)` in `face(h)` is keyed by the file indices
/// of `source(h)` and `target(h)`.
template <class Mesh, class HalfedgeUvMap>
Uv_table corner_uvs(const Mesh& mesh, HalfedgeUvMap uv, const Soup& soup)
{
  Uv_table table;
  for(auto h : halfedges(mesh))
    if(!CGAL::is_border(h, mesh))
      table[{input_index(mesh, source(h, mesh), soup), input_index(mesh, target(h, mesh), soup)}] = get(uv, h);
  return table;
}

void expect_same(const Result& got, const Result& expected, const std::string& what)
{
  ASSERT_EQ(got.status, SMP::OK) << what;
  EXPECT_EQ(got.charts, expected.charts) << what;
  EXPECT_EQ(got.cones, expected.cones) << what;
  EXPECT_EQ(got.seam_edges, expected.seam_edges) << what;
  ASSERT_FALSE(expected.uvs.empty()) << what;
  ASSERT_EQ(got.uvs.size(), expected.uvs.size()) << what;
  double largest = 0;
  for(const auto& [key, p] : expected.uvs)
  {
    const auto found = got.uvs.find(key);
    ASSERT_NE(found, got.uvs.end()) << what << ": no UV at (" << key.first << ", " << key.second << ")";
    largest = std::max({largest, std::abs(found->second.x() - p.x()), std::abs(found->second.y() - p.y())});
  }
  EXPECT_LT(largest, 1e-9) << what << ": UVs apart from Surface_mesh's";
  EXPECT_EQ(got.measures.flipped_faces, 0u) << what;
  EXPECT_EQ(got.measures.flipped_faces, expected.measures.flipped_faces) << what;
  EXPECT_NEAR(got.measures.qc_mean, expected.measures.qc_mean, 1e-9) << what;
  EXPECT_NEAR(got.measures.conformality, expected.measures.conformality, 1e-9) << what;
  EXPECT_NEAR(got.measures.log_area_distortion, expected.measures.log_area_distortion, 1e-9) << what;
}

/// `ICM::parameterize` on `mesh` into `uv`, in file indices.
template <class Mesh, class HalfedgeUvMap>
Result surface_run_into(const Mesh& mesh, HalfedgeUvMap uv, const Soup& soup,
                        const ICM::Surface_parameterization_options& options,
                        const std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, double>& cones = {},
                        const std::vector<typename boost::graph_traits<Mesh>::edge_descriptor>& seams = {})
{
  Result r;
  std::vector<typename boost::graph_traits<Mesh>::edge_descriptor> seam_edges;
  const ICM::Surface_parameterization_report report = ICM::parameterize(mesh, uv, options, cones, &seam_edges, seams);
  r.status = report.status;
  EXPECT_EQ(report.status, SMP::OK) << report.message;
  if(report.status != SMP::OK)
    return r;
  r.uvs = corner_uvs(mesh, uv, soup);
  r.measures = ICM::measure_distortion_corner_uv(mesh, uv);
  r.charts = report.charts.size();
  for(const ICM::Chart_report& chart : report.charts)
    r.cones += chart.cones.size();
  r.seam_edges = seam_edges.size();
  return r;
}

/// Through a CGAL dynamic halfedge map (`associative` false) or an associative_property_map
/// over a std::map.
template <class Mesh>
Result surface_run(const Mesh& mesh, bool associative, const Soup& soup,
                   const ICM::Surface_parameterization_options& options = {},
                   const std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, double>& cones = {},
                   const std::vector<typename boost::graph_traits<Mesh>::edge_descriptor>& seams = {})
{
  if(!associative)
    return surface_run_into(mesh, get(CGAL::dynamic_halfedge_property_t<Point_2>(), mesh), soup, options, cones, seams);
  std::map<typename boost::graph_traits<Mesh>::halfedge_descriptor, Point_2> table;
  return surface_run_into(mesh, boost::make_assoc_property_map(table), soup, options, cones, seams);
}

/// The border halfedge into the border vertex of least file index: one border halfedge for
/// every model, whichever its `halfedge()` functions return.
template <class Mesh>
typename boost::graph_traits<Mesh>::halfedge_descriptor first_border_halfedge(const Mesh& mesh, const Soup& soup)
{
  auto best = boost::graph_traits<Mesh>::null_halfedge();
  int least = -1;
  for(auto h : halfedges(mesh))
    if(CGAL::is_border(h, mesh))
    {
      const int i = input_index(mesh, target(h, mesh), soup);
      if(least < 0 || i < least)
      {
        least = i;
        best = h;
      }
    }
  return best;
}

/// The disk parameterizer through CGAL's `parameterize()`, one UV per vertex.
template <class Mesh, class VertexUvMap>
Result disk_run_into(Mesh& mesh, VertexUvMap uv, const Soup& soup)
{
  Result r;
  ICM::Inverse_curvature_map_parameterizer_3<Mesh> parameterizer;
  r.status = SMP::parameterize(mesh, parameterizer, first_border_halfedge(mesh, soup), uv);
  EXPECT_EQ(r.status, SMP::OK) << parameterizer.report().message;
  if(r.status != SMP::OK)
    return r;
  for(auto v : vertices(mesh))
    r.uvs[{input_index(mesh, v, soup), -1}] = get(uv, v);
  r.measures = ICM::measure_distortion(mesh, uv);
  r.charts = 1;
  return r;
}

template <class Mesh>
Result disk_run(Mesh& mesh, bool associative, const Soup& soup)
{
  if(!associative)
    return disk_run_into(mesh, get(CGAL::dynamic_vertex_property_t<Point_2>(), mesh), soup);
  std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, Point_2> table;
  return disk_run_into(mesh, boost::make_assoc_property_map(table), soup);
}

/// The sphere's user seams of `sphere966.selection.txt` (a star of four paths), as file indices.
std::vector<std::pair<int, int>> selection_seams(const Soup& soup)
{
  Surface_mesh mesh;
  build(soup, mesh);
  std::vector<Surface_mesh::Edge_index> edges;
  std::string error;
  EXPECT_TRUE(ICM::IO::read_seam_selection(icm_test::data_path("sphere966.selection.txt"), mesh, edges, error))
    << error;
  std::vector<std::pair<int, int>> seams;
  for(Surface_mesh::Edge_index e : edges)
    seams.emplace_back(input_index(mesh, source(e, mesh), soup), input_index(mesh, target(e, mesh), soup));
  return seams;
}

template <class Mesh>
std::vector<typename boost::graph_traits<Mesh>::edge_descriptor> edges_of(const Mesh& mesh, const Soup& soup,
                                                                          const std::vector<std::pair<int, int>>& pairs)
{
  const auto by_input = vertices_by_input(mesh, soup);
  std::vector<typename boost::graph_traits<Mesh>::edge_descriptor> edges;
  for(const auto& [a, b] : pairs)
  {
    const auto h = halfedge(by_input[a], by_input[b], mesh);
    EXPECT_TRUE(h.second) << "no edge " << a << " - " << b;
    edges.push_back(edge(h.first, mesh));
  }
  return edges;
}

/// Automatic cones off (the user's cones alone); with `keep_overlaps`, the overlap removal
/// too: the options of the `Seam_mesh` overload of `ICM::parameterize`, whose seams are the cut.
ICM::Surface_parameterization_options without_automatic_cones(bool keep_overlaps)
{
  ICM::Surface_parameterization_options options;
  options.automatic_cones = false;
  options.remove_overlaps = !keep_overlaps;
  return options;
}

/// A Seam_mesh over `mesh` cut along `seams`: `ICM::parameterize` on it (one UV per seam-mesh
/// vertex, given back per corner of `mesh`), or with `disk`, the disk parameterizer through
/// CGAL's `parameterize()` on the cut-open sphere.
template <class Mesh>
Result seam_mesh_run(const Mesh& mesh, const Soup& soup, const std::vector<std::pair<int, int>>& seams, bool disk)
{
  auto seam_edge = get(CGAL::dynamic_edge_property_t<bool>(), mesh);
  auto seam_vertex = get(CGAL::dynamic_vertex_property_t<bool>(), mesh);
  for(auto e : edges(mesh))
    put(seam_edge, e, false);
  for(auto v : vertices(mesh))
    put(seam_vertex, v, false);
  using Seam = CGAL::Seam_mesh<Mesh, decltype(seam_edge), decltype(seam_vertex)>;
  Seam seam_mesh(mesh, seam_edge, seam_vertex);
  const auto by_input = vertices_by_input(mesh, soup);
  for(const auto& [a, b] : seams)
    seam_mesh.add_seam(by_input[a], by_input[b]);
  std::map<typename boost::graph_traits<Seam>::vertex_descriptor, Point_2> table;
  auto uv = boost::make_assoc_property_map(table);
  Result r;
  if(disk)
  {
    ICM::Inverse_curvature_map_parameterizer_3<Seam> parameterizer;
    // The border of the cut sphere, from the corner of least file index.
    auto bhd = boost::graph_traits<Seam>::null_halfedge();
    int least = -1;
    for(auto h : halfedges(seam_mesh))
      if(CGAL::is_border(h, seam_mesh))
      {
        const int i = input_index(mesh, target(h.tmhd, mesh), soup) * static_cast<int>(soup.points.size()) +
                      input_index(mesh, source(h.tmhd, mesh), soup);
        if(least < 0 || i < least)
        {
          least = i;
          bhd = h;
        }
      }
    r.status = SMP::parameterize(seam_mesh, parameterizer, bhd, uv);
    EXPECT_EQ(r.status, SMP::OK) << parameterizer.report().message;
    r.charts = 1;
  }
  else
  {
    const ICM::Surface_parameterization_report report = ICM::parameterize(seam_mesh, uv);
    r.status = report.status;
    EXPECT_EQ(r.status, SMP::OK) << report.message;
    r.charts = report.charts.size();
    for(const ICM::Chart_report& chart : report.charts)
      r.cones += chart.cones.size();
  }
  if(r.status != SMP::OK)
    return r;
  for(auto f : faces(seam_mesh))
    for(auto h : CGAL::halfedges_around_face(halfedge(f, seam_mesh), seam_mesh))
      r.uvs[{input_index(mesh, source(h.tmhd, mesh), soup), input_index(mesh, target(h.tmhd, mesh), soup)}] =
        get(uv, target(h, seam_mesh));
  r.measures = ICM::measure_distortion(seam_mesh, uv);
  return r;
}

/// Cones at four vertices of the sphere far apart (a tetrahedron's directions), their angles
/// left to the optimum.
const std::vector<int> sphere_cones = {458, 198, 166, 484};

template <class Mesh>
std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, double> cones_of(const Mesh& mesh, const Soup& soup)
{
  const auto by_input = vertices_by_input(mesh, soup);
  std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, double> cones;
  for(int i : sphere_cones)
    cones[by_input[i]] = std::nan("");
  return cones;
}

std::map<std::string, Result>& reference_results()
{
  static std::map<std::string, Result> results;
  return results;
}

/// Surface_mesh's result of one case, computed once for every model.
template <class Compute>
const Result& reference(const std::string& name, Compute compute)
{
  auto found = reference_results().find(name);
  if(found == reference_results().end())
    found = reference_results().emplace(name, compute()).first;
  return found->second;
}

template <class Model>
class FaceGraphModels : public ::testing::Test
{};

using Models = ::testing::Types<Plain_model<Surface_mesh>, Plain_model<Polyhedron>, Plain_model<Polyhedron_with_ids>,
                                Plain_model<Tri_mesh>, Plain_model<Poly_mesh>, Plain_model<Lcc>, Filtered_model>;
TYPED_TEST_SUITE(FaceGraphModels, Models, Model_names);

/// The case `run` (a generic lambda taking the graph) on Surface_mesh and on the model, from
/// the soup of `files`.
template <class Model, class Run>
void expect_as_surface_mesh(const std::string& name, const std::vector<std::string>& files, Run run)
{
  const Soup soup = read_soup(files);
  const Result& expected = reference(name, [&] {
    Plain_model<Surface_mesh> reference_model(soup);
    return run(reference_model.graph(), soup);
  });
  ASSERT_EQ(expected.status, SMP::OK) << name << " on Surface_mesh";
  Model model(soup);
  expect_same(run(model.graph(), soup), expected, name);
}

TYPED_TEST(FaceGraphModels, DiskParameterizerThroughCgal)
{
  for(bool associative : {false, true})
    expect_as_surface_mesh<TypeParam>("disk", {"nefertiti.off"}, [associative](auto& mesh, const Soup& soup) {
      return disk_run(mesh, associative, soup);
    });
}

TYPED_TEST(FaceGraphModels, ClosedGenusTwo)
{
  for(bool associative : {false, true})
    expect_as_surface_mesh<TypeParam>("closed", {"eight.off"}, [associative](const auto& mesh, const Soup& soup) {
      return surface_run(mesh, associative, soup);
    });
}

TYPED_TEST(FaceGraphModels, SevenHoles)
{
  expect_as_surface_mesh<TypeParam>("holes", {"pig.off"},
                                    [](const auto& mesh, const Soup& soup) { return surface_run(mesh, false, soup); });
}

TYPED_TEST(FaceGraphModels, TwoComponents)
{
  expect_as_surface_mesh<TypeParam>("components", {"nefertiti.off", "eight.off"},
                                    [](const auto& mesh, const Soup& soup) { return surface_run(mesh, true, soup); });
}

TYPED_TEST(FaceGraphModels, UserSeams)
{
  expect_as_surface_mesh<TypeParam>("seams", {"sphere966.off"}, [](const auto& mesh, const Soup& soup) {
    return surface_run(mesh, false, soup, {}, {}, edges_of(mesh, soup, selection_seams(soup)));
  });
}

TYPED_TEST(FaceGraphModels, UserCones)
{
  expect_as_surface_mesh<TypeParam>("cones", {"sphere966.off"}, [](const auto& mesh, const Soup& soup) {
    return surface_run(mesh, true, soup, without_automatic_cones(false), cones_of(mesh, soup));
  });
}

template <class Model>
constexpr bool is_open_mesh =
  std::is_same_v<Model, Plain_model<Tri_mesh>> || std::is_same_v<Model, Plain_model<Poly_mesh>>;

TYPED_TEST(FaceGraphModels, SeamMeshOverTheModel)
{
  // ICM::parameterize on a Seam_mesh over the model is the model cut along exactly those
  // seams: the UVs of Surface_mesh with the same user seams and the seam overload's options.
  if constexpr(is_open_mesh<TypeParam>)
    GTEST_SKIP() << "CGAL 5.5's Seam_mesh calls CGAL::halfedges(tm), CGAL::faces(tm), ... qualified, and OpenMesh's "
                    "graph functions are in namespace OpenMesh: a Seam_mesh over OpenMesh does not compile";
  else
  {
    const Soup soup = read_soup({"sphere966.off"});
    const std::vector<std::pair<int, int>> seams = selection_seams(soup);
    const Result& expected = reference("seams, the Seam_mesh overload's options", [&] {
      Plain_model<Surface_mesh> model(soup);
      return surface_run(model.graph(), false, soup, without_automatic_cones(true), {},
                         edges_of(model.graph(), soup, seams));
    });
    TypeParam model(soup);
    Result got = seam_mesh_run(model.graph(), soup, seams, false);
    got.seam_edges = expected.seam_edges; // the seam mesh's own, given
    expect_same(got, expected, "Seam_mesh over the model");

    // The disk parameterizer on the cut-open sphere, as CGAL's Seam_mesh examples run it.
    const Result& disk = reference("disk parameterizer on a Seam_mesh", [&] {
      Plain_model<Surface_mesh> reference_model(soup);
      return seam_mesh_run(reference_model.graph(), soup, seams, true);
    });
    expect_same(seam_mesh_run(model.graph(), soup, seams, true), disk,
                "disk parameterizer on a Seam_mesh over the model");
  }
}

TEST(FaceGraphModelsOpenMesh, DefaultTriMeshTakesTheSameCall)
{
  // A new user's mesh type as it comes: OpenMesh's default (float) traits, read by CGAL.
  OpenMesh::TriMesh_ArrayKernelT<> mesh;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(icm_test::data_path("eight.off"), mesh));
  std::map<boost::graph_traits<OpenMesh::TriMesh_ArrayKernelT<>>::halfedge_descriptor, Point_2> table;
  const ICM::Surface_parameterization_report report = ICM::parameterize(mesh, boost::make_assoc_property_map(table));
  ASSERT_EQ(report.status, SMP::OK) << report.message;
  ASSERT_EQ(report.charts.size(), 1u);
  EXPECT_EQ(report.charts[0].genus, 2);
  EXPECT_EQ(ICM::measure_distortion_corner_uv(mesh, boost::make_assoc_property_map(table)).flipped_faces, 0u);
}

} // namespace
