// One mesh's side of a consistent partition while it grows
// (consistent_partition.cpp): the mesh refined by Steiner vertices, its
// features, the paths laid so far between them (closed to later paths), and
// the queries the partitioner asks of them: the ends around a feature in
// counter-clockwise order, the sector between two ends, the regions the paths
// cut the surface into, shortest paths that respect all of this.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "consistent_maps/mesh.h"
#include "paths/editable_mesh.h"
#include "paths/mesh_search.h"

namespace cmaps::partition {

// One end of a path: `end` 0 at its first vertex, 1 at its last.
struct End {
  int path = -1;
  int end = 0;
  bool operator==(const End& o) const { return path == o.path && end == o.end; }
};

class Side {
 public:
  Side(const TriangleMesh& mesh, int first_fan)
      : mesh(mesh), first_fan(first_fan), blocked(this->mesh.vertex_count(), 0) {}

  EditableMesh mesh;
  int first_fan;              // triangles refined from input triangles at or past this fill a hole
  std::vector<char> blocked;  // features and path vertices
  EdgeSet path_edges;
  std::vector<int> feature;
  std::vector<std::vector<int>> paths;

  bool fan(int f) const { return mesh.input_triangle(f) >= first_fan; }

  // Regions (see regions()) that hold surface, not a hole's fan.
  int surface_regions() const;

  // Appends mesh vertex v as the next feature (blocked from then on).
  void add_feature(int v);

  // Splits mesh edge e at its midpoint; returns the new (unblocked) vertex.
  int split(int e);

  // The vertex after the feature along the path of end x.
  int first_step(const End& x) const;

  // The ends at feature f, counter-clockwise.
  std::vector<End> ends(int f, const std::vector<std::array<int, 2>>& edges) const;

  // Ring positions of f's search neighbours (as in path_network.cpp): ring
  // vertex k at k, the midpoint of ring edge (k, k+1) at k + 0.5, the
  // midpoint of the edge to ring vertex k at k.
  Sector positions(int f, int vertices, bool midpoints) const;

  // The side of a traced node sequence (search nodes, `vertices` as at the
  // trace) each vertex of `queries` lies on: +1 left, -1 right, walking from
  // its first node with the surface's outside up; 0 when none is found. The
  // side is where the shortest route from the query meets the path's interior
  // (thesis 3.3.3); routes may cross other paths, not this one.
  std::vector<int> sides_of(const std::vector<int>& nodes, int vertices, const std::vector<int>& queries) const;

  // The sector after end x at f (up to the next end counter-clockwise).
  Sector after(int f, const End& x, const std::vector<End>& around, int vertices, bool midpoints) const;

  // The end after which a path through search node `node` leaves f.
  End gap_of(int f, int node, const std::vector<End>& around, int vertices, bool midpoints) const;

  using StepFactor = std::function<double(const Vec3&)>;

  // The shortest path of search nodes (mesh_search.h) from feature `from` to
  // feature `to`, leaving and entering through the given sectors when given.
  std::vector<int> trace(int from, int to, const Sector* leave, const Sector* enter, bool midpoints,
                         const StepFactor* factor) const;

  // The length of edge (u, w), times the mean of its ends' `weight` when given.
  double step(int u, int w, const std::vector<double>* weight) const;

  // Turns a traced node sequence into mesh vertices (splitting the edges of
  // midpoint nodes) and blocks it.
  void lay(const std::vector<int>& nodes, int vertices);

  // Records a path of mesh vertices: its edges closed, its vertices blocked.
  void register_path(const std::vector<int>& path);

  // Per triangle: its region (triangles connected across non-path edges).
  std::vector<int> regions(int& count) const;

  // A triangle in the sector after end x at f.
  int corner_face(int f, const End& x) const;

  // Dijkstra over unblocked vertices (those marked in `allowed` when given)
  // from `sources`; distances and parents; steps weighted as in
  // SearchRules::step_factor by the per-vertex `weight` when given.
  void dijkstra(const std::vector<int>& sources, const std::vector<char>* allowed, std::vector<double>& dist,
                std::vector<int>& parent, const std::vector<double>* weight = nullptr) const;
};

}  // namespace cmaps::partition
