// The result of `icm.parameterize` (icm_module_result.h).

#include "icm_module_result.h"

#include <ICM/IO/Uv_mesh.h>

#include <array>
#include <cstddef>

namespace icm_module {

namespace {

// The report's keys in three parts, each added to `d` in the order of icm_param's JSON line.

/// The mesh and the surface's run: charts, cones, seams, checks, metric.
void add_surface_figures(py::dict& d, const Mesh& mesh, const Run_figures& t)
{
  const ICM::Surface_summary& s = t.summary;
  d["vertices"] = num_vertices(mesh);
  d["faces"] = num_faces(mesh);
  d["charts"] = s.charts;
  d["components"] = t.components;
  d["boundary_loops"] = s.boundary_loops;
  d["genus"] = s.genus;
  d["cones"] = s.cones;
  d["cones_above_full_turn"] = s.wide_cones;
  d["cones_given_up"] = s.cones_given_up;
  d["seam_edges"] = t.seam_edges;
  d["seam_length"] = t.seam_length;
  d["layout"] = s.layouts;
  d["newton_iterations"] = s.newton_iterations;
  d["newton_factorizations"] = s.factorizations;
  d["newton_preconditioned_solves"] = s.preconditioned_solves;
  d["max_curvature_error"] = s.max_curvature_error;
  d["max_layout_length_error"] = s.max_layout_length_error;
  d["seam_length_error"] = s.seam_length_error;
  d["overlapping_border_edges"] = s.overlapping_border_edges;
  d["raw_overlapping_border_edges"] = s.raw_overlapping_border_edges;
  d["moved_vertices"] = s.moved_vertices;
  d["metric"] = s.metrics;
  d["metric_fallback"] = s.fallback_reason;
}

/// The energy other than the entropy, the prescribed border and the atlas, when there is one.
void add_energy_border_and_atlas(py::dict& d, const Run_figures& t, const Request& request)
{
  d["energy"] = t.energy;
  if(t.energy_run)
  {
    d["energy_iterations"] = t.energy_run->iterations;
    d["initial_energy"] = t.energy_run->initial_energy;
    d["final_energy"] = t.energy_run->final_energy;
    d["energy_message"] = t.energy_run->message;
  }
  d["boundary"] = t.boundary;
  if(t.boundary != "free")
  {
    d["degenerate_faces"] = t.degenerate_faces;
    d["border_iterations"] = t.border_iterations;
    d["circle_deviation"] = t.circle_deviation;
  }
  if(const std::optional<ICM::Atlas_options>& atlas = request.options.atlas)
  {
    d["atlas_size"] = atlas->size;
    d["atlas_padding"] = atlas->padding;
    d["atlas_packer"] = ICM::atlas_packer_name(atlas->packer);
    d["atlas_charts"] = t.atlas_charts;
    d["atlas_rotated_charts"] = t.atlas_rotated_charts;
    d["atlas_utilization"] = t.atlas_utilization;
  }
}

/// The distortion, the repairs of the input and the times.
void add_distortion_repairs_and_times(py::dict& d, const Run_figures& t, const ICM::IO::Mesh_reading_report& read,
                                      const ICM::Distortion_measures& m)
{
  d["flipped_faces"] = m.flipped_faces;
  d["log_area_distortion"] = m.log_area_distortion;
  d["log_area_distortion_area_weighted"] = m.log_area_distortion_area_weighted;
  d["area_ratio_min"] = m.area_ratio_min;
  d["area_ratio_max"] = m.area_ratio_max;
  d["qc_mean"] = m.qc_mean;
  d["isolated_vertices_dropped"] = read.isolated_vertices.size();
  d["vertices_split"] = read.split_vertices.size();
  d["faces_reoriented"] = read.reoriented_faces.size();
  d["repairs"] = list_of(read.repairs());
  d["seconds_index"] = t.seconds_index;
  d["seconds_cones"] = t.seconds_cones;
  d["seconds_optimum"] = t.seconds_optimum;
  d["seconds_cut"] = t.seconds_cut;
  d["seconds_layout"] = t.seconds_layout;
  d["seconds_parameterize"] = t.seconds_total;
}

} // namespace

py::dict report_dict(const Mesh& mesh, const Run_figures& t, const Request& request,
                     const ICM::IO::Mesh_reading_report& read, const ICM::Distortion_measures& m)
{
  py::dict d;
  add_surface_figures(d, mesh, t);
  add_energy_border_and_atlas(d, t, request);
  add_distortion_repairs_and_times(d, t, read, m);
  return d;
}

Parameterization result_of(const py::object& F, const Mesh& mesh, Corner_uv_map uvmap,
                           const std::vector<Mesh::Edge_index>& seams, const ICM::IO::Mesh_reading_report& read)
{
  const ICM::IO::Uv_mesh uv_mesh = ICM::IO::make_uv_mesh_from_corners(mesh, uvmap);
  const auto faces = index_rows(F, read.file_vertices, faces_of_V);
  std::vector<std::array<std::int64_t, 3>> fuv(uv_mesh.number_of_faces());
  for(std::size_t f = 0; f < fuv.size(); ++f)
    for(int k = 0; k < 3; ++k)
    {
      const std::size_t row = read.file_vertex[static_cast<std::size_t>(uv_mesh.face_positions[f][k])];
      int column = 0;
      while(column < 3 && static_cast<std::size_t>(faces.at(static_cast<py::ssize_t>(f), column)) != row)
        ++column;
      if(column == 3)
        throw Icm_error("internal error: face " + std::to_string(f) + " of the mesh is not row " + std::to_string(f) +
                        " of F");
      fuv[f][column] = uv_mesh.face_uvs[f][k];
    }
  std::vector<std::array<std::size_t, 2>> seam_rows;
  seam_rows.reserve(seams.size());
  for(Mesh::Edge_index e : seams)
    seam_rows.push_back({read.file_vertex[static_cast<std::size_t>(source(e, mesh))],
                         read.file_vertex[static_cast<std::size_t>(target(e, mesh))]});
  Parameterization result;
  result.uv = array_of<double>(uv_mesh.uvs, 2);
  result.fuv = array_of<std::int64_t>(fuv, 3);
  result.seams = seam_rows.empty() ? py::array_t<std::int64_t>(std::vector<py::ssize_t>{0, 2})
                                   : array_of<std::int64_t>(seam_rows, 2);
  return result;
}

std::string repairs_note(const ICM::IO::Mesh_reading_report& read)
{
  std::string note;
  for(const std::string& repair : read.repairs())
    note += (note.empty() ? " (the input was repaired: " : "; ") + repair;
  return note.empty() ? note : note + ")";
}

} // namespace icm_module
