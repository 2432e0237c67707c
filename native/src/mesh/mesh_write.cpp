// Writing meshes. The writers are small enough to own, which guarantees full
// double precision (OpenMesh's exporters go through single-precision points)
// and keeps every triangle, manifold or not.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "binary PLY and STL writers assume a little-endian machine"
#endif

namespace cmaps {
namespace {

// %.17g round-trips every double exactly.
void put_coordinates(std::ostream& out, const Vec3& p) {
  char line[96];
  const int n = std::snprintf(line, sizeof line, "%.17g %.17g %.17g", p.x(), p.y(), p.z());
  out.write(line, n);
}

template <class T>
void put_binary(std::ostream& out, T value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof value);
}

void write_obj(std::ostream& out, const TriangleMesh& mesh) {
  out << "# written by consistent_maps\n";
  for (const Vec3& p : mesh.vertices) {
    out << "v ";
    put_coordinates(out, p);
    out << '\n';
  }
  for (const Triangle& t : mesh.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

void write_off(std::ostream& out, const TriangleMesh& mesh) {
  out << "OFF\n" << mesh.vertices.size() << ' ' << mesh.triangles.size() << " 0\n";
  for (const Vec3& p : mesh.vertices) {
    put_coordinates(out, p);
    out << '\n';
  }
  for (const Triangle& t : mesh.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

void write_ply(std::ostream& out, const TriangleMesh& mesh) {
  out << "ply\nformat binary_little_endian 1.0\ncomment written by consistent_maps\n"
      << "element vertex " << mesh.vertices.size() << '\n'
      << "property double x\nproperty double y\nproperty double z\n"
      << "element face " << mesh.triangles.size() << '\n'
      << "property list uchar int vertex_indices\nend_header\n";
  for (const Vec3& p : mesh.vertices) {
    put_binary(out, p.x());
    put_binary(out, p.y());
    put_binary(out, p.z());
  }
  for (const Triangle& t : mesh.triangles) {
    put_binary(out, std::uint8_t(3));
    for (int v : t) put_binary(out, std::int32_t(v));
  }
}

// Binary STL stores single-precision corners per facet; it is offered for
// interchange only.
void write_stl(std::ostream& out, const TriangleMesh& mesh) {
  char header[80] = "binary STL written by consistent_maps";
  out.write(header, sizeof header);
  put_binary(out, std::uint32_t(mesh.triangles.size()));
  const int n = int(mesh.vertices.size());
  for (const Triangle& t : mesh.triangles) {
    const auto corner = [&](int i) { return 0 <= t[i] && t[i] < n ? mesh.vertices[t[i]] : Vec3::Zero().eval(); };
    const Vec3 a = corner(0), b = corner(1), c = corner(2);
    const Vec3 normal = (b - a).cross(c - a).normalized();
    for (const Vec3& p : {normal, a, b, c})
      for (int k = 0; k < 3; ++k) put_binary(out, float(p[k]));
    put_binary(out, std::uint16_t(0));
  }
}

}  // namespace

void write_mesh(const std::string& path, const TriangleMesh& mesh) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  std::function<void(std::ostream&, const TriangleMesh&)> writer;
  if (ext == ".obj") writer = write_obj;
  else if (ext == ".off") writer = write_off;
  else if (ext == ".ply") writer = write_ply;
  else if (ext == ".stl") writer = write_stl;
  else throw IoError("cannot write '" + path + "': unknown extension '" + ext + "' (supported: .obj .off .ply .stl)");

  std::ofstream out(path, std::ios::binary);
  if (!out) throw IoError("cannot write '" + path + "': cannot open file for writing");
  writer(out, mesh);
  out.close();
  if (!out) throw IoError("cannot write '" + path + "': write failed");
}

}  // namespace cmaps
