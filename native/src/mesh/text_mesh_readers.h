// Readers for the two text formats, used instead of OpenMesh's: those parse
// coordinates as float, silently skip vertices they cannot parse (shifting
// every later index), drop faces with repeated corners and reject OFF headers
// with comments. These keep doubles, NaN/inf, and every face as written.
#pragma once
#include <string>

#include "consistent_maps/mesh.h"
#include "consistent_maps/obj_attributes.h"

namespace cmaps {

// Both throw IoError naming `path` and the line for malformed content.
TriangleMesh read_obj(const std::string& path, const std::string& text);
TriangleMesh read_off(const std::string& path, const std::string& text);

// The texture coordinates and vertex colours of an OBJ text (see obj_attributes.h),
// triangulated like read_obj.
ObjAttributes read_obj_attributes(const std::string& path, const std::string& text);

}  // namespace cmaps
