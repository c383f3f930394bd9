// The Python module `icm` (its compiled part `_icm`): ICM::parameterize and the prescribed
// borders of Inverse_curvature_map_parameterizer_3, ICM's checked mesh readers and UV mesh
// writers, and the distortion measures, on numpy arrays (doc/python.md).
//
// This file runs `icm.parameterize` from its parts and binds; the parts, by what they do:
// - icm_module_arrays.*: the numpy arrays in (each checked, refused with `icm.Error`, never
//   passed on unchecked; V and F through the soup-to-mesh checks and repairs of a file read
//   by icm_param) and out;
// - icm_module_request.*: the other arguments, checked into icm_param's options, refused
//   together where icm_param refuses them together, and the cones and seams on the mesh;
// - icm_module_run.*: the runs, icm_param's (examples/icm_param_energy.h), every metric,
//   energy and border condition it takes, so that the module runs what icm_param runs;
// - icm_module_result.*: the UVs, the seams and the report back on the rows of V and F;
// - icm_module_meshes.*: read_mesh, write_mesh and measure_distortion.

#include "icm_module_meshes.h"
#include "icm_module_result.h"

#include <ICM/IO/write_uv_files.h>

#include <exception>
#include <map>
#include <new>
#include <string>
#include <utility>
#include <vector>

namespace icm_module {

namespace {

/// `icm.parameterize`: the arguments checked, V and F made a mesh, the run, and its result on
/// the rows of V and F; a failure after the input's repairs names them.
Parameterization parameterize(const py::object& V, const py::object& F, const py::object& cones,
                              const std::vector<std::pair<long long, double>>& cone, const std::string& energy,
                              const py::object& atlas, int padding, const py::object& seams, const std::string& metric,
                              const std::string& boundary, bool keep_overlaps)
{
  const Request request = request_of(cones, energy, metric, boundary, atlas, padding, keep_overlaps);
  if(const std::string conflict = border_conflict(request, !cone.empty(), !seams.is_none()); !conflict.empty())
    throw Icm_error(conflict);
  ICM::IO::Mesh_reading_report read;
  Mesh mesh = mesh_of(V, F, read);
  try
  {
    const Vertices_by_row by_row = vertices_by_row(read);
    const std::map<Mesh::Vertex_index, double> user_cones = user_cones_of(cone, by_row);
    const std::vector<Mesh::Edge_index> user_seams =
      seams.is_none() ? std::vector<Mesh::Edge_index>() : user_seams_of(seams, mesh, by_row);
    const Corner_uv_map uvmap = mesh.add_property_map<Mesh::Halfedge_index, Kernel::Point_2>("h:uv").first;
    std::vector<Mesh::Edge_index> cut;
    const Run_figures figures = request.prescribes_border()
                                  ? run_border(request, mesh, uvmap)
                                  : run_surface(request, mesh, uvmap, user_cones, user_seams, cut);
    Parameterization result = result_of(F, mesh, uvmap, cut, read);
    result.report = report_dict(mesh, figures, request, read, ICM::measure_distortion_corner_uv(mesh, uvmap));
    result.charts = figures.summary.charts;
    return result;
  }
  catch(const Icm_error& e)
  {
    throw Icm_error(e.what() + repairs_note(read), e.code);
  }
}

/// `icm.Error`, and the translation of `Icm_error` into it (with its code) and of
/// std::bad_alloc into MemoryError.
void register_errors(py::module_& m)
{
  static py::exception<Icm_error> error(m, "Error", PyExc_ValueError);
  error.attr("__module__") = "icm"; // icm.Error, as users name it
  error.attr("__doc__") = "A refused input or a failed run: the reason is the message; `code` is ICM's error code "
                          "(CGAL::Surface_mesh_parameterization::Error_code) where there is one, else None.";
  py::register_exception_translator([](std::exception_ptr p) {
    try
    {
      if(p)
        std::rethrow_exception(p);
    }
    catch(const Icm_error& e)
    {
      py::object instance = py::handle(error.ptr())(e.what()); // an instance, not raised yet
      instance.attr("code") = e.code ? py::object(py::int_(*e.code)) : py::object(py::none());
      PyErr_SetObject(error.ptr(), instance.ptr());
    }
    catch(const std::bad_alloc&)
    {
      PyErr_SetString(PyExc_MemoryError, "out of memory");
    }
  });
}

void bind_parameterization(py::module_& m)
{
  py::class_<Parameterization>(m, "Parameterization",
                               "The result of parameterize(): the UVs, their faces, the charts, the seams, the report.")
    .def_readonly("uv", &Parameterization::uv, "float64 array (k, 2): one row per UV corner index")
    .def_readonly("fuv", &Parameterization::fuv,
                  "int64 array (m, 3): for each row of F, the rows of uv of its three corners, in F's order")
    .def_readonly("charts", &Parameterization::charts, "the number of charts")
    .def_readonly("seams", &Parameterization::seams, "int64 array (s, 2): the seam edges, as pairs of rows of V")
    .def_readonly("report", &Parameterization::report,
                  "dict: the run's figures under the keys of icm_param's --json line (doc/cli.md)")
    .def("__repr__", [](const Parameterization& p) {
      return "<icm.Parameterization: " + std::to_string(p.uv.shape(0)) + " UVs, " + std::to_string(p.fuv.shape(0)) +
             " faces, " + std::to_string(p.charts) + " charts>";
    });
}

void def_parameterize(py::module_& m)
{
  m.def("parameterize", &parameterize, py::arg("V"), py::arg("F"), py::kw_only(), py::arg("cones") = "auto",
        py::arg("cone") = std::vector<std::pair<long long, double>>(), py::arg("energy") = "entropy",
        py::arg("atlas") = py::none(), py::arg("padding") = 4, py::arg("seams") = py::none(),
        py::arg("metric") = ICM::Default_metric::name, py::arg("boundary") = "free", py::arg("keep_overlaps") = false,
        R"(Parameterizes a triangle mesh (any topology) with ICM::parameterize, or a disk with a
prescribed border; each argument is the icm_param option of the same name (doc/cli.md).

V: float64 array (n, 3) of vertex positions; F: integer array (m, 3) of rows of V.
cones: "auto" (cones where the distortion asks for them) or an exact count of automatic
  cones (0: only the border and the user's cones and seams are singular).
cone: list of (vertex, degrees): vertices that must be cones with that total angle.
energy: one of icm.ENERGIES ("entropy", "u-square", "area", "angle", "log-area"); another
  energy than the entropy is minimised from the entropy optimum with its cones.
atlas: None (the charts at their 3D scale, side by side) or a texture size in texels: every
  chart in [0, 1]^2, `padding` texels apart.
seams: None, or an integer array (s, 2) of pairs of rows of V joined by an interior edge
  (icm_param --seams FILE): a component with any is cut along exactly these edges, their ends
  and branch points are its cones, whose angles the optimum chooses, and it gets no automatic
  cone; the components without any get automatic cones only when `cones` is a count.
metric: one of icm.METRICS ("intrinsic-delaunay", "vertex-scaling", "inversive-distance",
  "circle-packing"), with any energy and border.
boundary: one of icm.BOUNDARIES: "free", or "circle" or "square" (a disk's border on a circle
  or a square) or "circle-domain" (genus 0, every border loop a circle): the entropy's map
  with that border, without energy, cone, cones (but 0), seams or atlas.
keep_overlaps: keep a chart that folds over itself rather than cut it into pieces that do
  not; with a prescribed border (one chart, never cut) return such a map rather than fail.
The GIL is released during the solve. Returns an icm.Parameterization; raises icm.Error on a
refused input or a failed run (with `code`, ICM's error code, where there is one).)");
}

void def_mesh_functions(py::module_& m)
{
  m.def("read_mesh", &read_mesh, py::arg("path"), py::kw_only(), py::arg("triangulate") = false,
        R"(Reads a mesh file (OFF, OBJ, PLY or STL, by extension) through ICM's checked readers.

Returns (V, F, repairs): float64 (n, 3), int64 (m, 3) and the list of the repairs made
(isolated vertices dropped, non-manifold vertices split, faces reoriented, polygons
triangulated with triangulate=True). Raises icm.Error naming the reason of a refusal.)");
  m.def("write_mesh", &write_mesh, py::arg("path"), py::arg("V"), py::arg("F"), py::arg("uv"), py::arg("fuv"),
        py::kw_only(), py::arg("binary_ply") = false,
        R"(Writes the mesh with its UVs in the format the extension names: .obj, .ply, .gltf or .glb
(glTF only when icm.HAS_GLTF). uv/fuv as parameterize() returns them. The file is replaced only
once it is written whole. Raises icm.Error with the reason.)");
  m.def("measure_distortion", &measure_distortion, py::arg("V"), py::arg("F"), py::arg("uv"), py::arg("fuv"),
        R"(The distortion of the map from each 3D triangle (V, F) to its UV triangle (uv, fuv), as
ICM::measure_distortion_corner_uv gives it (doc/distortion.md): a dict with faces, flipped_faces,
degenerate_uv_faces, degenerate_3d_faces, conformality, angle_distortion, l2_shear, l2_stretch,
log_area_distortion, log_area_distortion_area_weighted, area_ratio_min, area_ratio_max, qc_mean,
qc_max.)");
}

} // namespace

} // namespace icm_module

PYBIND11_MODULE(_icm, m)
{
  using namespace icm_module;
  m.doc() = "ICM: conformal parameterization of triangle meshes by the inverse curvature map (doc/python.md).";
  register_errors(m);
  m.attr("ENERGIES") = py::cast(energy_names());
  m.attr("METRICS") = py::cast(metric_names());
  m.attr("BOUNDARIES") = py::cast(boundary_names());
  m.attr("HAS_GLTF") = ICM::IO::writes_gltf();

  bind_parameterization(m);
  def_parameterize(m);
  def_mesh_functions(m);
}
