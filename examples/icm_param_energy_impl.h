// The definitions of icm_param::parameterize_surface and parameterize_disk, included only by
// the files that instantiate them for one energy, or the border conditions, each
// (icm_param_energy_*.cpp, icm_param_border.cpp).

#ifndef ICM_PARAM_ENERGY_IMPL_H
#define ICM_PARAM_ENERGY_IMPL_H

#include "icm_param_energy.h"

#include <ICM/metrics/Circle_packing_metric.h>
#include <ICM/metrics/Intrinsic_delaunay_metric.h>
#include <ICM/metrics/Inversive_distance_metric.h>
#include <ICM/metrics/Vertex_scaling_metric.h>

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

namespace icm_param {

template <class Energy>
ICM::Surface_parameterization_report parameterize_surface(const Mesh& mesh, const std::string& metric, Corner_uv_map uv,
                                                          const ICM::Surface_parameterization_options& options,
                                                          const std::map<Mesh::Vertex_index, double>& cones,
                                                          std::vector<Mesh::Edge_index>& seams,
                                                          const std::vector<Mesh::Edge_index>& user_seams)
{
  auto in = [&](auto metric_tag) {
    using Metric = decltype(metric_tag);
    return ICM::parameterize<Metric, CGAL::Default, Energy>(mesh, uv, options, cones, &seams, user_seams);
  };
  if(metric == ICM::Circle_packing_metric::name)
    return in(ICM::Circle_packing_metric());
  if(metric == ICM::Inversive_distance_metric::name)
    return in(ICM::Inversive_distance_metric());
  if(metric == ICM::Vertex_scaling_metric::name)
    return in(ICM::Vertex_scaling_metric());
  return in(ICM::Intrinsic_delaunay_metric());
}

/// One (metric, border) pair: the parameterizer's vertex UVs, copied to the corners.
template <class Metric, class Border>
ICM::Parameterization_report parameterize_disk_in(Mesh& mesh, Corner_uv_map corner_uv)
{
  ICM::Inverse_curvature_map_parameterizer_3<Mesh, Metric, CGAL::Default, CGAL::Default, Border> parameterizer;
  auto vertex_uv = mesh.add_property_map<Mesh::Vertex_index, Kernel::Point_2>("v:icm_param_uv").first;
  const Mesh::Halfedge_index border = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  // The status is also the report's (CGAL's parameterize() passes a copy of the
  // parameterizer, whose copies share one report).
  CGAL::Surface_mesh_parameterization::parameterize(mesh, parameterizer, border, vertex_uv);
  for(Mesh::Halfedge_index h : halfedges(mesh))
    if(!is_border(h, mesh))
      put(corner_uv, h, get(vertex_uv, target(h, mesh)));
  mesh.remove_property_map(vertex_uv);
  return parameterizer.report();
}

template <class Border>
ICM::Parameterization_report parameterize_disk(Mesh& mesh, const std::string& metric, Corner_uv_map uv)
{
  if(metric == ICM::Circle_packing_metric::name)
    return parameterize_disk_in<ICM::Circle_packing_metric, Border>(mesh, uv);
  if(metric == ICM::Inversive_distance_metric::name)
    return parameterize_disk_in<ICM::Inversive_distance_metric, Border>(mesh, uv);
  if(metric == ICM::Vertex_scaling_metric::name)
    return parameterize_disk_in<ICM::Vertex_scaling_metric, Border>(mesh, uv);
  return parameterize_disk_in<ICM::Intrinsic_delaunay_metric, Border>(mesh, uv);
}

} // namespace icm_param

#endif // ICM_PARAM_ENERGY_IMPL_H
