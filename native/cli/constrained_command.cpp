// `cmaps constrained`: a spherical parameterization with feature vertices on
// given (or automatic) points.
#include <algorithm>
#include <cstdio>
#include <map>

#include "command_io.h"
#include "commands.h"
#include "consistent_maps/constrained_parameterization.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "json_reader.h"

namespace cmaps::cli {

namespace {

// Features (in the features file's order) with their targets, matched by name
// and checked against the mesh, each problem named by its feature.
struct Constraints {
  std::vector<std::string> names;
  std::vector<int> vertices;
  std::vector<cmaps::Vec3> targets;  // empty: automatic
};

Constraints read_constraints(const Arguments& args, int vertex_count) {
  Constraints c;
  const auto features = cmaps::read_feature_file(args.features);
  if (features.size() < 3)
    throw cmaps::InvalidInput(args.features + ": need at least 3 features, got " + std::to_string(features.size()));
  std::map<int, std::string> by_vertex;
  for (const auto& [name, vertex] : features) {
    if (vertex >= vertex_count)
      throw cmaps::InvalidInput(args.features + ": feature " + in_quotes(name) + ": vertex " + std::to_string(vertex) +
                                " is out of range (the mesh has " + std::to_string(vertex_count) + " vertices)");
    const auto [it, inserted] = by_vertex.emplace(vertex, name);
    if (!inserted)
      throw cmaps::InvalidInput(args.features + ": features " + in_quotes(it->second) + " and " + in_quotes(name) +
                                " are both vertex " + std::to_string(vertex));
    c.names.push_back(name);
    c.vertices.push_back(vertex);
  }
  if (args.targets.empty()) return c;

  const auto targets = cmaps::read_target_file(args.targets);
  std::map<std::string, cmaps::Vec3> by_name(targets.begin(), targets.end());
  for (const auto& [name, target] : targets) {
    if (std::find(c.names.begin(), c.names.end(), name) == c.names.end())
      throw cmaps::InvalidInput("target " + in_quotes(name) + " in " + args.targets + " names no feature in " +
                                args.features);
  }
  for (const std::string& name : c.names) {
    const auto it = by_name.find(name);
    if (it == by_name.end())
      throw cmaps::InvalidInput("feature " + in_quotes(name) + " has no target in " + args.targets);
    const cmaps::Vec3& p = it->second;
    if (!p.allFinite()) throw cmaps::InvalidInput(args.targets + ": target " + in_quotes(name) + " is not finite");
    if (!(p.norm() > 0))
      throw cmaps::InvalidInput(args.targets + ": target " + in_quotes(name) + " is the zero vector");
    c.targets.push_back(p);
  }
  // Same tolerance as the library, which would report indices instead of names.
  for (std::size_t i = 0; i < c.targets.size(); ++i)
    for (std::size_t j = i + 1; j < c.targets.size(); ++j)
      if ((c.targets[i].normalized() - c.targets[j].normalized()).norm() < 1e-9)
        throw cmaps::InvalidInput(args.targets + ": targets " + in_quotes(c.names[i]) + " and " +
                                  in_quotes(c.names[j]) + " are equal (after normalization)");
  return c;
}

}  // namespace

void run_constrained(const Arguments& args, Outcome& out) {
  out.constrained = true;
  check_output_path(args.output);
  if (!args.refined_mesh.empty()) check_output_path(args.refined_mesh);

  cmaps::TriangleMesh mesh = cmaps::read_mesh(args.input);
  out.faces = int(mesh.triangles.size());
  out.json.add("vertices", int(mesh.vertices.size()));
  const int n = int(mesh.vertices.size());
  const Constraints constraints = read_constraints(args, n);
  out.json.add("features", int(constraints.vertices.size()));

  const cmaps::SphereOptions options = sphere_options(args);
  const cmaps::ConstrainedResult result =
      with_terminal_progress(args, [&](const cmaps::ProgressCallback& progress) {
        return cmaps::constrained_spherical_parameterization(mesh, constraints.vertices, constraints.targets, options,
                                                             progress);
      });

  const std::size_t total = mesh.vertices.size() + result.steiner.size();
  if (result.sphere.size() != mesh.vertices.size() || result.targets.size() != constraints.vertices.size())
    throw cmaps::Error("internal error: the constrained parameterization returned " +
                       std::to_string(result.sphere.size()) + " positions for " + std::to_string(n) + " vertices");
  for (const cmaps::Triangle& t : result.triangles)
    for (int v : t)
      if (v < 0 || std::size_t(v) >= total)
        throw cmaps::Error("internal error: the refined triangulation refers to vertex " + std::to_string(v));

  // The sphere mesh: input vertices in input order, then the Steiner vertices.
  cmaps::TriangleMesh sphere{result.sphere, result.triangles};
  cmaps::TriangleMesh refined{mesh.vertices, result.triangles};
  for (const cmaps::SteinerVertex& s : result.steiner) {
    sphere.vertices.push_back(s.sphere);
    cmaps::Vec3 x = cmaps::Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      if (s.vertices[k] >= 0) x += s.weights[k] * mesh.vertices[s.vertices[k]];
    refined.vertices.push_back(x);
  }
  for (const cmaps::Vec3& p : sphere.vertices) {
    if (!p.allFinite()) throw cmaps::Error("internal error: the parameterization produced a non-finite position");
  }

  const cmaps::SphericalMapReport& r = result.report;
  out.efficiency = r.efficiency;
  out.flipped = r.flipped;
  out.degenerate = r.degenerate;
  out.bijective = r.bijective();
  out.steiner_vertices = int(result.steiner.size());
  out.steiner_fraction = double(result.steiner.size()) / double(n);
  out.auxiliary_vertices = result.auxiliary_vertices;
  out.retraced_paths = result.retraced_paths;
  out.layout_flips = result.layout_flips;
  out.max_constraint_error = result.max_constraint_error;
  out.seconds_paths = result.seconds_paths;
  out.seconds_simplify = result.seconds_simplify;
  out.seconds_optimize = result.seconds_optimize;
  JsonObject targets;
  for (std::size_t i = 0; i < constraints.names.size(); ++i) {
    const cmaps::Vec3& t = result.targets[i];
    targets.add(constraints.names[i], std::vector<double>{t.x(), t.y(), t.z()});
  }
  out.targets = targets;
  out.json.add("output_vertices", int(total))
      .add("output_faces", int(result.triangles.size()))
      .add("l2_stretch", r.l2_stretch)
      .add("linf_stretch", r.linf_stretch)
      .add("spherical_area_sum", r.spherical_area_sum)
      .add("surface_area", r.surface_area)
      .add("automatic_targets", constraints.targets.empty());
  add_settings(out.json, args);
  if (args.refined_mesh.empty()) out.json.null("refined_mesh");
  else out.json.add("refined_mesh", args.refined_mesh);

  cmaps::write_mesh(args.output, sphere);
  if (!args.refined_mesh.empty()) cmaps::write_mesh(args.refined_mesh, refined);

  char line[320];
  std::snprintf(line, sizeof line,
                "%zu features on their targets (max error %.3g), %zu Steiner vertices, stretch efficiency %.4f, "
                "%d flipped, %s",
                constraints.vertices.size(), result.max_constraint_error, result.steiner.size(), r.efficiency,
                r.flipped, r.bijective() ? "bijective" : "NOT bijective");
  out.summary = "wrote " + args.output + (args.refined_mesh.empty() ? "" : " and " + args.refined_mesh) + ": " + line;
}

}  // namespace cmaps::cli
