// The numpy arrays of the module `icm` (icm_module.cpp), in and out: every array that comes
// in is checked here (shape, dtype, finite coordinates, indices in range, not empty) and
// refused with `icm.Error`, never passed on unchecked; V and F become a mesh through the same
// soup-to-mesh checks and repairs as a file read by icm_param (IO/read_triangle_mesh.h).

#ifndef ICM_MODULE_ARRAYS_H
#define ICM_MODULE_ARRAYS_H

#include "icm_param_energy.h"

#include <ICM/IO/read_triangle_mesh.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h> // in every file of the module: the same casters of std::vector, std::pair

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace icm_module {

namespace py = pybind11;

using Kernel = icm_param::Kernel;
using Mesh = icm_param::Mesh;
using Corner_uv_map = icm_param::Corner_uv_map;

/// A refusal or a failure, raised in Python as `icm.Error` with the reason, and the ICM
/// error code (`CGAL::Surface_mesh_parameterization::Error_code`) when there is one.
struct Icm_error : std::runtime_error
{
  std::optional<int> code;
  explicit Icm_error(const std::string& why, std::optional<int> code_ = std::nullopt)
    : std::runtime_error(why), code(code_)
  {}
};

using Real_rows = py::array_t<double, py::array::c_style>;
using Index_rows = py::array_t<std::int64_t, py::array::c_style>;

/// `object` as a C-contiguous (rows, columns) array of doubles, or `Icm_error` naming `what`.
Real_rows real_rows(const py::object& object, py::ssize_t columns, const char* what);

/// How an array of indices is named in its refusals.
struct Index_array
{
  const char* what;  ///< "F"
  const char* shape; ///< "(m, 3)": the shape asked for
  const char* empty; ///< what an empty array lacks: "no faces"
  const char* into;  ///< the array it indexes: "V"
  py::ssize_t columns;
};

inline constexpr Index_array faces_of_V{"F", "(m, 3)", "no faces", "V", 3};
inline constexpr Index_array faces_of_uv{"fuv", "(m, 3)", "no faces", "uv", 3};
inline constexpr Index_array edges_of_V{"seams", "(s, 2)", "no edges; seams=None cuts where the topology needs it", "V",
                                        2};

/// `object` as a C-contiguous (rows, `a.columns`) array of indices below `bound`, or
/// `Icm_error` naming the row at fault.
Index_rows index_rows(const py::object& object, std::size_t bound, const Index_array& a);

/// The UVs of a Uv_mesh-like (uv, fuv) pair checked against F: (rows, 2) finite reals and
/// (faces, 3) indices into them.
std::pair<Real_rows, Index_rows> uv_rows(const py::object& uv, const py::object& fuv, py::ssize_t faces);

/// V and F checked and made a triangle mesh by ICM's soup checks (the repairs in `read`),
/// or `Icm_error` with the reason.
Mesh mesh_of(const py::object& V, const py::object& F, ICM::IO::Mesh_reading_report& read);

/// A (rows, columns) numpy array of `T` filled from `rows`.
template <class T, class Rows>
py::array_t<T> array_of(const Rows& rows, py::ssize_t columns)
{
  py::array_t<T> out({static_cast<py::ssize_t>(rows.size()), columns});
  auto view = out.template mutable_unchecked<2>();
  for(std::size_t i = 0; i < rows.size(); ++i)
    for(py::ssize_t j = 0; j < columns; ++j)
      view(static_cast<py::ssize_t>(i), j) = static_cast<T>(rows[i][j]);
  return out;
}

/// The lines as a Python list of str.
py::list list_of(const std::vector<std::string>& lines);

} // namespace icm_module

#endif // ICM_MODULE_ARRAYS_H
