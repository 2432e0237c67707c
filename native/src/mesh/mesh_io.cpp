// Reading meshes: text OBJ and OFF by the library's own readers (see
// text_mesh_readers.h), PLY, STL and binary OFF through OpenMesh's readers.
// OpenMesh's own importers build a halfedge mesh and drop faces it cannot
// insert (complex edges), which would hide exactly the defects check_mesh must
// report, so a recording importer keeps every face as the file lists it.
// OpenMesh hands over single-precision coordinates.
#include "consistent_maps/mesh_io.h"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

#include "consistent_maps/errors.h"
#include "mesh/text_mesh_readers.h"

namespace cmaps {
namespace {

namespace OM = OpenMesh;
namespace IO = OpenMesh::IO;

class RecordingImporter final : public IO::BaseImporter {
 public:
  explicit RecordingImporter(TriangleMesh& mesh) : mesh_(mesh) {}

  OM::VertexHandle add_vertex(const OM::Vec3f& p) override { return push({p[0], p[1], p[2]}); }
  OM::VertexHandle add_vertex(const OM::Vec3d& p) override { return push({p[0], p[1], p[2]}); }
  OM::VertexHandle add_vertex() override { return push(Vec3::Zero()); }
  void set_point(OM::VertexHandle v, const OM::Vec3f& p) override {
    if (v.is_valid() && size_t(v.idx()) < mesh_.vertices.size()) mesh_.vertices[v.idx()] = {p[0], p[1], p[2]};
  }

  // Fan triangulation; indices are kept even when out of range, for check_mesh to report.
  OM::FaceHandle add_face(const VHandles& face) override {
    if (face.size() < 3) return OM::FaceHandle();
    const int first = int(mesh_.triangles.size());
    for (size_t i = 1; i + 1 < face.size(); ++i)
      mesh_.triangles.push_back({face[0].idx(), face[i].idx(), face[i + 1].idx()});
    return OM::FaceHandle(first);
  }

  size_t n_vertices() const override { return mesh_.vertices.size(); }
  size_t n_faces() const override { return mesh_.triangles.size(); }
  size_t n_edges() const override { return 0; }

  // Everything below is attribute data or halfedge-level input the library does not use.
  OM::HalfedgeHandle add_edge(OM::VertexHandle, OM::VertexHandle) override { return OM::HalfedgeHandle(); }
  OM::FaceHandle add_face(OM::HalfedgeHandle) override { return OM::FaceHandle(); }
  void add_face_texcoords(OM::FaceHandle, OM::VertexHandle, const std::vector<OM::Vec2f>&) override {}
  void add_face_texcoords(OM::FaceHandle, OM::VertexHandle, const std::vector<OM::Vec3f>&) override {}
  void set_face_texindex(OM::FaceHandle, int) override {}
  void set_halfedge(OM::VertexHandle, OM::HalfedgeHandle) override {}
  void set_normal(OM::VertexHandle, const OM::Vec3f&) override {}
  void set_normal(OM::VertexHandle, const OM::Vec3d&) override {}
  void set_color(OM::VertexHandle, const OM::Vec3uc&) override {}
  void set_color(OM::VertexHandle, const OM::Vec4uc&) override {}
  void set_color(OM::VertexHandle, const OM::Vec3f&) override {}
  void set_color(OM::VertexHandle, const OM::Vec4f&) override {}
  void set_texcoord(OM::VertexHandle, const OM::Vec2f&) override {}
  void set_status(OM::VertexHandle, const OM::Attributes::StatusInfo&) override {}
  void set_next(OM::HalfedgeHandle, OM::HalfedgeHandle) override {}
  void set_face(OM::HalfedgeHandle, OM::FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(OM::HalfedgeHandle, const OM::Vec2f&) override {}
  void set_texcoord(OM::VertexHandle, const OM::Vec3f&) override {}
  void set_texcoord(OM::HalfedgeHandle, const OM::Vec3f&) override {}
  void set_status(OM::HalfedgeHandle, const OM::Attributes::StatusInfo&) override {}
  void set_color(OM::EdgeHandle, const OM::Vec3uc&) override {}
  void set_color(OM::EdgeHandle, const OM::Vec4uc&) override {}
  void set_color(OM::EdgeHandle, const OM::Vec3f&) override {}
  void set_color(OM::EdgeHandle, const OM::Vec4f&) override {}
  void set_status(OM::EdgeHandle, const OM::Attributes::StatusInfo&) override {}
  void set_normal(OM::FaceHandle, const OM::Vec3f&) override {}
  void set_normal(OM::FaceHandle, const OM::Vec3d&) override {}
  void set_color(OM::FaceHandle, const OM::Vec3uc&) override {}
  void set_color(OM::FaceHandle, const OM::Vec4uc&) override {}
  void set_color(OM::FaceHandle, const OM::Vec3f&) override {}
  void set_color(OM::FaceHandle, const OM::Vec4f&) override {}
  void set_status(OM::FaceHandle, const OM::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

 private:
  OM::VertexHandle push(const Vec3& p) {
    mesh_.vertices.push_back(p);
    return OM::VertexHandle(int(mesh_.vertices.size()) - 1);
  }

  TriangleMesh& mesh_;
};

// OpenMesh reports problems on its own streams; the library reports them as
// exceptions, so the chatter would only duplicate (or contradict) them.
void silence_openmesh() {
  static const bool silenced = [] {
    ::omlog().disable();
    ::omout().disable();
    ::omerr().disable();
    return true;
  }();
  (void)silenced;
}

}  // namespace

TriangleMesh read_mesh(const std::string& path) {
  silence_openmesh();
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw IoError("cannot read '" + path + "': no such file");
  if (std::filesystem::is_directory(status)) throw IoError("cannot read '" + path + "': is a directory");
  // IOManager::can_read cannot answer this: the OFF and PLY readers also sniff the file.
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".stl")
    throw IoError("cannot read '" + path + "': unknown extension '" + ext +
                  "' (supported: .obj .off .ply .stl)");
  if (std::filesystem::file_size(path, ec) == 0 && !ec) throw IoError("cannot read '" + path + "': file is empty");

  if (ext == ".obj" || ext == ".off") {
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in && !in.eof()) throw IoError("cannot read '" + path + "': " + std::strerror(errno));
    const bool binary_off = ext == ".off" && text.substr(0, text.find('\n')).find("BINARY") != std::string::npos;
    if (ext == ".obj") return read_obj(path, text);
    if (!binary_off) return read_off(path, text);
  }

  TriangleMesh mesh;
  RecordingImporter importer(mesh);
  IO::Options options;
  if (!IO::IOManager().read(path, importer, options))
    throw IoError("cannot read '" + path + "': not a valid " + ext.substr(1) + " file");
  if (mesh.vertices.empty()) throw IoError("cannot read '" + path + "': no vertices found");
  return mesh;
}

}  // namespace cmaps
