// compare's meshes (meshes.h).

#include "meshes.h"

#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/subdivision_method_3.h>

#include <exception>
#include <vector>

namespace compare {

namespace PMP = CGAL::Polygon_mesh_processing;

std::string mesh_name(const std::string& path)
{
  std::string name = path;
  const auto slash = name.find_last_of('/');
  if(slash != std::string::npos)
    name = name.substr(slash + 1);
  const auto dot = name.find_last_of('.');
  if(dot != std::string::npos && dot > 0)
    name = name.substr(0, dot);
  return name;
}

void open_at_first_vertex(Mesh& mesh)
{
  std::vector<face_descriptor> around;
  for(face_descriptor f : CGAL::faces_around_target(halfedge(*vertices(mesh).begin(), mesh), mesh))
    around.push_back(f);
  for(face_descriptor f : around)
    CGAL::Euler::remove_face(halfedge(f, mesh), mesh);
}

namespace {

/// Runs a CGAL reader or writer: false with `error` its exception's message, or `failure`
/// when it returns false.
template <class Io>
bool io_succeeds(Io&& io, const char* failure, std::string& error)
{
  try
  {
    if(io())
      return true;
    error = failure;
  }
  catch(const std::exception& e)
  {
    error = e.what();
  }
  return false;
}

} // namespace

bool load_mesh(const std::string& path, const Options& opt, Mesh& mesh, std::string& error)
{
  mesh.clear();
  if(!io_succeeds([&] { return CGAL::IO::read_polygon_mesh(path, mesh); }, "cannot read a polygon mesh from this file",
                  error))
    return false;
  if(num_faces(mesh) == 0)
  {
    error = "the mesh has no faces";
    return false;
  }
  if(!CGAL::is_triangle_mesh(mesh))
    PMP::triangulate_faces(mesh);
  if(opt.subdivide > 0)
    CGAL::Subdivision_method_3::Loop_subdivision(
      mesh, CGAL::parameters::number_of_iterations(static_cast<unsigned int>(opt.subdivide)));
  if(opt.open && CGAL::is_closed(mesh))
    open_at_first_vertex(mesh);
  if(mesh.has_garbage())
    mesh.collect_garbage();
  return true;
}

bool write_mesh(const std::string& path, const Mesh& mesh, std::string& error)
{
  return io_succeeds([&] { return CGAL::IO::write_polygon_mesh(path, mesh, CGAL::parameters::stream_precision(17)); },
                     "cannot write the mesh to this file", error);
}

Topology topology_of(Mesh& mesh)
{
  Topology t;
  auto fccmap = mesh.add_property_map<face_descriptor, std::size_t>("f:compare_cc").first;
  t.components = PMP::connected_components(mesh, fccmap);
  mesh.remove_property_map(fccmap);
  std::vector<halfedge_descriptor> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  t.loops = static_cast<long>(cycles.size());
  t.chi =
    static_cast<long>(num_vertices(mesh)) - static_cast<long>(num_edges(mesh)) + static_cast<long>(num_faces(mesh));
  return t;
}

std::string disk_check(Mesh& mesh)
{
  const Topology t = topology_of(mesh);
  const long b = t.loops;
  if(t.components != 1)
    return "skipped: not a disk (" + std::to_string(t.components) + " components, " + std::to_string(b) + " loops)";
  const long two_g = 2 - b - t.chi;
  const std::string genus = two_g % 2 == 0 ? std::to_string(two_g / 2) : "?";
  if(b != 1 || two_g != 0)
    return "skipped: not a disk (" + std::to_string(b) + " loops, genus " + genus + ")";
  return "";
}

} // namespace compare
