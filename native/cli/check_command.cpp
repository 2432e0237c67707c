// `cmaps check`: the mesh report, and whether the mesh suits a sphere or,
// failing that, an inter-surface map with a partner of its genus.
#include "commands.h"

#include <string>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"

namespace cmaps::cli {

namespace {

void add_report(JsonObject& json, const cmaps::MeshReport& r) {
  json.add("vertices", r.vertices)
      .add("referenced_vertices", r.referenced_vertices)
      .add("components", r.components)
      .add("boundary_loops", r.boundary_loops)
      .add("euler_characteristic", r.euler_characteristic)
      .add("genus", r.genus)
      .add("manifold", r.manifold())
      .add("closed", r.closed())
      .add("non_manifold_edges", r.non_manifold_edges)
      .add("non_manifold_vertices", r.non_manifold_vertices)
      .add("degenerate_faces", r.degenerate_faces)
      .add("duplicate_faces", r.duplicate_faces)
      .add("inconsistently_oriented_edges", r.inconsistently_oriented_edges)
      .add("non_finite_vertices", r.non_finite_vertices)
      .add("out_of_range_indices", r.out_of_range_indices);
}

}  // namespace

void run_check(const Arguments& args, Outcome& out) {
  const cmaps::TriangleMesh mesh = cmaps::read_mesh(args.input);
  const cmaps::MeshReport report = cmaps::check_mesh(mesh);
  out.faces = report.faces;
  add_report(out.json, report);
  out.summary = args.input + ": " + cmaps::summarize(report);
  bool pair_map = true;
  try {
    cmaps::require_pair_map_topology(mesh);
  } catch (const cmaps::InvalidInput&) {
    pair_map = false;
  }
  out.json.add("pair_map", pair_map);
  try {
    cmaps::require_sphere_topology(mesh);
  } catch (const cmaps::InvalidInput&) {
    if (pair_map)
      out.summary += "\nnot for the sphere, but `cmaps intersurface` maps it onto a partner of genus " +
                     std::to_string(report.genus) +
                     (report.closed() ? "" : " with as many holes (" + std::to_string(report.boundary_loops) + ")");
    throw;
  }
  out.summary += "\nok: suitable for spherical parameterization";
}

}  // namespace cmaps::cli
