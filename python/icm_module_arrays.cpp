// The numpy arrays of the module `icm`, in and out (icm_module_arrays.h).

#include "icm_module_arrays.h"

#include <cmath>

namespace icm_module {

namespace {

std::string shape_of(const py::array& a)
{
  return py::str(py::tuple(py::cast(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim())))).cast<std::string>();
}

} // namespace

Real_rows real_rows(const py::object& object, py::ssize_t columns, const char* what)
{
  const py::array any = py::array::ensure(object);
  if(!any)
    throw Icm_error(std::string(what) + " must be an array of numbers (numpy.ndarray)");
  const char kind = any.dtype().kind();
  if(kind != 'f' && kind != 'i' && kind != 'u')
    throw Icm_error(std::string(what) + " must hold real numbers, not dtype " +
                    py::str(any.dtype()).cast<std::string>());
  if(any.ndim() != 2 || any.shape(1) != columns)
    throw Icm_error(std::string(what) + " must have shape (n, " + std::to_string(columns) + "), not " + shape_of(any));
  if(any.shape(0) == 0)
    throw Icm_error(std::string(what) + " is empty");
  auto rows = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(any);
  if(!rows)
    throw Icm_error(std::string(what) + " cannot be converted to float64");
  const double* data = rows.data();
  for(py::ssize_t i = 0; i < rows.size(); ++i)
    if(!std::isfinite(data[i]))
      throw Icm_error(std::string(what) + " has a non-finite coordinate (NaN or infinity) in row " +
                      std::to_string(i / columns));
  return rows;
}

Index_rows index_rows(const py::object& object, std::size_t bound, const Index_array& a)
{
  const std::string what = a.what;
  const py::array any = py::array::ensure(object);
  if(!any)
    throw Icm_error(what + " must be an array of integers (numpy.ndarray)");
  const char kind = any.dtype().kind();
  if(kind != 'i' && kind != 'u')
    throw Icm_error(what + " must hold integers (indices), not dtype " + py::str(any.dtype()).cast<std::string>());
  if(any.ndim() != 2 || any.shape(1) != a.columns)
    throw Icm_error(what + " must have shape " + a.shape + ", not " + shape_of(any));
  if(any.shape(0) == 0)
    throw Icm_error(what + " is empty (" + a.empty + ")");
  auto rows = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(any);
  if(!rows)
    throw Icm_error(what + " cannot be converted to int64");
  const std::int64_t* data = rows.data();
  for(py::ssize_t i = 0; i < rows.size(); ++i)
    if(data[i] < 0 || static_cast<std::uint64_t>(data[i]) >= bound)
      throw Icm_error(what + " row " + std::to_string(i / a.columns) + " has index " + std::to_string(data[i]) +
                      " out of range: " + a.into + " has " + std::to_string(bound) + " rows");
  return rows;
}

std::pair<Real_rows, Index_rows> uv_rows(const py::object& uv, const py::object& fuv, py::ssize_t faces)
{
  auto uvs = real_rows(uv, 2, "uv");
  auto corners = index_rows(fuv, static_cast<std::size_t>(uvs.shape(0)), faces_of_uv);
  if(corners.shape(0) != faces)
    throw Icm_error("fuv has " + std::to_string(corners.shape(0)) + " rows and F " + std::to_string(faces) +
                    ": one row per face in both");
  return {uvs, corners};
}

Mesh mesh_of(const py::object& V, const py::object& F, ICM::IO::Mesh_reading_report& read)
{
  const auto points = real_rows(V, 3, "V");
  const auto faces = index_rows(F, static_cast<std::size_t>(points.shape(0)), faces_of_V);
  ICM::IO::Polygon_soup soup;
  soup.points.reserve(points.shape(0));
  for(py::ssize_t i = 0; i < points.shape(0); ++i)
    soup.points.emplace_back(points.at(i, 0), points.at(i, 1), points.at(i, 2));
  soup.polygons.reserve(faces.shape(0));
  for(py::ssize_t f = 0; f < faces.shape(0); ++f)
    soup.polygons.push_back({static_cast<std::size_t>(faces.at(f, 0)), static_cast<std::size_t>(faces.at(f, 1)),
                             static_cast<std::size_t>(faces.at(f, 2))});
  Mesh mesh;
  if(!ICM::IO::polygon_soup_to_triangle_mesh(soup, mesh, read))
    throw Icm_error("V, F: " + read.message);
  return mesh;
}

py::list list_of(const std::vector<std::string>& lines)
{
  py::list out;
  for(const std::string& line : lines)
    out.append(line);
  return out;
}

} // namespace icm_module
