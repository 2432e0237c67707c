// A network of non-crossing paths on a mesh between feature vertices, with
// the same topology as a triangulation of the features' target points on the
// sphere (thesis 3.3.2; Praun, Sweldens & Schroeder 2001): one path per arc,
// paths meet only at features, and the cyclic order of paths around every
// feature equals the order of arcs around its target.
//
// Paths are traced greedily, shortest first, by A* over mesh vertices; a
// spanning tree of the features is completed before any cycle is closed, so
// the network stays connected and, with matching cyclic orders, every face
// of the partial network corresponds to a face of the partial arc graph: the
// next arc always has a corridor on the mesh. Where the corridor is thinner
// than a mesh edge, the search also walks over edge midpoints, which become
// Steiner vertices (edge splits) when the path is laid down.
#pragma once
#include <array>
#include <vector>

#include "consistent_maps/progress.h"
#include "paths/editable_mesh.h"

namespace cmaps {

struct PathNetwork {
  std::vector<std::array<int, 2>> arcs;   // feature index pairs (the sphere triangulation's edges)
  std::vector<std::vector<int>> paths;     // per arc: mesh vertices from arcs[i][0]'s feature to arcs[i][1]'s
  int steiner_vertices = 0;
  int retraced = 0;  // candidates re-traced because the network had changed
  int flips = 0;     // layout arcs flipped to shorter surface paths before tracing
};

// `features[i]` is the mesh vertex of feature i, `targets[i]` its unit vector;
// `sphere_triangles` triangulate the targets (counter-clockwise from outside);
// arcs are first flipped where the other diagonal has a shorter surface path.
// The mesh must be oriented outwards (positive signed volume). Grows `mesh`
// by the Steiner vertices it needs.
//
// `prelaid` paths (mesh vertices from one feature's vertex to another's, for
// arcs of the triangulation; e.g. hole boundaries) are taken as given, never
// traced or flipped: they block their vertices and edges and fix the
// cyclic position of later paths at their ends.
PathNetwork trace_path_network(EditableMesh& mesh, const std::vector<int>& features, const std::vector<Vec3>& targets,
                               const std::vector<Triangle>& sphere_triangles, const ProgressSlice& progress,
                               const std::vector<std::vector<int>>& prelaid = {});

}  // namespace cmaps
