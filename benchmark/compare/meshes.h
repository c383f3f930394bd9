// compare's meshes (meshes.cpp): reading and preparing one, its topology, opening a closed one.

#ifndef ICM_BENCHMARK_COMPARE_MESHES_H
#define ICM_BENCHMARK_COMPARE_MESHES_H

#include "mesh_types.h"
#include "options.h"

#include <cstddef>
#include <string>

namespace compare {

// The file name without its folder and extension.
std::string mesh_name(const std::string& path);

// Opens a closed mesh by removing the faces around its first vertex (--open, and the mesh of
// icm_free_boundary_opened): a nearly closed disk, like a scan with one small hole.
void open_at_first_vertex(Mesh& mesh);

// Reads and prepares a mesh (triangulated, --subdivide, --open); on failure returns false
// with a reason.
bool load_mesh(const std::string& path, const Options& opt, Mesh& mesh, std::string& error);

// Writes the mesh to `path` (.obj, .off or .ply by its extension; coordinates with 17
// significant digits, so that a reader gets the same points); on failure returns false with
// a reason.
bool write_mesh(const std::string& path, const Mesh& mesh, std::string& error);

// Components, boundary loops and Euler characteristic chi = V - E + F = 2C - 2G - B.
struct Topology
{
  std::size_t components = 0;
  long loops = 0;
  long chi = 0;
  long two_g() const { return 2 * static_cast<long>(components) - loops - chi; }
  bool closed() const { return loops == 0; }
  bool disk() const { return components == 1 && loops == 1 && two_g() == 0; }
  // The genus when the mesh is connected, else "?".
  std::string genus() const { return components == 1 && two_g() % 2 == 0 ? std::to_string(two_g() / 2) : "?"; }
  std::string description() const
  {
    std::string s = components == 1 ? std::string() : std::to_string(components) + " components, ";
    return s + "genus " + genus() + ", " + std::to_string(loops) + " loops";
  }
};

Topology topology_of(Mesh& mesh);

// "" when the mesh is a topological disk (one component, one boundary loop, genus 0),
// else the reason for skipping it.
std::string disk_check(Mesh& mesh);

} // namespace compare

#endif // ICM_BENCHMARK_COMPARE_MESHES_H
