// Praun & Hoppe's octahedral grid and geometry images: reading, writing, meshing.
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

#include "bindings.h"
#include "consistent_maps/geometry_image.h"
#include "consistent_maps/octahedral_grid.h"
#include "conversions.h"

namespace cmaps::python {

namespace py = pybind11;

namespace {

py::array_t<std::int32_t> pixel_array(const cmaps::OctahedralGrid& grid) {
  const py::ssize_t side = grid.n + 1;
  py::array_t<std::int32_t> pixels({side, side});
  std::copy(grid.pixel_vertex.begin(), grid.pixel_vertex.end(), pixels.mutable_data());
  return pixels;
}

py::tuple octahedral_grid(int n) {
  require_grid_resolution(n, "n");
  cmaps::OctahedralGrid grid;
  {
    py::gil_scoped_release release;
    grid = cmaps::octahedral_grid(n);
  }
  return py::make_tuple(to_numpy(grid.sphere), to_numpy(grid.triangles), pixel_array(grid));
}

cmaps::GeometryImage to_image(const py::handle& data) {
  py::array array = as_array(data, "image");
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    raise(PyExc_TypeError, "image must hold real numbers, got dtype " + std::string(py::str(array.dtype())));
  if (array.ndim() != 3 || array.shape(0) != array.shape(1) || array.shape(2) != 3 || array.shape(0) < 3 ||
      (array.shape(0) - 1) % 2 != 0)
    raise(PyExc_ValueError, "image must have shape (n+1, n+1, 3) with n even and at least 2, got " + shape_of(array));
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  cmaps::GeometryImage image;
  image.n = int(array.shape(0) - 1);
  image.pixels.resize(std::size_t(values.size() / 3));
  const double* v = values.data();
  for (cmaps::Vec3& p : image.pixels) p = {v[0], v[1], v[2]}, v += 3;
  return image;
}

py::array_t<double> image_array(const cmaps::GeometryImage& image) {
  const py::ssize_t side = image.n + 1;
  py::array_t<double> array({side, side, py::ssize_t(3)});
  double* out = array.mutable_data();
  for (const cmaps::Vec3& p : image.pixels) out[0] = p.x(), out[1] = p.y(), out[2] = p.z(), out += 3;
  return array;
}

// ".npy" or ".png" (any case): the geometry image format of a path.
bool is_png(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".npy" && ext != ".png")
    raise(PyExc_ValueError, "geometry image path '" + path.string() + "' must end in .npy or .png");
  return ext == ".png";
}

void write_geometry_image(const std::filesystem::path& path, const py::handle& data) {
  const bool png = is_png(path);
  const cmaps::GeometryImage image = to_image(data);
  py::gil_scoped_release release;
  if (png) cmaps::write_geometry_image_png(path.string(), image);
  else cmaps::write_geometry_image_npy(path.string(), image);
}

py::array_t<double> read_geometry_image(const std::filesystem::path& path) {
  const bool png = is_png(path);
  if (!std::filesystem::exists(path))
    raise(PyExc_FileNotFoundError, "cannot read '" + path.string() + "': no such file");
  cmaps::GeometryImage image;
  {
    py::gil_scoped_release release;
    image = png ? cmaps::read_geometry_image_png(path.string()) : cmaps::read_geometry_image_npy(path.string());
  }
  return image_array(image);
}

py::tuple geometry_image_mesh(const py::handle& data) {
  const cmaps::GeometryImage image = to_image(data);
  cmaps::TriangleMesh mesh;
  {
    py::gil_scoped_release release;
    mesh = cmaps::geometry_image_mesh(image);
  }
  return py::make_tuple(to_numpy(mesh.vertices), to_numpy(mesh.triangles));
}

}  // namespace

void bind_geometry_image(py::module_& m) {
  m.def("octahedral_grid", &octahedral_grid, py::arg("n"),
        "Praun & Hoppe's flat-octahedron sphere grid of even resolution n: (sphere (n^2 + 2, 3) unit vectors,\n"
        "triangles (2 n^2, 3) int32 counter-clockwise from outside, pixel_vertex (n+1, n+1) int32: the vertex\n"
        "of each geometry-image pixel). values[pixel_vertex] is the geometry image of per-vertex values.");
  m.def("write_geometry_image", &write_geometry_image, py::arg("path"), py::arg("image"),
        "Writes an (n+1, n+1, 3) geometry image as float64 .npy or as 16-bit RGB .png quantized to the\n"
        "values' bounding box (kept in the file so it reads back to geometry). Raises MeshIOError.");
  m.def("read_geometry_image", &read_geometry_image, py::arg("path"),
        "Reads a geometry image (.npy float64/float32, or .png as written above) as (n+1, n+1, 3) float64.");
  m.def("geometry_image_mesh", &geometry_image_mesh, py::arg("image"),
        "The mesh of an (n+1, n+1, 3) geometry image: (vertices (n^2 + 2, 3), triangles (2 n^2, 3) int32), the\n"
        "octahedral grid's connectivity.");
}

}  // namespace cmaps::python
