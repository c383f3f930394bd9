// One call for any triangle mesh: `ICM::parameterize(mesh, uv_map, options)`.
//
// CGAL's `Parameterizer_3` concept takes one border halfedge and writes one UV per vertex, so
// it only fits a disk. This entry point takes any triangle mesh (closed, any genus, holes,
// several components) and writes one UV per corner (a halfedge map, as CGAL's `Seam_mesh`
// examples use). Per connected component, the two levels of the pipeline stay apart:
//   on the surface as given   index -> cones (cones/) -> entropy optimum with the cones
//                             singular, in the metric's class (optimum/Optimal_metric.h), or
//                             the minimum of another energy over the same singular set
//                             (optimum/Curvature_space_optimizer.h)
//   on the surface cut open   cut graph and wedges (cut/) -> layout of the surface's flat
//                             metric, both sides of a seam one length (layout/) -> checks:
//                             orientation, lengths, seams, border overlaps
// (pipeline/Surface_component.h), and the charts are then packed side by side
// (layout/Chart_packing.h), or into the unit square of a texture (`options.atlas`,
// layout/Atlas_packing.h). Options and reports: Options.h, Report.h. See
// doc/surfaces.md.

#ifndef ICM_PARAMETERIZE_H
#define ICM_PARAMETERIZE_H

#include <ICM/Status.h>
#include <ICM/Options.h>
#include <ICM/Report.h>
#include <ICM/internal/Mesh_index.h>
#include <ICM/internal/Stopwatch.h>
#include <ICM/pipeline/Surface_component.h>

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

namespace CGAL {
// Declared only: Seam_mesh.h itself must come after the BGL header of the mesh under it.
template <class TM, class SEM, class SVM>
class Seam_mesh;
} // namespace CGAL

namespace ICM {

/// \brief Parameterizes any triangle mesh: every connected component is cut into a disk
/// through its cones (chosen automatically, or the user's), laid out with the minimum of the
/// curvature entropy in the class of `Metric` (or of `Energy` over the same border and
/// cones), and the charts are packed side by side at their 3D scale (with `options.atlas`,
/// into [0, 1]^2 at one scale, padded apart in texels).
///
/// \image html cones.svg "Area distortion (area-weighted mean log² area) and charts against the number of cones, per mesh; solid: the entropy's cone angles, dashed: U_square's (doc/benchmarks.md, Cones)" width=100%
///
/// \tparam TriangleMesh a model of `FaceGraph`
/// \tparam HalfedgeUVMap a writable property map from `halfedge_descriptor` to a 2D point:
///         the UV of the corner at `target(h)` in `face(h)` (border halfedges get the UV of
///         the corner across `next(h)`). It serves directly as the UV map of a
///         `CGAL::Seam_mesh` whose seams are `seam_edges`.
/// \tparam Metric a model of \ref ::Metric "Metric"; `CGAL::Default` is `Default_metric`
/// \tparam SparseSolver a model of \ref ::SparseSolver "SparseSolver"; `CGAL::Default` is
///         `Default_sparse_solver`
/// \tparam Energy a model of \ref ::Energy "Energy" (doc/energies.md); `CGAL::Default` is
///         `Curvature_entropy`. Another energy is minimised over the conformal maps with the
///         singular set the entropy's run chose (the border and the cones; a user cone's
///         fixed angle stays fixed), from the entropy optimum, by
///         `minimize_energy_on_singular_values` with `options.energy`
/// \param mesh the triangle mesh; it is not modified
/// \param uv_map receives one UV per corner (see `HalfedgeUVMap`)
/// \param options cones, Newton, fallback and overlap options (doc/parameterizer.md)
/// \param user_cones vertices that must be singular: with a curvature 2 pi - angle, or NaN
///        to leave the angle to the optimum (Thm 3.5)
/// \param seam_edges if not null, receives the seam edges of every chart
/// \param user_seams the user's own cut (as a CGAL selection file gives it): a component with
///        any of these edges is cut along exactly them (they must cut it into one disk through
///        every user cone), their ends and branch points become singular with a free angle
///        and no automatic cone is added; a component without any is cut as usual
/// \param energy the energy's own settings (for example `Log_area_distortion`'s weighting)
/// \returns the status, the reason of a failure and one `Chart_report` per component
///          (doc/report.md)
template <class Metric_ = CGAL::Default, class SparseSolver = CGAL::Default, class Energy_ = CGAL::Default,
          class TriangleMesh, class HalfedgeUVMap>
Surface_parameterization_report
parameterize(const TriangleMesh& mesh, HalfedgeUVMap uv_map,
             const Surface_parameterization_options& options = Surface_parameterization_options(),
             const std::map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, double>& user_cones = {},
             std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>* seam_edges = nullptr,
             const std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>& user_seams = {},
             const typename CGAL::Default::Get<Energy_, Curvature_entropy>::type& energy =
               typename CGAL::Default::Get<Energy_, Curvature_entropy>::type())
{
  using namespace CGAL::Surface_mesh_parameterization;
  using Metric = typename CGAL::Default::Get<Metric_, Default_metric>::type;
  using Solver = typename CGAL::Default::Get<SparseSolver, Default_sparse_solver>::type;
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  const internal::Stopwatch stopwatch;

  Surface_parameterization_report report;
  auto finish = [&](Error_code code, const std::string& why) {
    report.status = code;
    report.message = why;
    report.seconds_total = stopwatch.total();
    return report;
  };
  if(const Status checked = check_options(options); !checked.ok())
    return finish(checked.code, checked.message);
  if(faces(mesh).empty())
    return finish(ERROR_EMPTY_MESH, "the mesh has no faces");
  if(const Status checked = internal::check_user_cones_and_seams(mesh, user_cones, user_seams); !checked.ok())
    return finish(checked.code, checked.message);

  // Components, each with a seed face.
  auto component_of = get(CGAL::dynamic_face_property_t<std::size_t>(), mesh);
  const std::size_t components = CGAL::Polygon_mesh_processing::connected_components(mesh, component_of);
  std::vector<face_descriptor> seeds(components, boost::graph_traits<TriangleMesh>::null_face());
  for(face_descriptor f : faces(mesh))
    if(seeds[get(component_of, f)] == boost::graph_traits<TriangleMesh>::null_face())
      seeds[get(component_of, f)] = f;

  auto is_user_seam = get(CGAL::dynamic_edge_property_t<bool>(), mesh);
  for(auto e : edges(mesh))
    put(is_user_seam, e, false);
  for(auto e : user_seams)
    put(is_user_seam, e, true);

  // One frame for every component, so that the charts are packed in common units; the UVs
  // go back to the mesh's units when written.
  std::vector<std::size_t> component_faces(components, 0);
  for(face_descriptor f : faces(mesh))
    ++component_faces[get(component_of, f)];
  const internal::Normalisation normalisation = internal::normalisation_of_corners(mesh);
  const double total_faces = static_cast<double>(num_faces(mesh));
  double faces_done = 0;

  std::vector<std::vector<Uv>> chart_uvs(components);
  std::vector<Cut_mesh> cuts(components);
  std::vector<std::vector<face_descriptor>> chart_faces(components);
  for(std::size_t c = 0; c < components; ++c)
  {
    internal::Stage_progress progress{&options.progress, faces_done / total_faces,
                                      static_cast<double>(component_faces[c]) / total_faces};
    faces_done += static_cast<double>(component_faces[c]);
    const internal::Clock::time_point indexing = internal::Clock::now();
    internal::Mesh_index index;
    std::vector<vertex_descriptor> vertices;
    const Status indexed = internal::index_mesh(mesh, seeds[c], get(CGAL::vertex_point, mesh), index, vertices,
                                                &chart_faces[c], &normalisation);
    Chart_report chart;
    chart.vertices = index.number_of_vertices();
    chart.faces = index.number_of_faces();
    chart.boundary_loops = index.number_of_boundary_loops();
    chart.genus = index.genus();
    if(!indexed.ok())
      return finish(indexed.code, "component " + std::to_string(c) + ": " + indexed.message +
                                    (components > 1 ? internal::too_small_beside_the_rest(mesh, seeds[c], normalisation)
                                                    : std::string()));
    internal::order_vertices_for_elimination_in<Metric>(index); // once for every Laplacian of the component
    report.seconds_index += internal::seconds_since(indexing);
    std::vector<char> is_user_cone, component_seams;
    std::vector<double> prescribed;
    internal::component_cones_and_seams(mesh, index, vertices, user_cones, is_user_seam, !user_seams.empty(),
                                        is_user_cone, prescribed, component_seams);
    const Status failure =
      internal::parameterize_component<Metric, Solver>(index, is_user_cone, prescribed, component_seams, options,
                                                       report, chart, cuts[c], chart_uvs[c], energy, progress);
    report.charts.push_back(chart);
    if(!failure.ok())
      return finish(failure.code, "component " + std::to_string(c) + " (" + std::to_string(chart.vertices) +
                                    " vertices, genus " + std::to_string(chart.genus) + ", " +
                                    std::to_string(chart.boundary_loops) + " boundary loops): " + failure.message);
    report.charts.back().seam_length = internal::relative_seam_length(index, cuts[c]);
    if(seam_edges)
      for(int e = 0; e < index.number_of_edges(); ++e)
        if(cuts[c].disk_edges[e][1] >= 0)
          seam_edges->push_back(
            edge(halfedge(vertices[index.edges[e][0]], vertices[index.edges[e][1]], mesh).first, mesh));
  }

  if(const Status packed = internal::pack_and_write_charts(mesh, chart_faces, cuts, chart_uvs, normalisation, uv_map,
                                                           options.atlas, report);
     !packed.ok())
    return finish(packed.code, packed.message);
  if(options.progress)
    options.progress("done", 1.0);
  return finish(OK, "");
}

/// \brief Parameterizes the surface under a `CGAL::Seam_mesh`, cut along its seams and nothing
/// else: the metric is flat across every seam, both sides of a seam get one length and fit
/// together by a rigid motion, and the seams' ends and branch points are the cones, their
/// angles chosen by the optimum (the seams are `user_seams` of the overload above). CGAL's
/// `parameterize()` with `Inverse_curvature_map_parameterizer_3` reads the same seams as free
/// border instead, whose two sides need not fit.
///
/// Every component of the underlying mesh is parameterized (a `Seam_mesh` offers no way to
/// restrict it to one), each at its own place in the plane. The seams are the whole cut:
/// `options.automatic_cones` and `options.remove_overlaps` do not apply (a cone off the seams,
/// or a cut of the overlap removal, would need seams the seam mesh does not have).
///
/// \tparam Metric, SparseSolver, Energy as the overload above: models of \ref ::Metric "Metric",
///         \ref ::SparseSolver "SparseSolver" and \ref ::Energy "Energy"
/// \tparam VertexUVMap a writable property map from the seam mesh's `vertex_descriptor` (one
///         per side of a seam) to a 2D point, as CGAL's `parameterize()` takes
/// \returns as the overload above
template <class Metric_ = CGAL::Default, class SparseSolver = CGAL::Default, class Energy_ = CGAL::Default,
          class TriangleMesh, class SeamEdgeMap, class SeamVertexMap, class VertexUVMap>
Surface_parameterization_report
parameterize(const CGAL::Seam_mesh<TriangleMesh, SeamEdgeMap, SeamVertexMap>& seam_mesh, VertexUVMap uv_map,
             const Surface_parameterization_options& options = Surface_parameterization_options(),
             const typename CGAL::Default::Get<Energy_, Curvature_entropy>::type& energy =
               typename CGAL::Default::Get<Energy_, Curvature_entropy>::type())
{
  using Uv_point = typename boost::property_traits<VertexUVMap>::value_type;
  const TriangleMesh& surface = seam_mesh.mesh();
  std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor> seams;
  for(auto e : edges(surface))
    if(seam_mesh.has_on_seam(e))
      seams.push_back(e);
  Surface_parameterization_options along_seams = options;
  along_seams.automatic_cones = false;
  along_seams.remove_overlaps = false;
  auto corner_uv = get(CGAL::dynamic_halfedge_property_t<Uv_point>(), surface);
  const Surface_parameterization_report report =
    parameterize<Metric_, SparseSolver, Energy_>(surface, corner_uv, along_seams, {}, nullptr, seams, energy);
  if(report.status == CGAL::Surface_mesh_parameterization::OK)
    for(auto f : faces(seam_mesh))
      for(auto h : CGAL::halfedges_around_face(halfedge(f, seam_mesh), seam_mesh))
        put(uv_map, target(h, seam_mesh), get(corner_uv, h.tmhd));
  return report;
}

} // namespace ICM

#endif // ICM_PARAMETERIZE_H
