// `cmaps sphere`: the stretch-minimizing spherical parameterization of one mesh.
#include <cstdio>

#include "command_io.h"
#include "commands.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/spherical_parameterization.h"

namespace cmaps::cli {

void run_sphere(const Arguments& args, Outcome& out) {
  check_output_path(args.output);

  cmaps::TriangleMesh mesh = cmaps::read_mesh(args.input);
  out.faces = int(mesh.triangles.size());
  out.json.add("vertices", int(mesh.vertices.size()));

  const cmaps::SphereOptions options = sphere_options(args);
  const cmaps::SphereResult result =
      with_terminal_progress(args, [&](const cmaps::ProgressCallback& progress) {
        return cmaps::spherical_parameterization(mesh, options, progress);
      });

  if (result.sphere.size() != mesh.vertices.size())
    throw cmaps::Error("internal error: the parameterization returned " + std::to_string(result.sphere.size()) +
                       " positions for " + std::to_string(mesh.vertices.size()) + " vertices");
  for (const cmaps::Vec3& p : result.sphere) {
    if (!p.allFinite()) throw cmaps::Error("internal error: the parameterization produced a non-finite position");
  }
  const cmaps::SphericalMapReport& r = result.report;
  out.efficiency = r.efficiency;
  out.flipped = r.flipped;
  out.json.add("l2_stretch", r.l2_stretch)
      .add("linf_stretch", r.linf_stretch)
      .add("degenerate", r.degenerate)
      .add("spherical_area_sum", r.spherical_area_sum)
      .add("surface_area", r.surface_area)
      .add("bijective", r.bijective())
      .add("seconds_simplify", result.seconds_simplify)
      .add("seconds_optimize", result.seconds_optimize);
  add_settings(out.json, args);

  mesh.vertices = std::move(result.sphere);
  cmaps::write_mesh(args.output, mesh);

  char line[256];
  std::snprintf(line, sizeof line, "stretch efficiency %.4f, L2 stretch %.4f, Linf stretch %.4f, %d flipped, %s",
                r.efficiency, r.l2_stretch, r.linf_stretch, r.flipped, r.bijective() ? "bijective" : "NOT bijective");
  out.summary = "wrote " + args.output + ": " + line;
}

}  // namespace cmaps::cli
