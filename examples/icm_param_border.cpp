// icm_param --boundary circle|square|circle-domain: the parameterizer with the curvature entropy
// and each prescribed border condition, in a file of its own so that it compiles in parallel
// with the energies (icm_param_energy.h).

#include "icm_param_energy_impl.h"

#include <ICM/border/Border_conditions.h>
#include <ICM/border/Border_shape.h>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>

#include <iterator>

namespace icm_param {

namespace {

/// Why `mesh` is not a topological disk (one connected component, one boundary loop, genus
/// 0), or with `several_loops` not a genus-0 surface with borders, in words, or empty.
std::string why_not_a_disk(Mesh& mesh, bool several_loops)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  auto component = mesh.add_property_map<Mesh::Face_index, std::size_t>("f:icm_param_component").first;
  const std::size_t components = PMP::connected_components(mesh, component);
  mesh.remove_property_map(component);
  if(components > 1)
    return "it has " + std::to_string(components) + " connected components";
  std::vector<Mesh::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  const long loops = static_cast<long>(cycles.size());
  const long euler =
    static_cast<long>(num_vertices(mesh)) - static_cast<long>(num_edges(mesh)) + static_cast<long>(num_faces(mesh));
  const long genus = (2 - loops - euler) / 2;
  if(genus == 0 && (loops == 1 || (several_loops && loops > 1)))
    return {};
  return loops == 0 ? "it is closed, genus " + std::to_string(genus)
                    : "it has genus " + std::to_string(genus) + " and " + std::to_string(loops) + " boundary loops";
}

} // namespace

std::string why_the_border_is_refused(const std::string& asked, const std::string& boundary, Mesh& mesh)
{
  const bool circle_domain = boundary == "circle-domain";
  const std::string not_a_disk = why_not_a_disk(mesh, circle_domain);
  if(not_a_disk.empty())
    return {};
  return asked +
         (circle_domain ? " needs one component of genus 0 with at least one border loop, and "
                        : " needs a disk (one component, one boundary loop, genus 0), and ") +
         not_a_disk;
}

template ICM::Parameterization_report
parameterize_disk<ICM::Circular_border<Mesh>>(Mesh& mesh, const std::string& metric, Corner_uv_map uv);
template ICM::Parameterization_report parameterize_disk<ICM::Square_border<Mesh>>(Mesh& mesh, const std::string& metric,
                                                                                  Corner_uv_map uv);
template ICM::Parameterization_report parameterize_disk<ICM::Circle_domain>(Mesh& mesh, const std::string& metric,
                                                                            Corner_uv_map uv);
} // namespace icm_param
