// One connected component through `ICM::parameterize` (parameterize.h): on the surface as
// given its cones and the optimum of its metric, on the surface cut open the layout of that
// metric and its checks, then the overlap removal; and the charts packed side by side.

#ifndef ICM_PIPELINE_SURFACE_COMPONENT_H
#define ICM_PIPELINE_SURFACE_COMPONENT_H

#include <ICM/Status.h>
#include <ICM/Options.h>
#include <ICM/Report.h>
#include <ICM/pipeline/Component_cones.h>
#include <ICM/pipeline/Cone_angle_trials.h>
#include <ICM/pipeline/Singular_set_chart.h>
#include <ICM/cones/Singular_vertices.h>
#include <ICM/curvature/Curvature_map.h>
#include <ICM/curvature/Inverse_curvature_map.h>
#include <ICM/cut/Cut_graph.h>
#include <ICM/layout/Atlas_packing.h>
#include <ICM/layout/Border_overlaps.h>
#include <ICM/layout/Chart_packing.h>
#include <ICM/layout/Layout.h>
#include <ICM/layout/Overlap_removal.h>
#include <ICM/layout/Unflip.h>
#include <ICM/measures/Distortion.h>
#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/pipeline/Chart_solver.h>
#include <ICM/optimum/Curvature_space_optimizer.h>
#include <ICM/optimum/Energies.h>
#include <ICM/optimum/Optimal_metric.h>
#include <ICM/internal/Mesh_index.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace ICM {
namespace internal {

/// Whether the user's cones are interior vertices of `mesh` with a positive angle (or a free
/// one), and the user's seams edges of `mesh` off its border. Membership is found by
/// comparison only: a null, foreign or stale descriptor is refused, never dereferenced.
template <class TriangleMesh>
Status check_user_cones_and_seams(
  const TriangleMesh& mesh,
  const std::map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, double>& user_cones,
  const std::vector<typename boost::graph_traits<TriangleMesh>::edge_descriptor>& user_seams)
{
  std::size_t cones_in_mesh = 0;
  for(auto v : vertices(mesh))
    cones_in_mesh += user_cones.count(v);
  if(cones_in_mesh != user_cones.size())
    return Status::wrong_parameter(user_cones.count(boost::graph_traits<TriangleMesh>::null_vertex())
                                     ? "a user cone is the null vertex"
                                     : "a user cone is not a vertex of this mesh");
  for(const auto& [v, curvature] : user_cones)
  {
    if(CGAL::is_border(v, mesh))
      return Status::wrong_parameter("a user cone is a boundary vertex (border vertices are singular already; "
                                     "prescribe interior cones only)");
    if(!std::isnan(curvature) && !(curvature < 2 * M_PI))
      return Status::wrong_parameter("a user cone angle must be positive (curvature " + std::to_string(curvature) +
                                     " >= 2 pi)");
  }
  if(user_seams.empty())
    return Status::success();
  const auto mesh_halfedges = sorted_halfedges(mesh);
  for(auto e : user_seams)
  {
    if(!std::binary_search(mesh_halfedges.begin(), mesh_halfedges.end(), halfedge(e, mesh)))
      return Status::wrong_parameter("a user seam is not an edge of this mesh (or is the null edge)");
    if(CGAL::is_border(e, mesh))
      return Status::wrong_parameter("a user seam is a border edge (the border is cut already)");
  }
  return Status::success();
}

/// The singular set before automatic cones: the border, the user's cones, and the vertices
/// where user seams end or branch (a seam through a flat vertex passes it along two seam
/// edges; anywhere else the two sides meet at an angle the flat metric cannot have). Refuses
/// user cone angles on a closed surface that miss Gauss-Bonnet.
inline Status user_singular_set(const Mesh_index& index, const std::vector<char>& is_user_cone,
                                const std::vector<double>& prescribed, const std::vector<char>& user_seams,
                                std::vector<char>& is_singular)
{
  const int nv = index.number_of_vertices();
  is_singular.assign(index.is_boundary_vertex.begin(), index.is_boundary_vertex.end());
  int user_cones = 0, free_user_cones = 0;
  double sum = 0;
  for(int v = 0; v < nv; ++v)
    if(is_user_cone[v])
    {
      is_singular[v] = 1;
      ++user_cones;
      free_user_cones += std::isnan(prescribed[v]);
      sum += prescribed[v];
    }
  const int chi = index.euler_characteristic();
  if(index.number_of_boundary_loops() == 0 && user_cones > 0 && free_user_cones == 0 &&
     !meets_gauss_bonnet(sum - 2 * M_PI * chi, user_cones))
    return Status::wrong_parameter("the cone curvatures sum to " + std::to_string(sum) +
                                   ", Gauss-Bonnet needs 2 pi chi = " + std::to_string(2 * M_PI * chi) +
                                   " (chi = " + std::to_string(chi) + ")");
  if(!user_seams.empty())
  {
    const std::vector<int> seam_degree = seam_degrees(index, user_seams);
    for(int v = 0; v < nv; ++v)
      if(seam_degree[v] != 0 && seam_degree[v] != 2)
        is_singular[v] = 1;
  }
  return Status::success();
}

/// A surface with a border that wanted automatic cones and whose chart overlaps itself with
/// all of them (`chart`, `cut`, `uv`): nearly the most cones, in the greedy's order, that lay
/// out in one piece, found by bisection over the count (more cones, longer seams, more
/// overlaps: monotone on the shared disks). Each trial is a solve and a layout of the whole
/// mesh, so the bisection stops once the count is known within an eighth of the cones (on
/// lion-head Loop x2, 267k faces: 3 trials instead of 5, one cone fewer kept). That map
/// replaces the one given, with `chart.cones_given_up` the cones left out, when its area
/// distortion is at most `fewer_cones_distortion_factor` times the one with all cones;
/// otherwise, or when even one cone overlaps, the map is left as it is, for the overlap
/// removal. A user who passes a disk expects one island, but not at any price in area.
template <class Metric, class Solver, class Energy>
void keep_one_piece_with_fewer_cones(const Mesh_index& index, std::vector<char> is_singular,
                                     const std::vector<double>& prescribed, std::vector<double> expected_curvature,
                                     const std::vector<int>& placed, const Surface_parameterization_options& options,
                                     const Chart_report& before, Chart_report& chart, Cut_mesh& cut,
                                     std::vector<Uv>& uv, const Energy& energy)
{
  const int all = static_cast<int>(placed.size());
  auto keep_first = [&](int count) {
    for(int i = 0; i < all; ++i)
    {
      is_singular[placed[i]] = i < count;
      if(i >= count)
        expected_curvature[placed[i]] = prescribed[placed[i]];
    }
  };
  Surface_parameterization_report trials; // their stage seconds count as the cone stage's
  Chart_report kept_chart;
  Cut_mesh kept_cut;
  std::vector<Uv> kept_uv;
  int lo = 0, hi = all; // `hi` cones overlap; `lo` is the most that did not (0: none found yet)
  const int close_enough = std::max(1, all / 8);
  while(hi - lo > (lo == 0 ? 1 : close_enough))
  {
    const int mid = (lo + hi) / 2;
    keep_first(mid);
    Chart_report trial_chart;
    Cut_mesh trial_cut;
    std::vector<Uv> trial_uv;
    const Status status =
      cut_and_solve<Metric, Solver>(index, is_singular, prescribed, expected_curvature, {}, {}, options, trials, before,
                                    trial_chart, trial_cut, trial_uv, energy, Stage_progress());
    if(status.ok() && trial_chart.overlapping_border_edges == 0)
    {
      lo = mid;
      kept_chart = std::move(trial_chart);
      kept_cut = std::move(trial_cut);
      kept_uv = std::move(trial_uv);
    }
    else
      hi = mid;
  }
  if(lo == 0 || mean_log_area_squared(index, kept_cut, kept_uv) >
                  fewer_cones_distortion_factor * mean_log_area_squared(index, cut, uv))
    return;
  chart = std::move(kept_chart);
  cut = std::move(kept_cut);
  uv = std::move(kept_uv);
  chart.cones_given_up = all - lo;
}

/// One component: cones, cut, optimum, layout, checks, overlaps. `uv` receives one UV per
/// wedge of `cut.disk`. `user_seams` (per edge; empty: none) are taken as the cut as given,
/// their ends and branch points singular with a free angle, and no cone is added.
template <class Metric, class Solver, class Energy>
Status parameterize_component(const Mesh_index& index, const std::vector<char>& is_user_cone,
                              const std::vector<double>& prescribed, const std::vector<char>& user_seams,
                              const Surface_parameterization_options& options, Surface_parameterization_report& report,
                              Chart_report& chart, Cut_mesh& cut, std::vector<Uv>& uv, const Energy& energy,
                              const Stage_progress& progress = Stage_progress())
{
  progress("cones", 0.0);
  Clock::time_point t = Clock::now();
  std::vector<char> is_singular;
  if(const Status status = user_singular_set(index, is_user_cone, prescribed, user_seams, is_singular); !status.ok())
    return status;
  std::vector<double> expected_curvature = prescribed;
  Eigen::VectorXd first_step;
  std::vector<int> placed;
  Cone_angle_trial least_log_area;
  if(options.automatic_cones && options.cones.max_cones > 0 && user_seams.empty())
    if(const Status status = place_automatic_cones<Metric, Solver>(index, options, is_singular, expected_curvature,
                                                                   first_step, placed, least_log_area, progress);
       !status.ok())
      return status;
  if(index.number_of_boundary_loops() == 0 && index.euler_characteristic() > 0 &&
     std::count(is_singular.begin(), is_singular.end(), 1) < 2)
    return Status::wrong_parameter("a closed genus-0 surface needs at least two cones (automatic cones are off)");
  report.seconds_cones += seconds_since(t);

  const Chart_report before = chart;
  // Another energy is minimised over the cones' angles from the entropy's: it has its own.
  const Status status =
    least_log_area.empty() || !std::is_same<Energy, Curvature_entropy>::value
      ? cut_and_solve<Metric, Solver>(index, is_singular, prescribed, expected_curvature, user_seams,
                                      std::move(first_step), options, report, before, chart, cut, uv, energy, progress)
      : cut_and_solve_with_the_better_angles<Metric, Solver>(index, is_singular, prescribed, expected_curvature,
                                                             std::move(first_step), least_log_area, options, report,
                                                             before, chart, cut, uv, energy, progress);
  if(!status.ok() || !options.remove_overlaps || chart.overlapping_border_edges == 0)
    return status;
  // An exact count (`max_log_scale` 0) is the user's; an automatic one gives cones up first.
  if(index.number_of_boundary_loops() > 0 && !placed.empty() && options.cones.max_log_scale > 0)
  {
    progress("overlaps", 0.8);
    t = Clock::now();
    keep_one_piece_with_fewer_cones<Metric, Solver>(index, is_singular, prescribed, expected_curvature, placed, options,
                                                    before, chart, cut, uv, energy);
    report.seconds_cones += seconds_since(t);
    if(chart.overlapping_border_edges == 0)
      return Status::success();
  }
  progress("overlaps", 0.9);
  t = Clock::now();
  const Status removed = remove_component_overlaps(index, chart, cut, uv);
  report.seconds_layout += seconds_since(t);
  return removed;
}

/// For a component refused in the mesh's one frame: why, when in its own frame it would pass.
/// Its faces then have area but vanish beside the rest of the mesh, and no UV map in which
/// every chart keeps its 3D scale can hold both (the small chart's UVs would round to one
/// point where it is packed). Empty when the component fails in its own frame too.
template <class TriangleMesh>
std::string too_small_beside_the_rest(const TriangleMesh& mesh,
                                      typename boost::graph_traits<TriangleMesh>::face_descriptor seed,
                                      const Normalisation& common)
{
  Mesh_index own;
  std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor> vertices;
  if(!index_mesh(mesh, seed, get(CGAL::vertex_point, mesh), own, vertices).ok())
    return {};
  return "; in its own frame its faces have area, but it is " +
         message_number(own.normalisation.scale / common.scale, 3) +
         " times the size of the mesh, too small to share one UV map with the rest at their 3D scales "
         "(parameterize it on its own)";
}

/// The normalisation of the corners of every face of `mesh`: one frame for all components.
template <class TriangleMesh>
Normalisation normalisation_of_corners(const TriangleMesh& mesh)
{
  std::vector<std::array<double, 3>> corner_points;
  const auto vpm = get(CGAL::vertex_point, mesh);
  for(auto f : faces(mesh))
    for(auto v : CGAL::vertices_around_face(halfedge(f, mesh), mesh))
    {
      const auto& p = get(vpm, v);
      corner_points.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
    }
  return normalisation_of(corner_points);
}

/// The user's cones and seams on the component `index` (whose vertices are `vertices`):
/// per vertex whether it is a user cone and its prescribed curvature (NaN: free), and per
/// edge whether it is a user seam (empty when the component has none).
template <class TriangleMesh, class SeamMap>
void component_cones_and_seams(
  const TriangleMesh& mesh, const Mesh_index& index,
  const std::vector<typename boost::graph_traits<TriangleMesh>::vertex_descriptor>& vertices,
  const std::map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, double>& user_cones,
  const SeamMap& is_user_seam, bool any_user_seam, std::vector<char>& is_user_cone, std::vector<double>& prescribed,
  std::vector<char>& component_seams)
{
  is_user_cone.assign(index.number_of_vertices(), 0);
  prescribed.assign(index.number_of_vertices(), std::nan(""));
  for(int v = 0; v < index.number_of_vertices(); ++v)
  {
    const auto it = user_cones.find(vertices[v]);
    if(it != user_cones.end())
    {
      is_user_cone[v] = 1;
      prescribed[v] = it->second;
    }
  }
  component_seams.clear();
  if(!any_user_seam)
    return;
  component_seams.assign(index.number_of_edges(), 0);
  for(int e = 0; e < index.number_of_edges(); ++e)
    component_seams[e] =
      get(is_user_seam, edge(halfedge(vertices[index.edges[e][0]], vertices[index.edges[e][1]], mesh).first, mesh));
  if(std::find(component_seams.begin(), component_seams.end(), 1) == component_seams.end())
    component_seams.clear();
}

/// The connected pieces of a cut disk (the overlap removal's pieces share no wedge): the
/// piece of each wedge, and their count.
inline int wedge_pieces(const Mesh_index& disk, std::vector<int>& piece_of_wedge)
{
  std::vector<int> parent(disk.number_of_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&parent](int v) {
    while(parent[v] != v)
      v = parent[v] = parent[parent[v]];
    return v;
  };
  for(const auto& f : disk.faces)
    for(int c = 1; c < 3; ++c)
      parent[root(f[c])] = root(f[0]);
  piece_of_wedge.assign(parent.size(), -1);
  std::vector<int> piece_of_root(parent.size(), -1);
  int pieces = 0;
  for(const auto& f : disk.faces)
    for(int v : f)
    {
      int& piece = piece_of_root[root(v)];
      if(piece < 0)
        piece = pieces++;
      piece_of_wedge[v] = piece;
    }
  return pieces;
}

/// Atlas mode: every piece of every chart into [0, 1]^2 (layout/Atlas_packing.h), in place;
/// the figures into `report`. Fails when the pieces do not fit at one texel each.
inline Status pack_atlas_charts(const std::vector<Cut_mesh>& cuts, std::vector<std::vector<Uv>>& chart_uvs,
                                const Atlas_options& options, Surface_parameterization_report& report)
{
  std::vector<std::vector<int>> piece_of_wedge(cuts.size());
  std::vector<int> first_piece(cuts.size() + 1, 0);
  for(std::size_t c = 0; c < cuts.size(); ++c)
    first_piece[c + 1] = first_piece[c] + wedge_pieces(cuts[c].disk, piece_of_wedge[c]);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Chart_box> boxes(first_piece.back(), Chart_box{inf, inf, -inf, -inf});
  for(std::size_t c = 0; c < cuts.size(); ++c)
    for(std::size_t w = 0; w < chart_uvs[c].size(); ++w)
      if(piece_of_wedge[c][w] >= 0)
      {
        Chart_box& b = boxes[first_piece[c] + piece_of_wedge[c][w]];
        const Uv& p = chart_uvs[c][w];
        b = {std::min(b[0], p[0]), std::min(b[1], p[1]), std::max(b[2], p[0]), std::max(b[3], p[1])};
      }
  Atlas_packing packing;
  if(const Status packed = pack_atlas(boxes, options, packing); !packed.ok())
    return packed;
  std::vector<std::vector<std::array<int, 3>>> triangles(cuts.size());
  for(std::size_t c = 0; c < cuts.size(); ++c)
  {
    for(std::size_t w = 0; w < chart_uvs[c].size(); ++w)
      if(piece_of_wedge[c][w] >= 0)
      {
        const Uv& p = chart_uvs[c][w];
        chart_uvs[c][w] =
          packing.placements[first_piece[c] + piece_of_wedge[c][w]]({packing.scale * p[0], packing.scale * p[1]});
      }
    triangles[c] = cuts[c].disk.faces;
  }
  report.atlas_charts = static_cast<int>(boxes.size());
  report.atlas_rotated_charts = packing.rotated_charts;
  report.atlas_utilization = atlas_utilization(chart_uvs, triangles);
  return Status::success();
}

/// The charts side by side, each at its 3D scale (UV area = 3D area, normalised units), and
/// their UVs written per corner of `mesh` in its units; with `atlas`, every chart into
/// [0, 1]^2 instead (`pack_atlas_charts`), written as they are.
template <class TriangleMesh, class HalfedgeUVMap>
Status pack_and_write_charts(
  const TriangleMesh& mesh,
  const std::vector<std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor>>& chart_faces,
  const std::vector<Cut_mesh>& cuts, std::vector<std::vector<Uv>>& chart_uvs, const Normalisation& normalisation,
  HalfedgeUVMap uv_map, const std::optional<Atlas_options>& atlas, Surface_parameterization_report& report)
{
  using halfedge_descriptor = typename boost::graph_traits<TriangleMesh>::halfedge_descriptor;
  const std::size_t components = chart_uvs.size();
  for(std::size_t c = 0; c < components; ++c)
    scale_to_3d_area(cuts[c].disk, chart_uvs[c]);
  std::vector<Uv> offsets(components, Uv{0.0, 0.0});
  double units = 1; // of the written UVs, per normalised unit
  if(atlas)
  {
    if(const Status packed = pack_atlas_charts(cuts, chart_uvs, *atlas, report); !packed.ok())
      return packed;
  }
  else
  {
    std::vector<Chart_box> boxes;
    for(std::size_t c = 0; c < components; ++c)
      boxes.push_back(chart_bounding_box(chart_uvs[c]));
    offsets = shelf_pack(boxes);
    units = normalisation.scale;
  }

  using Uv_point = typename boost::property_traits<HalfedgeUVMap>::value_type;
  for(std::size_t c = 0; c < components; ++c)
    for(std::size_t f = 0; f < chart_faces[c].size(); ++f)
    {
      int corner = 0;
      for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(chart_faces[c][f], mesh), mesh))
      {
        const Uv& p = chart_uvs[c][cuts[c].disk.faces[f][corner++]];
        const Uv_point q(units * (p[0] + offsets[c][0]), units * (p[1] + offsets[c][1]));
        put(uv_map, h, q);
        // The border halfedge into the same vertex, if any, shares this corner's wedge when
        // it is the corner next to the border.
        const halfedge_descriptor out = opposite(next(h, mesh), mesh);
        if(CGAL::is_border(out, mesh))
          put(uv_map, prev(out, mesh), q);
      }
    }
  return Status::success();
}

} // namespace internal
} // namespace ICM

#endif // ICM_PIPELINE_SURFACE_COMPONENT_H
