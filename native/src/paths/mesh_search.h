// Shortest paths on an EditableMesh by A* over its vertices and, optionally,
// its edge midpoints (candidate Steiner vertices). Search node v < V is a
// vertex, node V + e the midpoint of edge e, with V = vertex_count() at the
// time of the search.
#pragma once
#include <functional>
#include <unordered_map>
#include <vector>

#include "paths/edge_set.h"
#include "paths/editable_mesh.h"

namespace cmaps {

// The ring positions through which a path may leave (or enter) a vertex:
// ring vertex k sits at k, the midpoint of ring edge (k, k+1) at k + 0.5;
// allowed are positions strictly inside (lo, lo + span), counter-clockwise.
struct Sector {
  std::unordered_map<int, double> position;  // search node -> ring position
  double lo = 0, span = 0, size = 0;
  bool everything = true;

  bool allows(int node) const;
};

struct SearchRules {
  const std::vector<char>* blocked = nullptr;        // vertices no path may pass through
  const EdgeSet* closed_edges = nullptr;             // edges whose midpoints are off limits
  const Sector* leave = nullptr;   // how the path may leave the source (nullptr = freely)
  const Sector* enter = nullptr;   // how it may enter the target
  bool midpoints = false;
  double midpoint_penalty = 1.0;   // a step touching a midpoint costs 1 + this times its length
  // Optional, at least 1 everywhere (so the A* estimate stays a lower bound):
  // a step costs its length times the mean of this at its two ends.
  const std::function<double(const Vec3&)>* step_factor = nullptr;
};

// Node sequence from source to target, empty when none exists.
std::vector<int> shortest_path(const EditableMesh& mesh, int source, int target, const SearchRules& rules);

// Euclidean length of a node sequence (nodes encoded as in the search).
double path_length(const EditableMesh& mesh, const std::vector<int>& nodes, int vertices);

// A path laid down from a search result can step back into a triangle that
// one of its own earlier midpoints has split, so two consecutive vertices
// end up one Steiner vertex apart: reconnects them through the path's new
// vertices (those >= first_new, all inside the traced corridor) and cuts the
// loops that creates.
std::vector<int> reconnect_traced_path(const EditableMesh& mesh, const std::vector<int>& path, int first_new);

// The search-node position of a vertex or edge midpoint.
Vec3 node_position(const EditableMesh& mesh, int node, int vertices);

}  // namespace cmaps
