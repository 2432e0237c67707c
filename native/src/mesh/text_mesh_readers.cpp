#include "mesh/text_mesh_readers.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "consistent_maps/errors.h"

namespace cmaps {
namespace {

// Splits a buffer into lines without their comments, keeping line numbers for messages.
class Lines {
 public:
  explicit Lines(const std::string& text) : text_(text) {}

  // The next line with content (comment stripped), or false at the end.
  bool next(std::string& line) {
    while (pos_ < text_.size()) {
      size_t end = text_.find('\n', pos_);
      if (end == std::string::npos) end = text_.size();
      line.assign(text_, pos_, end - pos_);
      pos_ = end + 1;
      ++number_;
      if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
      if (line.find_first_not_of(" \t\r\f\v") != std::string::npos) return true;
    }
    return false;
  }

  int number() const { return number_; }

 private:
  const std::string& text_;
  size_t pos_ = 0;
  int number_ = 0;
};

// Whitespace-separated tokens of one line.
std::vector<std::string_view> tokens(const std::string& line) {
  std::vector<std::string_view> out;
  const std::string_view s(line);
  size_t i = 0;
  while (true) {
    i = s.find_first_not_of(" \t\r\f\v", i);
    if (i == std::string_view::npos) return out;
    const size_t end = std::min(s.find_first_of(" \t\r\f\v", i), s.size());
    out.push_back(s.substr(i, end - i));
    i = end;
  }
}

// strtod accepts "nan" and "inf", which must reach check_mesh as such.
bool parse_double(std::string_view token, double& value) {
  const std::string copy(token);
  char* end = nullptr;
  value = std::strtod(copy.c_str(), &end);
  return end != copy.c_str() && *end == '\0';
}

// Parses a leading integer ("12", "-3", "7/2/1"); out-of-int values saturate so
// they are reported as out-of-range indices rather than wrapping around.
bool parse_index(std::string_view token, long long& value) {
  const std::string copy(token);
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(copy.c_str(), &end, 10);
  if (end == copy.c_str() || (*end != '\0' && *end != '/')) return false;
  if (errno == ERANGE || value > INT_MAX || value < INT_MIN) value = value < 0 ? INT_MIN : INT_MAX;
  return true;
}

int saturate(long long v) { return v > INT_MAX ? INT_MAX : v < INT_MIN ? INT_MIN : int(v); }

void add_fan(TriangleMesh& mesh, const std::vector<int>& polygon) {
  for (size_t i = 1; i + 1 < polygon.size(); ++i) mesh.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
}

[[noreturn]] void malformed(const std::string& path, int line, const std::string& what) {
  throw IoError("cannot read '" + path + "': line " + std::to_string(line) + ": " + what);
}

}  // namespace

TriangleMesh read_obj(const std::string& path, const std::string& text) {
  TriangleMesh mesh;
  Lines lines(text);
  std::string line;
  std::vector<int> polygon;
  while (lines.next(line)) {
    const auto t = tokens(line);
    if (t[0] == "v") {
      Vec3 p;
      if (t.size() < 4 || !parse_double(t[1], p.x()) || !parse_double(t[2], p.y()) || !parse_double(t[3], p.z()))
        malformed(path, lines.number(), "a vertex needs three numbers");
      mesh.vertices.push_back(p);
    } else if (t[0] == "f" || t[0] == "fo") {
      polygon.clear();
      for (size_t i = 1; i < t.size(); ++i) {
        long long index = 0;
        if (!parse_index(t[i], index) || index == 0)
          malformed(path, lines.number(), "bad face index '" + std::string(t[i]) + "'");
        // OBJ counts from 1; negative indices count back from the latest vertex.
        polygon.push_back(saturate(index > 0 ? index - 1 : (long long)mesh.vertices.size() + index));
      }
      if (polygon.size() < 3) malformed(path, lines.number(), "a face needs at least three vertices");
      add_fan(mesh, polygon);
    }
    // Texture coordinates, normals, groups, materials and lines carry nothing the library uses.
  }
  if (mesh.vertices.empty()) throw IoError("cannot read '" + path + "': no vertices found");
  return mesh;
}

ObjAttributes read_obj_attributes(const std::string& path, const std::string& text) {
  ObjAttributes attributes;
  Lines lines(text);
  std::string line;
  int vertices = 0, faces = 0, faces_with_uvs = 0, first_face_without = 0, first_face_with = 0;
  int first_colourless = 0, first_coloured = 0;
  std::vector<int> polygon_uvs;
  while (lines.next(line)) {
    const auto t = tokens(line);
    if (t[0] == "v") {
      ++vertices;
      if (t.size() >= 7) {
        std::array<double, 3> c{};
        if (!parse_double(t[4], c[0]) || !parse_double(t[5], c[1]) || !parse_double(t[6], c[2]))
          malformed(path, lines.number(), "a vertex colour needs three numbers");
        attributes.colors.push_back(c);
        if (!first_coloured) first_coloured = lines.number();
      } else if (!first_colourless) {
        first_colourless = lines.number();
      }
    } else if (t[0] == "vt") {
      std::array<double, 2> uv{};
      if (t.size() < 2 || !parse_double(t[1], uv[0]) || (t.size() > 2 && !parse_double(t[2], uv[1])))
        malformed(path, lines.number(), "texture coordinates need one or two numbers");
      attributes.uvs.push_back(uv);
    } else if (t[0] == "f" || t[0] == "fo") {
      ++faces;
      polygon_uvs.clear();
      for (size_t i = 1; i < t.size(); ++i) {
        const size_t slash = t[i].find('/');
        if (slash == std::string_view::npos || slash + 1 >= t[i].size() || t[i][slash + 1] == '/') continue;
        long long index = 0;
        if (!parse_index(t[i].substr(slash + 1), index) || index == 0)
          malformed(path, lines.number(), "bad texture coordinate index in '" + std::string(t[i]) + "'");
        const long long resolved = index > 0 ? index - 1 : (long long)attributes.uvs.size() + index;
        if (resolved < 0 || resolved >= (long long)attributes.uvs.size())
          malformed(path, lines.number(), "texture coordinate " + std::to_string(index) + " does not exist (" +
                                              std::to_string(attributes.uvs.size()) + " so far)");
        polygon_uvs.push_back(int(resolved));
      }
      if (t.size() < 4) malformed(path, lines.number(), "a face needs at least three vertices");
      if (polygon_uvs.empty()) {
        if (!first_face_without) first_face_without = lines.number();
        continue;
      }
      if (polygon_uvs.size() != t.size() - 1)
        malformed(path, lines.number(), "some corners of the face have texture coordinates and some not");
      ++faces_with_uvs;
      if (!first_face_with) first_face_with = lines.number();
      for (size_t i = 1; i + 1 < polygon_uvs.size(); ++i)  // the fan of read_obj
        attributes.triangle_uvs.push_back({polygon_uvs[0], polygon_uvs[i], polygon_uvs[i + 1]});
    }
  }
  if (faces_with_uvs > 0 && faces_with_uvs < faces)
    malformed(path, first_face_without,
              "the face has no texture coordinates but the face on line " + std::to_string(first_face_with) +
                  " has; give every face texture coordinates or none");
  if (!attributes.colors.empty() && int(attributes.colors.size()) < vertices)
    malformed(path, first_colourless,
              "the vertex has no colour but the vertex on line " + std::to_string(first_coloured) +
                  " has; give every vertex a colour or none");
  return attributes;
}

TriangleMesh read_off(const std::string& path, const std::string& text) {
  TriangleMesh mesh;
  Lines lines(text);
  std::string line;
  if (!lines.next(line)) throw IoError("cannot read '" + path + "': no vertices found");
  auto header = tokens(line);
  const std::string_view keyword = header[0];
  // [ST][C][N]OFF; the 4D and n-dimensional variants have no meaning here.
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF" ||
      keyword.find_first_of("4n") != std::string_view::npos)
    malformed(path, lines.number(), "expected an OFF header, got '" + std::string(keyword) + "'");
  const bool texture = keyword.find("ST") != std::string_view::npos;
  header.erase(header.begin());
  if (header.empty()) {
    if (!lines.next(line)) malformed(path, lines.number(), "missing vertex and face counts");
    header = tokens(line);
  }
  long long n_vertices = 0, n_faces = 0;
  if (header.size() < 2 || !parse_index(header[0], n_vertices) || !parse_index(header[1], n_faces) ||
      n_vertices < 0 || n_faces < 0 || n_vertices > INT_MAX / 2 || n_faces > INT_MAX / 4)
    malformed(path, lines.number(), "expected vertex, face and edge counts");

  mesh.vertices.reserve(size_t(n_vertices));
  for (long long v = 0; v < n_vertices; ++v) {
    if (!lines.next(line)) malformed(path, lines.number(), "file ends after " + std::to_string(v) + " of " +
                                                              std::to_string(n_vertices) + " vertices");
    const auto t = tokens(line);
    Vec3 p;
    if (t.size() < (texture ? 5u : 3u) || !parse_double(t[0], p.x()) || !parse_double(t[1], p.y()) ||
        !parse_double(t[2], p.z()))
      malformed(path, lines.number(), "a vertex needs three numbers");
    mesh.vertices.push_back(p);
  }
  std::vector<int> polygon;
  mesh.triangles.reserve(size_t(n_faces));
  for (long long f = 0; f < n_faces; ++f) {
    if (!lines.next(line)) malformed(path, lines.number(), "file ends after " + std::to_string(f) + " of " +
                                                              std::to_string(n_faces) + " faces");
    const auto t = tokens(line);
    long long corners = 0;
    if (!parse_index(t[0], corners) || corners < 3 || t.size() < size_t(corners) + 1)
      malformed(path, lines.number(), "a face needs a corner count of at least 3 and that many indices");
    polygon.clear();
    for (long long i = 1; i <= corners; ++i) {
      long long index = 0;
      if (!parse_index(t[i], index)) malformed(path, lines.number(), "bad face index '" + std::string(t[i]) + "'");
      polygon.push_back(saturate(index));
    }
    add_fan(mesh, polygon);  // anything after the indices is a face colour
  }
  if (mesh.vertices.empty()) throw IoError("cannot read '" + path + "': no vertices found");
  return mesh;
}

}  // namespace cmaps
