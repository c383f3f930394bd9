// Tests of the input side: the checked readers of OFF (and its variants), OBJ, PLY and STL,
// the repairs that make a triangle mesh of their soup, the all-or-nothing writing of several
// files, scale-free indexing, and the library's "not run" and empty-mesh answers.

#include <ICM/Inverse_curvature_map_parameterizer_3.h>
#include <ICM/IO/read_polygon_soup.h>
#include <ICM/IO/read_triangle_mesh.h>
#include <ICM/parameterize.h>
#include <ICM/internal/Atomic_file.h>
#include <ICM/internal/Mesh_index.h>

#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <set>
#include <locale>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using ICM::IO::Mesh_file_format;
using ICM::IO::Polygon_soup;
namespace fs = std::filesystem;
namespace SMP = CGAL::Surface_mesh_parameterization;

/// The soup of `content`, read as `format`; fails the test if it is refused.
Polygon_soup soup_of(const std::string& content, Mesh_file_format format)
{
  Polygon_soup soup;
  std::string error;
  EXPECT_TRUE(ICM::IO::read_polygon_soup(content, format, soup, error)) << error << "\n" << content;
  return soup;
}

/// The reason `content` is refused; fails the test if it is read.
std::string refusal_of(const std::string& content, Mesh_file_format format)
{
  Polygon_soup soup;
  std::string error;
  EXPECT_FALSE(ICM::IO::read_polygon_soup(content, format, soup, error)) << content;
  EXPECT_TRUE(soup.points.empty() && soup.polygons.empty());
  return error;
}

std::vector<std::array<double, 3>> coordinates(const Polygon_soup& soup)
{
  std::vector<std::array<double, 3>> out;
  for(const auto& p : soup.points)
    out.push_back({p.x(), p.y(), p.z()});
  return out;
}

const std::vector<std::array<double, 3>> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0}};
const std::vector<std::vector<std::size_t>> two_triangles = {{0, 1, 2}, {0, 2, 3}};

TEST(ReadPolygonSoup, OffVariantsReadTheSamePointsAndFaces)
{
  const char* bodies[] = {
    "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0.5\n0 1 0\n3 0 1 2\n3 0 2 3\n",
    "OFF 4 2 0\n# comment\n\n0 0 0 # trailing\n1 0 0\n1 1 0.5\n0 1 0\n3 0 1 2 255 0 0\n3 0 2 3\n",
    "4 2 0\n0 0 0\n1 0 0\n1 1 0.5\n0 1 0\n3 0 1 2\n3 0 2 3\n", // the keyword is optional
    "COFF\n4 2 0\n0 0 0 255 0 0 255\n1 0 0 1 1 1\n1 1 0.5 0.5 0.5 0.5 1\n0 1 0 7\n3 0 1 2\n3 0 2 3\n",
    "NOFF\n4 2 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0.5 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n3 0 2 3\n",
    "STOFF\n4 2 0\n0 0 0 0 0\n1 0 0 1 0\n1 1 0.5 1 1\n0 1 0 0 1\n3 0 1 2\n3 0 2 3\n",
    "STCNOFF\n4 2 0\n0 0 0 0 0 1 1 0 0 0 0\n1 0 0 0 0 1 1 0 0 1 0\n1 1 0.5 0 0 1 1 0 0 1 1\n"
    "0 1 0 0 0 1 1 0 0 0 1\n3 0 1 2\n3 0 2 3\n",
    "4OFF\n4 2 0\n0 0 0 2\n2 0 0 2\n-1 -1 -0.5 -1\n0 4 0 4\n3 0 1 2\n3 0 2 3\n",
    "\xEF\xBB\xBFOFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0.5\n0 1 0\n3 0 1 2\n3 0 2 3\n", // a UTF-8 byte-order mark
  };
  for(const char* body : bodies)
  {
    const Polygon_soup soup = soup_of(body, Mesh_file_format::Off);
    EXPECT_EQ(coordinates(soup), square) << body;
    EXPECT_EQ(soup.polygons, two_triangles) << body;
  }
  // Lines are those of the file, for messages.
  const Polygon_soup soup = soup_of(bodies[1], Mesh_file_format::Off);
  EXPECT_EQ(soup.polygon_lines, (std::vector<std::size_t>{8, 9}));
  EXPECT_EQ(soup.describe_polygon(1), "face 1 (line 9)");
}

TEST(ReadPolygonSoup, ObjRelativeAndForwardIndices)
{
  const Polygon_soup relative =
    soup_of("v 0 0 0\nv 1 0 0\nvt 0 0\nv 1 1 0.5 1.0\nv 0 1 0 0.2 0.3 0.4\nf -4/1 -3/1/1 -2//1\nf 1 -2 -1\n",
            Mesh_file_format::Obj);
  EXPECT_EQ(coordinates(relative), square);
  EXPECT_EQ(relative.polygons, two_triangles);
  // A face may name vertices defined after it.
  const Polygon_soup forward =
    soup_of("f 1 2 3\nf 1 3 4\nv 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0\n", Mesh_file_format::Obj);
  EXPECT_EQ(forward.polygons, two_triangles);
  EXPECT_NE(refusal_of("f 1 2 3\nf 1 3 5\nv 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0\n", Mesh_file_format::Obj)
              .find("line 2: face 1: vertex index 5 is out of range (the file has 4 vertices)"),
            std::string::npos);
}

/// A binary PLY of the square, in the byte order asked for, with float coordinates and a list
/// of `uchar` counts and `int` indices.
std::string binary_ply(bool big_endian, std::uint8_t last_count = 3)
{
  std::string out = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
  auto put = [&](const void* p, std::size_t n) {
    std::string bytes(static_cast<const char*>(p), n);
    if(big_endian)
      std::reverse(bytes.begin(), bytes.end()); // the test machine is little endian
    out += bytes;
  };
  for(const auto& p : square)
    for(double x : p)
    {
      const float f = static_cast<float>(x);
      put(&f, 4);
    }
  for(std::size_t i = 0; i < two_triangles.size(); ++i)
  {
    const std::uint8_t n = i + 1 == two_triangles.size() ? last_count : 3;
    out += static_cast<char>(n);
    for(std::size_t v : two_triangles[i])
    {
      const std::int32_t index = static_cast<std::int32_t>(v);
      put(&index, 4);
    }
  }
  return out;
}

TEST(ReadPolygonSoup, PlyAsciiAndBinaryInBothByteOrders)
{
  const std::string ascii = "ply\nformat ascii 1.0\ncomment x\nelement vertex 4\nproperty double x\n"
                            "property double y\nproperty double z\nproperty uchar red\nelement edge 1\n"
                            "property int vertex1\nproperty int vertex2\nelement face 2\n"
                            "property list uchar uint vertex_indices\nend_header\n"
                            "0 0 0 1\n1 0 0 2\n1 1 0.5 3\n0 1 0 4\n0 1\n3 0 1 2\n3 0 2 3\n";
  const Polygon_soup a = soup_of(ascii, Mesh_file_format::Ply);
  EXPECT_EQ(coordinates(a), square);
  EXPECT_EQ(a.polygons, two_triangles);
  EXPECT_EQ(a.polygon_lines, (std::vector<std::size_t>{20, 21}));
  for(bool big_endian : {false, true})
  {
    const Polygon_soup b = soup_of(binary_ply(big_endian), Mesh_file_format::Ply);
    EXPECT_EQ(coordinates(b), square) << big_endian;
    EXPECT_EQ(b.polygons, two_triangles) << big_endian;
  }
  // A list count that runs past the end of the file is refused before it is read.
  EXPECT_NE(refusal_of(binary_ply(false, 200), Mesh_file_format::Ply).find("runs past the end of the file"),
            std::string::npos);
}

TEST(ReadPolygonSoup, StlCornersAtOnePointAreOneVertexInFirstAppearanceOrder)
{
  const std::string ascii = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0.5\n"
                            "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0.5\n"
                            "vertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
  const Polygon_soup a = soup_of(ascii, Mesh_file_format::Stl);
  EXPECT_EQ(coordinates(a), square);
  EXPECT_EQ(a.polygons, two_triangles);

  std::string binary(80, ' ');
  const std::uint32_t count = 2;
  binary.append(reinterpret_cast<const char*>(&count), 4);
  for(const auto& t : two_triangles)
  {
    const float normal[3] = {0, 0, 1};
    binary.append(reinterpret_cast<const char*>(normal), 12);
    for(std::size_t v : t)
      for(double x : square[v])
      {
        const float f = static_cast<float>(x);
        binary.append(reinterpret_cast<const char*>(&f), 4);
      }
    binary.append(2, '\0');
  }
  const Polygon_soup b = soup_of(binary, Mesh_file_format::Stl);
  EXPECT_EQ(coordinates(b), square);
  EXPECT_EQ(b.polygons, two_triangles);
  // The count of a binary STL must match its size.
  binary[80] = 3;
  EXPECT_NE(refusal_of(binary, Mesh_file_format::Stl).find("announces 3 triangles"), std::string::npos);
}

TEST(ReadPolygonSoup, EveryRefusalNamesWhereAndWhat)
{
  struct Case
  {
    Mesh_file_format format;
    std::string content, reason;
  };
  const Case cases[] = {
    {Mesh_file_format::Off, "", "the file is empty"},
    {Mesh_file_format::Off, "OFF\n2000000000 1 0\n", "more than this reader takes"},
    {Mesh_file_format::Off, "OFF\n100000 1 0\n0 0 0\n",
     "line 2: the header announces 100000 vertices but only 6 bytes follow"},
    {Mesh_file_format::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
     "line 6: face 0: vertex index 3 is out of range"},
    {Mesh_file_format::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "vertex index -1 is out of range"},
    {Mesh_file_format::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000000 0 1 2\n",
     "announces 1000000000 corners but the file has only 3 vertices"},
    {Mesh_file_format::Off, "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n",
     "line 4: vertex 1 has a non-finite coordinate 'nan'"},
    {Mesh_file_format::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n# a long comment\n", "the file ends after 2 of the 3 vertices"},
    {Mesh_file_format::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n", "face 0 (line 6) uses vertex 1 twice"},
    {Mesh_file_format::Off, "STOFF\n3 1 0\n0 0 0\n1 0 0 0 0\n0 1 0 0 0\n3 0 1 2\n",
     "line 3: vertex 0 has 3 numbers; this OFF variant has 5"},
    {Mesh_file_format::Off, "nOFF\n3\n", "nOFF"},
    {Mesh_file_format::Off, "OFF BINARY\n", "binary OFF is not supported"},
    {Mesh_file_format::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n",
     "line 7: the file goes on after the 1 faces its header announces"},
    {Mesh_file_format::Off, "ply\nformat ascii 1.0\n", "looks like PLY, not OFF"},
    {Mesh_file_format::Obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n",
     "line 4: face 0: vertex index 0 (OBJ indices start at 1)"},
    {Mesh_file_format::Obj, "v 0 0 0\nf -1 -2 -3\n", "relative vertex index -2 reaches before the first vertex"},
    {Mesh_file_format::Obj, "v 0 0 inf\n", "non-finite"},
    {Mesh_file_format::Obj, "OFF\n3 1 0\n", "looks like OFF, not OBJ"},
    {Mesh_file_format::Ply, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", "no 'end_header'"},
    {Mesh_file_format::Ply,
     "ply\nformat ascii 1.0\nelement vertex 1000000\nproperty float x\nproperty float y\n"
     "property float z\nend_header\n0 0 0\n",
     "the header announces 1000000 'vertex' elements"},
    {Mesh_file_format::Ply,
     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
     "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
     "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
     "line 13: face 0: vertex index 7 is out of range"},
    {Mesh_file_format::Stl, "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nendloop\nendfacet\nendsolid\n",
     "line 2: the facet has 1 vertices"},
    {Mesh_file_format::Stl, "hello", "too short for a binary STL"},
  };
  for(const Case& c : cases)
  {
    const std::string reason = refusal_of(c.content, c.format);
    EXPECT_NE(reason.find(c.reason), std::string::npos) << "expected '" << c.reason << "' in '" << reason << "'";
  }
}

TEST(ReadPolygonSoup, FilesAreNamedByTheirExtension)
{
  icm_test::Scratch_directory dir("icm_read");
  icm_test::write_text(dir.path() / "mesh.OFF", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0.5\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  icm_test::write_text(dir.path() / "mesh.dat", "OFF\n");
  Polygon_soup soup;
  std::string error;
  EXPECT_TRUE(ICM::IO::read_polygon_soup(dir.file("mesh.OFF"), soup, error)) << error;
  EXPECT_EQ(coordinates(soup), square);
  EXPECT_FALSE(ICM::IO::read_polygon_soup(dir.file("mesh.dat"), soup, error));
  EXPECT_NE(error.find("unknown extension '.dat'"), std::string::npos) << error;
  EXPECT_FALSE(ICM::IO::read_polygon_soup(dir.file("none.off"), soup, error));
  EXPECT_NE(error.find("no such file"), std::string::npos) << error;
  fs::create_directory(dir.path() / "d.off");
  EXPECT_FALSE(ICM::IO::read_polygon_soup(dir.file("d.off"), soup, error));
  EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
}

/// `polygon_soup_to_triangle_mesh` on an OFF text.
bool mesh_of(const std::string& off, Mesh& mesh, ICM::IO::Mesh_reading_report& report, bool triangulate = false)
{
  Polygon_soup soup = soup_of(off, Mesh_file_format::Off);
  ICM::IO::Mesh_reading_options options;
  options.triangulate = triangulate;
  return ICM::IO::polygon_soup_to_triangle_mesh(soup, mesh, report, options);
}

TEST(ReadTriangleMesh, IsolatedVerticesDroppedNonManifoldVerticesSplitInDocumentedOrder)
{
  // Vertex 0 is in no face; vertex 1 joins two fans that share nothing else.
  const std::string off = "OFF\n8 4 0\n9 9 9\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n-1 0 0\n-1 -1 0\n0 -1 0\n"
                          "3 1 2 3\n3 1 3 4\n3 1 5 6\n3 1 6 7\n";
  Mesh mesh;
  ICM::IO::Mesh_reading_report report;
  ASSERT_TRUE(mesh_of(off, mesh, report)) << report.message;
  EXPECT_EQ(report.isolated_vertices, (std::vector<std::size_t>{0}));
  EXPECT_EQ(report.split_vertices, (std::vector<std::size_t>{1}));
  EXPECT_EQ(report.file_vertex, (std::vector<std::size_t>{1, 2, 3, 4, 5, 6, 7, 1}));
  EXPECT_EQ(num_vertices(mesh), 8u);
  EXPECT_EQ(num_faces(mesh), 4u);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  // Every vertex has one fan now: the mesh is a manifold with two components.
  for(Mesh::Vertex_index v : vertices(mesh))
    EXPECT_FALSE(mesh.is_isolated(v));
  const std::vector<std::string> repairs = report.repairs();
  ASSERT_EQ(repairs.size(), 2u);
  EXPECT_EQ(repairs[0], "dropped 1 isolated vertex (in no face): 0");
  EXPECT_EQ(repairs[1], "split 1 non-manifold vertex into one vertex per fan of faces (1 added): 1");
  // The faces keep their orientation (orient_polygon_soup only split the vertex).
  std::vector<std::size_t> first_face;
  for(Mesh::Vertex_index v : CGAL::vertices_around_face(halfedge(*faces(mesh).begin(), mesh), mesh))
    first_face.push_back(report.file_vertex[v]);
  std::rotate(first_face.begin(), std::min_element(first_face.begin(), first_face.end()), first_face.end());
  EXPECT_EQ(first_face, (std::vector<std::size_t>{1, 2, 3}));
}

TEST(ReadTriangleMesh, WhatCannotBeRepairedIsRefusedWithItsReason)
{
  Mesh mesh;
  ICM::IO::Mesh_reading_report report;
  // Three faces on one edge.
  EXPECT_FALSE(mesh_of("OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n", mesh, report));
  EXPECT_NE(report.message.find("the edge between vertices 0 and 1 is shared by 3 faces (face 0 (line 8), "
                                "face 1 (line 9), face 2 (line 10)): a non-manifold edge"),
            std::string::npos)
    << report.message;
  EXPECT_EQ(num_faces(mesh), 0u);
  // Polygons, unless triangulation was asked for.
  const std::string quads = "OFF\n6 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n2 1 0\n4 0 1 2 3\n4 1 4 5 2\n";
  EXPECT_FALSE(mesh_of(quads, mesh, report));
  EXPECT_NE(report.message.find("non-triangle faces: face 0 (line 9) has 4 sides (2 faces have more than 3)"),
            std::string::npos)
    << report.message;
  ASSERT_TRUE(mesh_of(quads, mesh, report, true)) << report.message;
  EXPECT_EQ(report.triangulated_faces, 2u);
  EXPECT_EQ(num_faces(mesh), 4u);
  EXPECT_TRUE(CGAL::is_triangle_mesh(mesh));
  // No faces at all.
  EXPECT_FALSE(mesh_of("OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", mesh, report));
  EXPECT_EQ(report.message, "the file has no faces (only 3 vertices)");
}

/// An OFF text of `points` and `faces`, coordinates written to every digit.
std::string off_text(const std::vector<std::array<double, 3>>& points,
                     const std::vector<std::vector<std::size_t>>& faces)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s.precision(17);
  s << "OFF\n" << points.size() << " " << faces.size() << " 0\n";
  for(const auto& p : points)
    s << p[0] << " " << p[1] << " " << p[2] << "\n";
  for(const auto& f : faces)
  {
    s << f.size();
    for(std::size_t i : f)
      s << " " << i;
    s << "\n";
  }
  return s.str();
}

/// The n x n grid of `points` in [0, scale]^2 from `origin`, with a bump, and its triangles
/// after the vertices `first`, all counterclockwise.
void add_grid(std::vector<std::array<double, 3>>& points, std::vector<std::vector<std::size_t>>& faces, double scale,
              double origin = 0, std::size_t n = 4)
{
  const std::size_t first = points.size();
  for(std::size_t j = 0; j < n; ++j)
    for(std::size_t i = 0; i < n; ++i)
    {
      const double x = double(i) / (n - 1), y = double(j) / (n - 1);
      points.push_back({origin + x * scale, y * scale, 0.3 * std::sin(3 * x) * scale});
    }
  for(std::size_t j = 0; j + 1 < n; ++j)
    for(std::size_t i = 0; i + 1 < n; ++i)
    {
      const std::size_t a = first + j * n + i, b = a + 1, c = a + n + 1, d = a + n;
      faces.push_back({a, b, c});
      faces.push_back({a, c, d});
    }
}

/// The vertices of face `f` of `mesh`, as the file numbers them, from the smallest.
std::vector<std::size_t> file_corners(const Mesh& mesh, std::size_t f, const ICM::IO::Mesh_reading_report& report)
{
  std::vector<std::size_t> corners;
  for(Mesh::Vertex_index v : CGAL::vertices_around_face(halfedge(*std::next(faces(mesh).begin(), f), mesh), mesh))
    corners.push_back(report.file_vertex[v]);
  std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
  return corners;
}

TEST(ReadTriangleMesh, FacesThatDisagreeAreReorientedTheFewestAndReported)
{
  Mesh mesh;
  ICM::IO::Mesh_reading_report report;
  // Two faces that disagree: one of them turns.
  ASSERT_TRUE(mesh_of("OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 3 2\n", mesh, report)) << report.message;
  EXPECT_EQ(report.reoriented_faces.size(), 1u);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  EXPECT_EQ(num_faces(mesh), 2u);
  // A fan of four whose first face is the odd one out: that face turns, not the three others
  // (orient_polygon_soup alone keeps the first face and turns the rest).
  const std::string fan = "OFF\n5 4 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n3 0 2 1\n3 0 2 3\n3 0 3 4\n3 0 4 1\n";
  ASSERT_TRUE(mesh_of(fan, mesh, report)) << report.message;
  EXPECT_EQ(report.reoriented_faces, (std::vector<std::size_t>{0}));
  EXPECT_EQ(file_corners(mesh, 0, report), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(file_corners(mesh, 1, report), (std::vector<std::size_t>{0, 2, 3}));
  ASSERT_EQ(report.repairs().size(), 1u);
  EXPECT_EQ(report.repairs()[0], "reoriented 1 face to agree with the faces around it: 0");
  // Three faces of a grid reversed, and a non-manifold vertex joining a second grid: both
  // repairs at once, each face of each component turned the way most of them run.
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<std::size_t>> faces;
  add_grid(points, faces, 1);
  add_grid(points, faces, 1, 1);
  for(auto& f : faces)
    for(std::size_t& v : f)
      v = v == 16 ? 3 : v; // the second grid's first corner is the first grid's corner (1, 0)
  for(std::size_t f : {4, 9, 13, 20})
    std::reverse(faces[f].begin(), faces[f].end());
  ASSERT_TRUE(mesh_of(off_text(points, faces), mesh, report)) << report.message;
  EXPECT_EQ(report.reoriented_faces, (std::vector<std::size_t>{4, 9, 13, 20}));
  EXPECT_EQ(report.split_vertices, (std::vector<std::size_t>{3}));
  EXPECT_EQ(report.isolated_vertices, (std::vector<std::size_t>{16}));
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  EXPECT_EQ(report.repairs()[2], "reoriented 4 faces to agree with the faces around them: 4, 9, 13, 20");
}

TEST(ReadTriangleMesh, NonOrientableSurfacesAndFacesListedTwiceAreRefusedByName)
{
  Mesh mesh;
  ICM::IO::Mesh_reading_report report;
  // A Moebius strip of 8 quads, each in two triangles.
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<std::size_t>> faces;
  const std::size_t m = 8;
  for(std::size_t k = 0; k < m; ++k)
    for(const double s : {-0.3, 0.3})
    {
      const double a = 2 * M_PI * double(k) / m, r = 1 + s * std::cos(a / 2);
      points.push_back({r * std::cos(a), r * std::sin(a), s * std::sin(a / 2)});
    }
  for(std::size_t k = 0; k < m; ++k)
  {
    const std::size_t i0 = 2 * k, i1 = 2 * k + 1, j0 = k + 1 < m ? 2 * k + 2 : 1, j1 = k + 1 < m ? 2 * k + 3 : 0;
    faces.push_back({i0, j0, j1});
    faces.push_back({i0, j1, i1});
  }
  EXPECT_FALSE(mesh_of(off_text(points, faces), mesh, report));
  EXPECT_NE(
    report.message.find("against any orientation the faces around them can take: the surface is not orientable"),
    std::string::npos)
    << report.message;
  EXPECT_EQ(num_faces(mesh), 0u);
  // The same triangle twice, either way round inside a disk.
  points.clear();
  faces.clear();
  add_grid(points, faces, 1);
  faces.push_back(faces[7]);
  EXPECT_FALSE(mesh_of(off_text(points, faces), mesh, report));
  EXPECT_NE(report.message.find("face 18 (line 37) has the corners of face 7 (line 26): a face listed twice"),
            std::string::npos)
    << report.message;
  std::reverse(faces.back().begin(), faces.back().end());
  EXPECT_FALSE(mesh_of(off_text(points, faces), mesh, report));
  EXPECT_NE(report.message.find("a non-manifold edge"), std::string::npos) << report.message;
}

TEST(ReadTriangleMesh, PolygonsThatCrossThemselvesAreRefusedBeforeTriangulation)
{
  Mesh mesh;
  ICM::IO::Mesh_reading_report report;
  std::vector<std::array<double, 3>> heptagon;
  for(int k = 0; k < 7; ++k)
    heptagon.push_back({std::cos(2 * M_PI * k / 7), std::sin(2 * M_PI * k / 7), 0});
  ASSERT_TRUE(mesh_of(off_text(heptagon, {{0, 1, 2, 3, 4, 5, 6}}), mesh, report, true)) << report.message;
  EXPECT_EQ(report.triangulated_faces, 1u);
  EXPECT_EQ(num_faces(mesh), 5u);
  // The star {7/2}: CGAL 5.5's triangulate_face crashed on it.
  EXPECT_FALSE(mesh_of(off_text(heptagon, {{0, 2, 4, 6, 1, 3, 5}}), mesh, report, true));
  EXPECT_EQ(report.message, "face 0 (line 10) (7 sides) cannot be triangulated: its side from vertex 0 to vertex 2 "
                            "meets its side from vertex 6 to vertex 1 on its best-fit plane (the polygon crosses "
                            "itself, it is not simple)");
  // The same star tilted out of every axis plane, the star's corners off its plane by a little.
  for(auto& p : heptagon)
    p = {p[0] + 0.3 * p[1], p[1] - 0.2 * p[0], 0.5 * p[0] + 0.7 * p[1] + 0.01 * p[0] * p[1]};
  EXPECT_FALSE(mesh_of(off_text(heptagon, {{0, 2, 4, 6, 1, 3, 5}}), mesh, report, true));
  EXPECT_NE(report.message.find("the polygon crosses itself"), std::string::npos) << report.message;
  // Bow ties, lopsided and symmetric (whose two loops cancel out), a side folding back onto
  // the next one, two corners at one point, corners on a line.
  EXPECT_FALSE(mesh_of(off_text({{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 1, 0}}, {{0, 1, 2, 3}}), mesh, report, true));
  EXPECT_NE(report.message.find("its side from vertex 0 to vertex 1 meets its side from vertex 2 to vertex 3"),
            std::string::npos)
    << report.message;
  const std::vector<std::array<double, 3>> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
  EXPECT_FALSE(mesh_of(off_text(square, {{0, 2, 1, 3}}), mesh, report, true));
  EXPECT_NE(report.message.find("its loops cancel out"), std::string::npos) << report.message;
  EXPECT_FALSE(mesh_of(off_text(square, {{0, 4, 1, 2, 3}}), mesh, report, true));
  EXPECT_NE(report.message.find("meets"), std::string::npos) << report.message;
  EXPECT_FALSE(mesh_of(off_text({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 1, 2, 3}}), mesh, report, true));
  EXPECT_NE(report.message.find("its corners 1 and 2 are at one point of its plane"), std::string::npos)
    << report.message;
  EXPECT_FALSE(mesh_of(off_text({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}, {{0, 1, 2, 3}}), mesh, report, true));
  EXPECT_NE(report.message.find("its corners do not span a plane polygon"), std::string::npos) << report.message;
}

TEST(ReadTriangleMesh, TallPolygonsAreCheckedWithoutComparingEverySideWithEveryOther)
{
  // A tall, thin polygon: 2,000 corners on two vertical lines, all of its long sides sharing
  // one abscissa (where a sweep along x compares every side with every other, and CGAL's
  // triangulate_face walks up the triangulation for each corner).
  const int m = 1000;
  std::vector<std::array<double, 3>> points;
  std::vector<std::size_t> polygon;
  for(int i = 0; i < m; ++i)
    points.push_back({0, double(i), 0});
  for(int i = m - 1; i >= 0; --i)
    points.push_back({1, double(i), 0});
  for(std::size_t i = 0; i < points.size(); ++i)
    polygon.push_back(i);
  Mesh mesh;
  ICM::IO::Mesh_reading_report report;
  ASSERT_TRUE(mesh_of(off_text(points, {polygon}), mesh, report, true)) << report.message;
  EXPECT_EQ(num_faces(mesh), 2u * m - 2);
  // Its triangles tile it, all turned as the polygon is (clockwise seen from +z).
  double area = 0;
  for(auto f : faces(mesh))
  {
    const auto h = halfedge(f, mesh);
    const auto &a = mesh.point(source(h, mesh)), &b = mesh.point(target(h, mesh)),
               &c = mesh.point(target(next(h, mesh), mesh));
    const double twice_area = CGAL::cross_product(b - a, c - a).z();
    EXPECT_LT(twice_area, 0);
    area -= twice_area / 2;
  }
  EXPECT_NEAR(area, m - 1.0, 1e-9);
  // One corner of the right side moved across the left one: both of its sides cross it.
  const std::size_t moved = m + m / 2;
  points[moved][0] = -1;
  EXPECT_FALSE(mesh_of(off_text(points, {polygon}), mesh, report, true));
  EXPECT_NE(report.message.find("the polygon crosses itself"), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("vertex " + std::to_string(moved) + " "), std::string::npos) << report.message;
}

TEST(ReadTriangleMesh, DegenerateFacesAreJudgedAtAnyScaleAndAnExtentBeyondADoubleIsNamed)
{
  Mesh mesh;
  ICM::IO::Mesh_reading_report report;
  // A unit grid beside one of 1e200 or 1e308: the small faces are not degenerate, though the
  // bounding box is 1e200 or 1e308 times their size.
  for(const double scale : {1e200, 1e308})
  {
    std::vector<std::array<double, 3>> points;
    std::vector<std::vector<std::size_t>> faces;
    add_grid(points, faces, 1);
    add_grid(points, faces, scale / 2, scale / 2);
    EXPECT_TRUE(mesh_of(off_text(points, faces), mesh, report)) << scale << ": " << report.message;
    EXPECT_EQ(num_faces(mesh), 36u);
  }
  // Corners that differ but lie on a line, whatever their size; corners at one point.
  EXPECT_FALSE(mesh_of(off_text({{0, 0, 0}, {1e-300, 1e-300, 0}, {3e-300, 3e-300, 0}}, {{0, 1, 2}}), mesh, report));
  EXPECT_EQ(report.message, "face 0 (line 6) is degenerate (zero area: its corners are collinear)");
  EXPECT_FALSE(mesh_of(off_text({{1e308, 0, 0}, {1e308, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}), mesh, report));
  EXPECT_EQ(report.message, "face 0 (line 6) is degenerate (zero area: its corners are collinear)");
  EXPECT_FALSE(mesh_of(off_text({{1e308, 0, 0}, {1e308, 0, 0}, {1e308, 0, 0}}, {{0, 1, 2}}), mesh, report));
  EXPECT_EQ(report.message, "face 0 (line 6) is degenerate (zero area: its corners are at one point)");
  // Coordinates whose difference overflows.
  EXPECT_FALSE(mesh_of(off_text({{0, -1e308, 0}, {1, 1e308, 0}, {0, 1, 0}}, {{0, 1, 2}}), mesh, report));
  EXPECT_EQ(report.message, "the mesh's extent along y, from -1e+308 to 1e+308, is beyond the range of a double (the "
                            "difference of two coordinates overflows): scale the mesh down");
}

TEST(AtomicFiles, SeveralFilesAreWrittenAllOrNothing)
{
  icm_test::Scratch_directory dir("icm_atomic");
  const std::string a = dir.file("a.txt"), b = dir.file("b.txt");
  icm_test::write_text(a, "old a\n");
  std::string error;
  auto writes = [](const char* text) { return [text](std::ostream& os) { return static_cast<bool>(os << text); }; };
  auto fails = [](std::ostream& os) {
    os << "half";
    return false;
  };
  // The second output fails: the first target keeps its content, the second is not created.
  EXPECT_FALSE(ICM::internal::write_files_atomically({{a, writes("new a\n")}, {b, fails}}, error));
  EXPECT_NE(error.find("cannot write '" + b + "'"), std::string::npos) << error;
  EXPECT_EQ(icm_test::read_text(a), "old a\n");
  EXPECT_EQ(dir.number_of_entries(), 1u) << "a temporary was left behind";
  // Both succeed: both replaced.
  EXPECT_TRUE(ICM::internal::write_files_atomically({{a, writes("new a\n")}, {b, writes("new b\n")}}, error)) << error;
  EXPECT_EQ(icm_test::read_text(a), "new a\n");
  EXPECT_EQ(icm_test::read_text(b), "new b\n");
  EXPECT_EQ(dir.number_of_entries(), 2u);
  EXPECT_TRUE(ICM::internal::same_file(dir.file("new.txt"), dir.file("./missing/../new.txt")));
  EXPECT_FALSE(ICM::internal::same_file(dir.file("new.txt"), dir.file("new.obj")));
  // One file named twice, through different paths.
  EXPECT_FALSE(ICM::internal::write_files_atomically({{a, writes("x")}, {dir.file("./a.txt"), writes("y")}}, error));
  EXPECT_NE(error.find("twice"), std::string::npos) << error;
  EXPECT_EQ(icm_test::read_text(a), "new a\n");
  // A read-only target is refused, even where the rename would be allowed.
  fs::permissions(b, fs::perms::owner_read);
  EXPECT_FALSE(ICM::internal::write_files_atomically({{a, writes("x")}, {b, writes("y")}}, error));
  EXPECT_NE(error.find("read-only"), std::string::npos) << error;
  EXPECT_EQ(icm_test::read_text(a), "new a\n");
  EXPECT_EQ(icm_test::read_text(b), "new b\n");
  EXPECT_EQ(dir.number_of_entries(), 2u);
}

TEST(LibraryEntryPoints, NotRunBeforeTheFirstRunAndEmptyMeshes)
{
  EXPECT_STREQ(ICM::error_message(ICM::NOT_RUN), "not run");
  const ICM::Inverse_curvature_map_parameterizer_3<Mesh> parameterizer;
  EXPECT_EQ(parameterizer.report().status, ICM::NOT_RUN);
  EXPECT_EQ(parameterizer.report().message, "not run");
  const ICM::Surface_parameterization_report report;
  EXPECT_EQ(report.status, ICM::NOT_RUN);
  EXPECT_EQ(report.message, "not run");
  // NOT_RUN is no CGAL code.
  for(int code = SMP::OK; code <= SMP::ERROR_WRONG_PARAMETER; ++code)
    EXPECT_NE(static_cast<SMP::Error_code>(code), ICM::NOT_RUN);

  // An empty mesh: ERROR_EMPTY_MESH from the member function (CGAL's wrapper cannot be
  // called without a border halfedge) and from the one call.
  Mesh empty;
  auto uv = empty.add_property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;
  auto done = empty.add_property_map<Mesh::Vertex_index, bool>("v:done").first;
  ICM::Inverse_curvature_map_parameterizer_3<Mesh> p;
  EXPECT_EQ(p.parameterize(empty, Mesh::null_halfedge(), uv, get(CGAL::vertex_index, empty), done),
            SMP::ERROR_EMPTY_MESH);
  EXPECT_EQ(p.report().status, SMP::ERROR_EMPTY_MESH);
  EXPECT_STREQ(ICM::error_message(p.report().status), "Input mesh is empty");
  auto corner_uv = empty.add_property_map<Mesh::Halfedge_index, Kernel::Point_2>("h:uv").first;
  EXPECT_EQ(ICM::parameterize(empty, corner_uv).status, SMP::ERROR_EMPTY_MESH);
}

TEST(LibraryEntryPoints, ProgressCallbackReportsStagesWithGrowingFractions)
{
  // Two components (a disk and a closed sphere): each stage of each, then "done" at 1.
  Mesh mesh;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(icm_test::data_path("sphere966.off"), mesh));
  Mesh disk;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(icm_test::data_path("nefertiti.off"), disk));
  CGAL::copy_face_graph(disk, mesh);
  std::vector<std::pair<std::string, double>> calls;
  ICM::Surface_parameterization_options options;
  options.progress = [&calls](const std::string& stage, double fraction) { calls.push_back({stage, fraction}); };
  auto uv = mesh.add_property_map<Mesh::Halfedge_index, Kernel::Point_2>("h:uv").first;
  ASSERT_EQ(ICM::parameterize(mesh, uv, options).status, SMP::OK);
  ASSERT_GE(calls.size(), 7u);
  EXPECT_EQ(calls.front(), (std::pair<std::string, double>{"cones", 0.0}));
  EXPECT_EQ(calls.back(), (std::pair<std::string, double>{"done", 1.0}));
  int optimum_calls = 0;
  for(std::size_t i = 0; i < calls.size(); ++i)
  {
    EXPECT_GE(calls[i].second, 0.0);
    EXPECT_LE(calls[i].second, 1.0);
    if(i > 0)
    {
      EXPECT_GE(calls[i].second, calls[i - 1].second) << calls[i].first;
    }
    optimum_calls += calls[i].first == "optimum";
  }
  EXPECT_EQ(optimum_calls, 2); // one per component
}

TEST(LibraryEntryPoints, ProgressMovesThroughTheGreedyConeRounds)
{
  // The cones stage reports each greedy round (a solve of the whole mesh each, the bulk of a
  // large closed mesh's time), not only its start; within a stage the fraction never falls.
  Mesh mesh;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(icm_test::data_path("sphere966.off"), mesh));
  std::vector<std::pair<std::string, double>> calls;
  ICM::Surface_parameterization_options options;
  options.progress = [&calls](const std::string& stage, double fraction) { calls.push_back({stage, fraction}); };
  std::vector<double> rounds;
  options.cones.progress = [&rounds](double done) { rounds.push_back(done); };
  auto uv = mesh.add_property_map<Mesh::Halfedge_index, Kernel::Point_2>("h:uv").first;
  const ICM::Surface_parameterization_report report = ICM::parameterize(mesh, uv, options);
  ASSERT_EQ(report.status, SMP::OK) << report.message;
  std::set<double> cone_fractions;
  for(std::size_t i = 0; i < calls.size(); ++i)
  {
    if(i > 0 && calls[i].first == calls[i - 1].first)
    {
      EXPECT_GE(calls[i].second, calls[i - 1].second) << calls[i].first << " at call " << i;
    }
    if(calls[i].first == "cones")
      cone_fractions.insert(calls[i].second);
  }
  EXPECT_GT(cone_fractions.size(), 1u) << "the cones stage reported only its start";
  EXPECT_LE(*cone_fractions.rbegin(), 0.35) << "the cut starts at 35%";
  // The user's own callback of the placement sees the rounds too, ending at 1.
  ASSERT_GE(rounds.size(), 2u);
  EXPECT_TRUE(std::is_sorted(rounds.begin(), rounds.end()));
  EXPECT_EQ(rounds.back(), 1.0);
  EXPECT_GE(report.charts.at(0).cones.size() + 1, rounds.size()) << "one call per round and one at the end";
}

/// nefertiti with every coordinate multiplied by `scale`.
Mesh scaled_nefertiti(double scale)
{
  Mesh mesh;
  EXPECT_TRUE(CGAL::IO::read_polygon_mesh(icm_test::data_path("nefertiti.off"), mesh));
  for(Mesh::Vertex_index v : vertices(mesh))
  {
    const Kernel::Point_3 p = mesh.point(v);
    mesh.point(v) = Kernel::Point_3(p.x() * scale, p.y() * scale, p.z() * scale);
  }
  return mesh;
}

TEST(ScaleFree, IndexAndUvsDoNotDependOnTheMeshsUnits)
{
  // The index is the same at every scale; CGAL's parameterize() gives UVs in the mesh's
  // units, so they scale with it.
  std::vector<std::array<double, 3>> unit_points;
  std::vector<Kernel::Point_2> unit_uvs;
  double unit_scale = 0;
  for(const double scale : {1.0, 1e-300, 1e+300, 1e-150})
  {
    Mesh mesh = scaled_nefertiti(scale);
    ICM::internal::Mesh_index index;
    std::vector<Mesh::Vertex_index> vertices;
    ASSERT_TRUE(
      ICM::internal::index_mesh(mesh, *faces(mesh).begin(), get(CGAL::vertex_point, mesh), index, vertices).ok());
    if(unit_points.empty())
    {
      unit_points = index.points;
      unit_scale = index.normalisation.scale;
    }
    EXPECT_NEAR(index.normalisation.scale / scale, unit_scale, 1e-12 * unit_scale) << "scale " << scale;
    for(std::size_t v = 0; v < unit_points.size(); ++v)
      for(int k = 0; k < 3; ++k)
        EXPECT_NEAR(index.points[v][k], unit_points[v][k], 1e-12) << "scale " << scale;

    auto uv = mesh.add_property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;
    ICM::Inverse_curvature_map_parameterizer_3<Mesh> parameterizer;
    // Not longest_border(): its lengths underflow to 0 at 1e-300 and it returns no halfedge.
    Mesh::Halfedge_index bhd;
    for(Mesh::Halfedge_index h : halfedges(mesh))
      if(is_border(h, mesh))
        bhd = h;
    ASSERT_EQ(SMP::parameterize(mesh, parameterizer, bhd, uv), SMP::OK)
      << scale << ": " << parameterizer.report().message;
    std::vector<Kernel::Point_2> uvs;
    for(Mesh::Vertex_index v : CGAL::vertices(mesh))
      uvs.push_back(get(uv, v));
    if(unit_uvs.empty())
      unit_uvs = uvs;
    double worst = 0, extent = 0;
    for(std::size_t i = 0; i < uvs.size(); ++i)
    {
      extent = std::max({extent, std::abs(unit_uvs[i].x()), std::abs(unit_uvs[i].y())});
      worst = std::max(
        {worst, std::abs(uvs[i].x() / scale - unit_uvs[i].x()), std::abs(uvs[i].y() / scale - unit_uvs[i].y())});
    }
    EXPECT_LT(worst, 1e-9 * extent) << "scale " << scale;
  }
}

} // namespace
