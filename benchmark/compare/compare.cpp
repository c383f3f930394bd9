// compare: runs ICM's parameterizers and CGAL's on the same meshes and prints the paper's
// Table I (conformality, angle distortion, L2 shear, L2 stretch, log area distortion) plus
// wall time, peak memory, flipped faces and quasi-conformal ratios, as Markdown or JSON lines.
//
//   compare [--json] [--runs N] [--time-limit SECONDS] [--methods a,b,c] [--subdivide K]
//           [--open] [--svg-panels FILE] [--write-mesh FILE] [--quiet] MESH...
//
// A topological disk goes through CGAL's parameterize() with every method of the registry
// (ICM's rows, in each metric and with each energy, show the report's optimum time and the
// energy optimizer's steps and values).
// Any other connected mesh (closed, genus > 0, several boundary loops) is parameterized by
// ICM's one call, ICM::parameterize() (row `icm`: cones, cut, optimum, layout); CGAL's
// methods then run on a CGAL::Seam_mesh cut along ICM's seams (the same cut), and a closed
// genus-0 mesh also gets `icm_free_boundary_opened`, the free-boundary parameterizer on the
// mesh opened at its first vertex.
//
// Every run of every method happens in a forked child process on its own copy of the mesh:
// a method that hangs is killed at the time limit and shown as `timeout`, a method that
// crashes is shown as `crashed (signal N)`, and the child's peak resident memory is the
// method's (plus the process image inherited at fork, which holds the input mesh).
// See doc/benchmarks.md.
//
// The files of this folder: methods.* (the registry) and seam_methods.cpp, options.* (the
// command line), jobs.* and icm_jobs.cpp (what a child does), child_result.* (what it sends
// back), run.* (the child processes, through tools/child_process.h), meshes.*, rows.h with
// disk_rows.cpp and surface_rows.cpp (the rows of a mesh), output.* and svg_panels.cpp.

#include "meshes.h"
#include "methods.h"
#include "options.h"
#include "output.h"
#include "rows.h"

#include <signal.h>

#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace compare;

// The names --methods takes: the registry's, then the rows of surfaces that are not disks.
std::vector<std::string> known_methods(const std::vector<Method>& registry)
{
  std::vector<std::string> names;
  for(const Method& m : registry)
    names.push_back(m.name);
  names.insert(names.end(), surface_methods.begin(), surface_methods.end());
  return names;
}

// The names asked for, once each, in the order given (default: the whole registry for a
// disk; see surface_names() for the other meshes).
std::vector<std::string> asked_names(const Options& opt)
{
  std::vector<std::string> asked;
  for(const std::string& name : opt.methods)
    if(std::find(asked.begin(), asked.end(), name) == asked.end())
      asked.push_back(name);
  return asked;
}

// The rows of the mesh at `path`; false when it cannot be read.
bool run_mesh(const std::string& path, const Options& opt, const std::vector<std::string>& asked,
              const std::vector<Method>& registry, const std::vector<Seam_method>& seam_registry)
{
  Mesh mesh;
  std::string error;
  if(!load_mesh(path, opt, mesh, error))
  {
    std::cerr << "compare: " << path << ": " << error << "\n";
    return false;
  }
  if(!opt.write_mesh.empty() && !write_mesh(opt.write_mesh, mesh, error))
  {
    std::cerr << "compare: --write-mesh " << opt.write_mesh << ": " << error << "\n";
    return false;
  }
  Row base;
  base.mesh = mesh_name(path);
  base.vertices = num_vertices(mesh);
  base.faces = num_faces(mesh);
  const Topology topology = topology_of(mesh);
  if(topology.disk())
    run_disk(mesh, base, opt, asked, registry);
  else
    run_surface(mesh, topology, base, opt, asked, registry, seam_registry);
  return true;
}

} // namespace

int main(int argc, char** argv)
{
  ::signal(SIGPIPE, SIG_IGN);
  const std::vector<Method> registry = make_registry();
  const Options opt = parse_options(argc, argv, known_methods(registry));
  const std::vector<Seam_method> seam_registry = make_seam_registry();
  const std::vector<std::string> asked = asked_names(opt);

  if(!opt.json_file.empty() && !open_json_file(opt.json_file))
  {
    std::cerr << "compare: cannot write " << opt.json_file << "\n";
    return 2;
  }
  if(!opt.json)
    print_markdown_preamble(opt);

  int exit_status = 0;
  std::string first_mesh_path;
  for(const std::string& path : opt.meshes)
  {
    if(!run_mesh(path, opt, asked, registry, seam_registry))
      exit_status = 1;
    else if(first_mesh_path.empty())
      first_mesh_path = path;
  }

  if(!opt.svg_panels.empty())
  {
    // Drawn after all timed runs, so that the parent's memory seen by later children stays small.
    if(first_mesh_path.empty())
    {
      std::cerr << "compare: --svg-panels: no readable mesh\n";
      exit_status = 1;
    }
    else if(!write_panels(first_mesh_path, opt, registry))
    {
      exit_status = 1;
    }
  }
  return exit_status;
}
