// Progressive mesh by half-edge collapses (Hoppe 1996) ordered by quadric
// error (Garland & Heckbert 1997), kept positions: a collapse removed -> kept
// moves nothing, so every intermediate mesh uses original vertex positions.
//
// The mesh at any level is the input's triangle array with collapsed vertex
// indices replaced by the vertices they merged into; triangles that became
// degenerate are inactive. A VertexSplit undoes one collapse exactly, so
// replaying all splits restores the input triangles, index for index.
#pragma once
#include <array>
#include <vector>

#include "consistent_maps/mesh.h"
#include "consistent_maps/progress.h"

namespace cmaps {

struct SimplificationOptions {
  // Per-vertex flag (empty = none): locked vertices are never removed.
  std::vector<char> locked;
  // Constrained edges (paths). A vertex on a path is only removed by
  // collapsing along one of its two path edges; path junctions and ends must
  // be locked.
  std::vector<std::array<int, 2>> path_edges;
  // Vertex chains (hole boundaries between two features, which map onto one
  // great-circle arc): no collapse may join two vertices of one chain by a
  // new edge unless the removed vertex lies on that chain (a collapse along it).
  std::vector<std::vector<int>> chains;
  // Further geometries sharing the input's connectivity (vertex order); the
  // quadric error and the flip test then cover every geometry.
  std::vector<std::vector<Vec3>> extra_geometries;
  // Per geometry (the input's first, then the extra ones; empty = none), one
  // normal per vertex: that of the surface it lies on. A triangle facing
  // against its corners' normals is folded: no collapse may fold a triangle,
  // one may turn a folded triangle over, and collapses removing folds go first.
  std::vector<std::vector<Vec3>> reference_normals;
  // Stop at this many vertices (4 = tetrahedron) or when nothing can collapse.
  int target_vertices = 4;
  // When the geometric tests block every collapse before the target: go on
  // without them (true), or stop there.
  bool finish_without_geometric_tests = true;
};

// The inverse of the half-edge collapse `removed` -> `kept`.
struct VertexSplit {
  int removed = -1, kept = -1;
  int left = -1, right = -1;            // third vertices of the two restored triangles
  int face_left = -1, face_right = -1;  // the two restored triangles
  int changed_begin = 0, changed_end = 0;  // range in ProgressiveMesh::changed_faces
};

struct ProgressiveMesh {
  int vertex_count = 0;  // of the full mesh
  // Triangle array at the coarsest level; inactive triangles hold the corners
  // they had when they collapsed.
  std::vector<Triangle> base_triangles;
  std::vector<char> base_face_active;
  std::vector<char> base_vertex_active;
  // Splits in refinement order (coarse to fine).
  std::vector<VertexSplit> splits;
  // Triangles whose `kept` corner becomes `removed` again at a split.
  std::vector<int> changed_faces;
  int base_vertex_count() const { return vertex_count - static_cast<int>(splits.size()); }
};

// Throws TopologyError unless the mesh is closed and manifold, and Cancelled.
ProgressiveMesh build_progressive_mesh(const TriangleMesh& mesh, const SimplificationOptions& options = {},
                                       const ProgressCallback& progress = {});

// Walks a progressive mesh from its base to the full mesh one split at a time,
// maintaining the current triangles and each vertex's incident triangles.
class MeshRefinement {
 public:
  explicit MeshRefinement(const ProgressiveMesh& pm);

  bool has_next_split() const { return next_ < pm_.splits.size(); }
  size_t splits_applied() const { return next_; }
  const VertexSplit& apply_next_split();

  int active_vertex_count() const { return active_vertices_; }
  bool vertex_active(int v) const { return vertex_active_[v]; }
  bool face_active(int f) const { return face_active_[f]; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<int>& faces_of(int v) const { return vertex_faces_[v]; }
  // The current neighbours of v in counter-clockwise order.
  std::vector<int> ring(int v) const;
  // The triangles currently active.
  std::vector<Triangle> active_triangles() const;

 private:
  const ProgressiveMesh& pm_;
  size_t next_ = 0;
  int active_vertices_ = 0;
  std::vector<Triangle> triangles_;
  std::vector<char> face_active_, vertex_active_;
  std::vector<std::vector<int>> vertex_faces_;
};

}  // namespace cmaps
