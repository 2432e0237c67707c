// Texture coordinates and vertex colours of OBJ files (see obj_attributes.h).
#include "consistent_maps/obj_attributes.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "consistent_maps/errors.h"
#include "mesh/text_mesh_readers.h"

namespace cmaps {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace

ObjAttributes read_obj_attributes(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw IoError("cannot read '" + path + "': no such file");
  if (std::filesystem::is_directory(status)) throw IoError("cannot read '" + path + "': is a directory");
  if (lower_extension(path) != ".obj")
    throw IoError("cannot read texture coordinates or colours from '" + path + "': only .obj files carry them here");
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw IoError("cannot read '" + path + "': " + std::strerror(errno));
  return read_obj_attributes(path, text);
}

void write_obj_with_attributes(const std::string& path, const TriangleMesh& mesh, const ObjAttributes& attributes) {
  if (lower_extension(path) != ".obj") throw IoError("cannot write '" + path + "': the output must end in .obj");
  if (!attributes.colors.empty() && attributes.colors.size() != mesh.vertices.size())
    throw InvalidInput(std::to_string(attributes.colors.size()) + " colours for " +
                       std::to_string(mesh.vertices.size()) + " vertices");
  const bool uvs = !attributes.triangle_uvs.empty();
  if (uvs && attributes.triangle_uvs.size() != mesh.triangles.size())
    throw InvalidInput(std::to_string(attributes.triangle_uvs.size()) + " triangles of texture coordinates for " +
                       std::to_string(mesh.triangles.size()) + " triangles");
  for (const auto& corners : attributes.triangle_uvs)
    for (int k : corners)
      if (k < 0 || k >= int(attributes.uvs.size()))
        throw InvalidInput("texture coordinate index " + std::to_string(k) + " out of range (" +
                           std::to_string(attributes.uvs.size()) + ")");

  std::ofstream out(path, std::ios::binary);
  if (!out) throw IoError("cannot write '" + path + "': cannot open file for writing");
  out << "# written by consistent_maps\n";
  char line[256];
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& p = mesh.vertices[i];
    int n = std::snprintf(line, sizeof line, "v %.17g %.17g %.17g", p.x(), p.y(), p.z());
    if (!attributes.colors.empty()) {
      const auto& c = attributes.colors[i];
      n += std::snprintf(line + n, sizeof line - n, " %.9g %.9g %.9g", c[0], c[1], c[2]);
    }
    out.write(line, n);
    out << '\n';
  }
  for (const auto& uv : attributes.uvs) {
    const int n = std::snprintf(line, sizeof line, "vt %.17g %.17g\n", uv[0], uv[1]);
    out.write(line, n);
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& v = mesh.triangles[t];
    if (uvs) {
      const auto& c = attributes.triangle_uvs[t];
      out << "f " << v[0] + 1 << '/' << c[0] + 1 << ' ' << v[1] + 1 << '/' << c[1] + 1 << ' ' << v[2] + 1 << '/'
          << c[2] + 1 << '\n';
    } else {
      out << "f " << v[0] + 1 << ' ' << v[1] + 1 << ' ' << v[2] + 1 << '\n';
    }
  }
  out.close();
  if (!out) throw IoError("cannot write '" + path + "': write failed");
}

}  // namespace cmaps
