// Reading and writing triangle meshes through OpenMesh's readers and writers.
#pragma once
#include <string>

#include "consistent_maps/mesh.h"

namespace cmaps {

// Reads OBJ, OFF, PLY (ascii or binary) or STL. Polygons are fan-triangulated.
// Faces are returned exactly as the file lists them (no vertex merging beyond
// what the format implies, non-manifold faces kept) so check_mesh can report
// defects. Throws IoError for a missing, empty or unreadable file.
TriangleMesh read_mesh(const std::string& path);

// Writes by extension: .obj, .off, .ply, .stl. Throws IoError on failure.
void write_mesh(const std::string& path, const TriangleMesh& mesh);

}  // namespace cmaps
