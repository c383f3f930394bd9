// --svg-panels (output.h): the UV layouts of icm_free_boundary, lscm and arap side by side,
// recomputed in this process after the timed runs.

#include "meshes.h"
#include "output.h"

#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_svg.h>
#include <ICM/parameterize.h>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <iostream>
#include <utility>

namespace compare {

namespace {

// The layouts of panel_methods on `mesh` that worked; a failing method is left out, said on
// stderr.
std::vector<std::pair<std::string, ICM::IO::Uv_mesh>> panels_of(const Mesh& mesh, const std::vector<Method>& registry)
{
  std::vector<std::pair<std::string, ICM::IO::Uv_mesh>> panels;
  for(const std::string& name : panel_methods)
  {
    const Method* method = find_method(registry, name);
    if(method == nullptr)
      continue;
    Mesh copy = mesh;
    UV_map uvmap = copy.add_property_map<vertex_descriptor, Point_2>("v:compare_uv", Point_2(0, 0)).first;
    const halfedge_descriptor bhd = CGAL::Polygon_mesh_processing::longest_border(copy).first;
    const Run_result r = method->run(copy, bhd, uvmap);
    if(!has_usable_uvs(r.code))
    {
      std::cerr << "compare: --svg-panels: " << name << " failed (" << ICM::error_message(r.code)
                << (r.message.empty() ? "" : "; " + r.message) << "), panel left out\n";
      continue;
    }
    panels.emplace_back(name, ICM::IO::make_uv_mesh(copy, uvmap));
  }
  return panels;
}

} // namespace

bool write_panels(const std::string& mesh_path, const Options& opt, const std::vector<Method>& registry)
{
  Mesh mesh;
  std::string error;
  if(!load_mesh(mesh_path, opt, mesh, error))
  {
    std::cerr << "compare: --svg-panels: " << mesh_path << ": " << error << "\n";
    return false;
  }
  const std::string skip = disk_check(mesh);
  if(!skip.empty())
  {
    std::cerr << "compare: --svg-panels: " << mesh_path << ": " << skip << "\n";
    return false;
  }
  const std::vector<std::pair<std::string, ICM::IO::Uv_mesh>> panels = panels_of(mesh, registry);
  if(panels.empty())
  {
    std::cerr << "compare: --svg-panels: no method produced a layout\n";
    return false;
  }
  if(!ICM::IO::write_uv_svg_panels(opt.svg_panels, panels, error))
  {
    std::cerr << "compare: --svg-panels: " << opt.svg_panels << ": " << error << "\n";
    return false;
  }
  if(!opt.quiet)
    std::cerr << "compare: wrote " << opt.svg_panels << "\n";
  return true;
}

} // namespace compare
