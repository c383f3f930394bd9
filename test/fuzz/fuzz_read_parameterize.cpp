// libFuzzer harness: untrusted bytes through everything icm_param does with them.
//
// The first byte chooses the format (bits 0-1: OFF, OBJ, PLY, STL) and whether polygons are
// triangulated (bit 2); the rest is the file. The bytes are read as a polygon soup, repaired
// into a triangle mesh, parameterized by ICM::parameterize (meshes up to a few hundred faces,
// so that each run stays short), measured and written as OBJ and SVG to memory. Any crash,
// sanitizer report, leak or time-out is a finding; a refusal is not.
//
// Build and run: test/fuzz/run_fuzz.sh MINUTES (clang's -fsanitize=fuzzer).

#include <ICM/IO/read_triangle_mesh.h>
#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_obj.h>
#include <ICM/IO/write_uv_svg.h>
#include <ICM/measures/Distortion.h>
#include <ICM/parameterize.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

/// Larger meshes are read and repaired but not parameterized: a run must stay well under a
/// second for the fuzzer to explore.
constexpr std::size_t max_parameterized_faces = 600;

void parameterize_and_write(const Mesh& mesh)
{
  Mesh copy = mesh;
  auto uv = copy.add_property_map<Mesh::Halfedge_index, Kernel::Point_2>("h:uv").first;
  const ICM::Surface_parameterization_report report = ICM::parameterize(copy, uv);
  if(report.status != CGAL::Surface_mesh_parameterization::OK)
    return;
  const ICM::IO::Uv_mesh uv_mesh = ICM::IO::make_uv_mesh_from_corners(copy, uv);
  std::ostringstream out;
  ICM::IO::write_uv_obj(out, uv_mesh);
  std::string error;
  ICM::IO::write_uv_svg(out, uv_mesh, error);
  ICM::measure_distortion_corner_uv(copy, uv);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if(size < 1)
    return 0;
  const auto format = static_cast<ICM::IO::Mesh_file_format>(data[0] & 3);
  ICM::IO::Mesh_reading_options options;
  options.triangulate = (data[0] & 4) != 0;
  const std::string_view content(reinterpret_cast<const char*>(data + 1), size - 1);

  ICM::IO::Polygon_soup soup;
  std::string error;
  if(!ICM::IO::read_polygon_soup(content, format, soup, error))
    return 0;
  Mesh mesh;
  ICM::IO::Mesh_reading_report report;
  if(!ICM::IO::polygon_soup_to_triangle_mesh(soup, mesh, report, options))
    return 0;
  if(num_faces(mesh) <= max_parameterized_faces)
    parameterize_and_write(mesh);
  return 0;
}
