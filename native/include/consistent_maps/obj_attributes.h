// What an OBJ file holds beyond the geometry read_mesh returns: texture
// coordinates per face corner ("vt" lines referenced as "f v/vt ...") and
// vertex colours ("v x y z r g b"). Polygons are fan-triangulated exactly as
// read_mesh does, so triangle k here is triangle k of read_mesh's mesh of the
// same file (and of every map computed on it).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

struct ObjAttributes {
  std::vector<std::array<double, 2>> uvs;        // the texture coordinates (u, v), file order
  std::vector<std::array<int, 3>> triangle_uvs;  // per triangle: index into uvs of each corner;
                                                 // empty when no face references texture coordinates
  std::vector<std::array<double, 3>> colors;     // per vertex (r, g, b); empty when no vertex has a colour
};

// Throws IoError naming the file (and the line) for a missing or unreadable
// file, a path not ending in .obj, malformed lines, a vt index out of range,
// and files that give texture coordinates to some faces only or colours to
// some vertices only.
ObjAttributes read_obj_attributes(const std::string& path);

// Writes `mesh` as OBJ with the attributes: "v x y z r g b" when colors is
// not empty (one per vertex), the texture coordinates and "f v/vt" faces when
// triangle_uvs is not empty (one per triangle). Throws InvalidInput for
// attributes that do not fit the mesh, IoError when the file cannot be written.
void write_obj_with_attributes(const std::string& path, const TriangleMesh& mesh, const ObjAttributes& attributes);

}  // namespace cmaps
