// Gauss-Seidel style sweeps of per-vertex moves, run in parallel: vertices
// are greedily coloured so that no two neighbours share a colour, each colour
// class moves at once (a move reads only its neighbours, which stay put), and
// later sweeps revisit only the neighbourhoods of vertices that moved.
// Shared by the stretch optimizer of the spherical maps and the distortion
// optimizer of the inter-surface maps.
#pragma once
#include <algorithm>
#include <vector>

#include "common/parallel_for.h"
#include "consistent_maps/mesh.h"

namespace cmaps {

struct VertexColouring {
  std::vector<std::vector<int>> neighbours;  // per vertex (with repeats; only membership matters)
  std::vector<std::vector<int>> classes;     // vertices of each colour
};

// Colours the vertices for which vertex_active(v) holds, over the triangles
// for which face_active(f) holds.
template <class FaceActive, class VertexActive>
VertexColouring colour_vertices(int vertex_count, const std::vector<Triangle>& triangles,
                                const FaceActive& face_active, const VertexActive& vertex_active) {
  VertexColouring c;
  c.neighbours.resize(vertex_count);
  for (size_t f = 0; f < triangles.size(); ++f)
    if (face_active(f)) {
      const Triangle& t = triangles[f];
      for (int k = 0; k < 3; ++k) c.neighbours[t[k]].push_back(t[(k + 1) % 3]);
    }
  std::vector<int> colour(vertex_count, -1);
  std::vector<char> taken;
  for (int v = 0; v < vertex_count; ++v) {
    if (!vertex_active(v)) continue;
    taken.assign(c.classes.size() + 1, 0);
    for (int w : c.neighbours[v])
      if (colour[w] >= 0) taken[colour[w]] = 1;
    const int k = static_cast<int>(std::find(taken.begin(), taken.end(), 0) - taken.begin());
    if (k == static_cast<int>(c.classes.size())) c.classes.emplace_back();
    colour[v] = k;
    c.classes[k].push_back(v);
  }
  return c;
}

// Runs move(v) (returning how far v moved, relative) for the coloured
// vertices, sweep after sweep, until no vertex moved more than `tolerance`,
// `max_sweeps` is reached or keep_going(sweep) says stop; after_class(members)
// runs after each colour class, on the calling thread.
template <class Move, class KeepGoing, class AfterClass>
void coloured_sweeps(const VertexColouring& c, int threads, int max_sweeps, double tolerance, const Move& move,
                     const KeepGoing& keep_going, const AfterClass& after_class) {
  const size_t n = c.neighbours.size();
  std::vector<char> active(n, 0), next(n, 0);
  for (const auto& members : c.classes)
    for (int v : members) active[v] = 1;
  std::vector<double> moved(n, 0);
  for (int sweep = 0; sweep < max_sweeps && keep_going(sweep); ++sweep) {
    for (const auto& members : c.classes) {
      // A thread is started per call: not worth it for a small class. 256
      // keeps a coarse side's few hundred costly moves in parallel (the cow
      // against the horse: 6 classes of about 480, swept in 11.6 s on one
      // thread, 6.8 s on two).
      parallel_for(members.size(), members.size() > 256 ? threads : 1, [&](size_t i) {
        const int v = members[i];
        moved[v] = active[v] ? move(v) : 0;
      });
      after_class(members);
    }
    bool any = false;
    std::fill(next.begin(), next.end(), 0);
    for (size_t v = 0; v < n; ++v)
      if (active[v] && moved[v] > tolerance) {
        any = true;
        next[v] = 1;
        for (int w : c.neighbours[v]) next[w] = 1;
      }
    if (!any) break;
    active.swap(next);
  }
}

}  // namespace cmaps
