// The jobs of the registry's methods, on a disk and on a seam mesh (jobs.h).

#include "jobs.h"

#include <ICM/measures/Distortion.h>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <child_process.h>

namespace compare {

namespace PMP = CGAL::Polygon_mesh_processing;

Job method_job(const Mesh& input, const Method& method)
{
  return [&input, &method](Child_result& r, bool measure) {
    Mesh mesh = input; // the method's own copy
    UV_map uvmap = mesh.add_property_map<vertex_descriptor, Point_2>("v:compare_uv", Point_2(0, 0)).first;
    const halfedge_descriptor bhd = PMP::longest_border(mesh).first;
    const Run_result run = method.run(mesh, bhd, uvmap);
    r.peak_rss_mb = icm_tools::peak_rss_mb(); // right after the run, before measuring
    r.code = static_cast<int>(run.code);
    r.seconds = run.seconds;
    r.newton_iterations = run.newton_iterations;
    r.metric = run.metric;
    r.message = run.message;
    r.extra = run.report_numbers;
    r.fallback_reason = run.fallback_reason;
    if(measure && has_usable_uvs(run.code))
    {
      r.m = to_measures(ICM::measure_distortion(mesh, uvmap));
      r.has_measures = true;
    }
  };
}

namespace {

// Why the mesh cut along its seams is not one disk, or empty.
std::string not_a_disk(const Seam_mesh& seam_mesh)
{
  std::vector<seam_halfedge_descriptor> cycles;
  PMP::extract_boundary_cycles(seam_mesh, std::back_inserter(cycles));
  const long chi = static_cast<long>(num_vertices(seam_mesh)) - static_cast<long>(num_edges(seam_mesh)) +
                   static_cast<long>(num_faces(seam_mesh));
  if(cycles.size() == 1 && chi == 1)
    return {};
  return "the cut leaves " + std::to_string(cycles.size()) + " border loops, chi " + std::to_string(chi);
}

} // namespace

Job seam_job(const Mesh& input, const std::vector<std::size_t>& seams, const Seam_method& method)
{
  return [&input, &seams, &method](Child_result& r, bool measure) {
    Mesh mesh = input;
    Seam_edge_map seam_edge = mesh.add_property_map<edge_descriptor, bool>("e:compare_seam", false).first;
    Seam_vertex_map seam_vertex = mesh.add_property_map<vertex_descriptor, bool>("v:compare_seam", false).first;
    Corner_UV_map uvmap = mesh.add_property_map<halfedge_descriptor, Point_2>("h:compare_uv", Point_2(0, 0)).first;
    Seam_mesh seam_mesh(mesh, seam_edge, seam_vertex);
    for(std::size_t i : seams)
    {
      const edge_descriptor e(static_cast<Mesh::size_type>(i));
      seam_mesh.add_seam(source(e, mesh), target(e, mesh));
    }
    if(const std::string why = not_a_disk(seam_mesh); !why.empty())
    {
      r.code = static_cast<int>(SMP::ERROR_NO_TOPOLOGICAL_DISC);
      r.message = why;
      return;
    }
    const seam_halfedge_descriptor bhd = PMP::longest_border(seam_mesh).first;
    const Run_result run = method.run(seam_mesh, bhd, uvmap);
    r.peak_rss_mb = icm_tools::peak_rss_mb();
    r.code = static_cast<int>(run.code);
    r.seconds = run.seconds;
    r.message = run.message;
    if(measure && has_usable_uvs(run.code))
    {
      r.m = to_measures(ICM::measure_distortion(seam_mesh, uvmap));
      r.has_measures = true;
    }
  };
}

} // namespace compare
