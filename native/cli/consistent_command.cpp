// `cmaps consistent`: the consistent spherical parameterization of a set, with
// its remeshes and geometry images.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>

#include "command_io.h"
#include "commands.h"
#include "consistent_maps/consistent_parameterization.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/geometry_image.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "json_reader.h"

namespace cmaps::cli {

namespace {

// A set's members with their features, read and checked with the input file
// and the feature named in every message.
struct SetInput {
  std::vector<std::string> names;
  std::vector<cmaps::ConsistentMember> members;
};

SetInput read_set(const Arguments& args, Outcome& out) {
  SetInput set;
  std::vector<int> faces;
  for (const std::string& path : args.inputs) {
    cmaps::TriangleMesh mesh = cmaps::read_mesh(path);
    faces.push_back(int(mesh.triangles.size()));
    out.faces_per_input = JsonObject::array(faces);
    try {
      cmaps::require_sphere_topology(mesh, true);
    } catch (const cmaps::TopologyError& e) {
      throw cmaps::TopologyError(path + ": " + e.what());
    } catch (const cmaps::InvalidInput& e) {
      throw cmaps::InvalidInput(path + ": " + e.what());
    }
    set.members.push_back({std::move(mesh), {}});
  }

  const int count = int(args.inputs.size());
  const auto features = cmaps::read_set_feature_file(args.features, count);
  if (features.size() < 3)
    throw cmaps::InvalidInput(args.features + ": need at least 3 features, got " + std::to_string(features.size()));
  std::vector<std::map<int, std::string>> by_vertex(count);
  for (const auto& [name, vertices] : features) {
    set.names.push_back(name);
    for (int i = 0; i < count; ++i) {
      const int v = vertices[i], n = int(set.members[i].mesh.vertices.size());
      const std::string& path = args.inputs[i];
      if (v >= n)
        throw cmaps::InvalidInput(args.features + ": feature " + in_quotes(name) + ": vertex " + std::to_string(v) +
                                  " is out of range for " + path + " (" + std::to_string(n) + " vertices)");
      if (v >= 0) {
        const auto [it, inserted] = by_vertex[i].emplace(v, name);
        if (!inserted)
          throw cmaps::InvalidInput(args.features + ": features " + in_quotes(it->second) + " and " + in_quotes(name) +
                                    " are both vertex " + std::to_string(v) + " of " + path);
      }
      set.members[i].features.push_back(v);
    }
  }
  const auto lacking = [&](int i) {
    std::vector<std::string> missing;
    for (std::size_t k = 0; k < set.names.size(); ++k)
      if (set.members[i].features[k] < 0) missing.push_back(in_quotes(set.names[k]));
    return missing;
  };
  for (int i = 0; i < count; ++i) {
    const std::size_t present = set.names.size() - lacking(i).size();
    if (present < 3)
      throw cmaps::InvalidInput(args.features + ": " + args.inputs[i] + " has " + std::to_string(present) +
                                " of the features; every input needs at least 3");
  }
  if (args.first_given) {
    const auto missing = lacking(args.first);
    if (!missing.empty())
      throw cmaps::InvalidInput("--first " + std::to_string(args.first) + ": " + args.inputs[args.first] +
                                " lacks feature " + missing.front() + "; the first input must have every feature");
  } else {
    bool complete = false;
    for (int i = 0; i < count && !complete; ++i) complete = lacking(i).empty();
    if (!complete)
      throw cmaps::InvalidInput(args.features +
                                ": no input has every feature; one must, to seed the feature locations");
  }
  return set;
}

}  // namespace

void run_consistent(const Arguments& args, Outcome& out) {
  out.consistent = true;
  check_output_directory(args.output);
  out.json.add("inputs_count", int(args.inputs.size())).add_json("inputs", JsonObject::array(args.inputs));
  const SetInput set = read_set(args, out);
  const std::vector<cmaps::ConsistentMember>& members = set.members;
  out.json.add("features", int(set.names.size()));

  cmaps::ConsistentOptions options;
  options.sphere = sphere_options(args);
  options.first = args.first;
  options.grid = args.grid;
  options.restarts = args.restarts;
  options.align = args.align;
  const cmaps::ConsistentResult result =
      with_terminal_progress(args, [&](const cmaps::ProgressCallback& progress) {
        return cmaps::consistent_spherical_parameterization(members, options, progress);
      });
  if (result.members.size() != members.size() || result.feature_locations.size() != set.names.size())
    throw cmaps::Error("internal error: the consistent parameterization returned " +
                       std::to_string(result.members.size()) + " maps for " + std::to_string(members.size()) +
                       " meshes");
  std::optional<cmaps::ConsistentRemesh> remesh;
  if (args.remesh_given) remesh = cmaps::consistent_remesh(members, result, args.remesh, args.threads);

  // Everything to write, prepared in memory: nothing is written unless all of it could be computed.
  namespace fs = std::filesystem;
  std::vector<std::string> outputs;
  std::vector<std::function<void()>> writers;
  const auto output = [&](const std::string& name, std::function<void(const std::string&)> write) {
    const std::string path = (fs::path(args.output) / name).string();
    outputs.push_back(path);
    writers.push_back([path, write = std::move(write)] { write(path); });
  };
  const auto mesh_output = [&](const std::string& name, cmaps::TriangleMesh mesh) {
    output(name, [mesh = std::move(mesh)](const std::string& path) { cmaps::write_mesh(path, mesh); });
  };

  std::vector<int> steiner, flipped;
  std::vector<double> efficiency;
  std::string bijective = "[";
  for (std::size_t i = 0; i < members.size(); ++i) {
    const cmaps::ConstrainedResult& map = result.members[i];
    const std::string k = std::to_string(i);
    for (const cmaps::Vec3& p : map.sphere)
      if (!p.allFinite()) throw cmaps::Error("internal error: the parameterization produced a non-finite position");
    mesh_output(k + ".sphere.obj", cmaps::TriangleMesh{map.sphere, members[i].mesh.triangles});
    cmaps::ParameterizedSurface surface = cmaps::parameterized_surface(members[i].mesh, map);
    mesh_output(k + ".refined_sphere.obj", cmaps::TriangleMesh{surface.sphere, surface.surface.triangles});
    mesh_output(k + ".refined.obj", std::move(surface.surface));
    steiner.push_back(int(map.steiner.size()));
    flipped.push_back(map.report.flipped);
    efficiency.push_back(map.report.efficiency);
    bijective += std::string(i ? ", " : "") + (map.report.bijective() ? "true" : "false");
  }

  JsonObject locations;
  for (std::size_t k = 0; k < set.names.size(); ++k) {
    const cmaps::Vec3& p = result.feature_locations[k];
    locations.add(set.names[k], std::vector<double>{p.x(), p.y(), p.z()});
  }
  output("features.json", [text = locations.str()](const std::string& path) { write_text(path, text); });

  if (remesh) {
    const cmaps::OctahedralGrid grid = cmaps::octahedral_grid(args.remesh);
    for (std::size_t i = 0; i < members.size(); ++i) {
      const std::string k = std::to_string(i);
      cmaps::TriangleMesh mesh{remesh->positions[i], remesh->triangles};
      const cmaps::GeometryImage geometry = cmaps::geometry_image(grid, mesh.vertices);
      const cmaps::GeometryImage normals = cmaps::geometry_image(grid, cmaps::vertex_normals(mesh));
      mesh_output(k + ".remesh.obj", std::move(mesh));
      output(k + ".geometry.npy", [geometry](const std::string& p) { cmaps::write_geometry_image_npy(p, geometry); });
      output(k + ".geometry.png", [geometry](const std::string& p) { cmaps::write_geometry_image_png(p, geometry); });
      output(k + ".normals.npy", [normals](const std::string& p) { cmaps::write_geometry_image_npy(p, normals); });
    }
    JsonObject vertices;
    for (std::size_t k = 0; k < set.names.size(); ++k) vertices.add(set.names[k], remesh->feature_vertices[k]);
    output("remesh_features.json", [text = vertices.str()](const std::string& path) { write_text(path, text); });
    out.json.add("remesh", args.remesh).add("remesh_vertices", int(remesh->sphere.size()));
  } else {
    out.json.null("remesh").null("remesh_vertices");
  }

  std::error_code error;
  fs::create_directories(args.output, error);
  if (error) throw cmaps::IoError("cannot create '" + args.output + "': " + error.message());
  for (const auto& write : writers) write();

  out.efficiencies = JsonObject::array(efficiency);
  out.flips = JsonObject::array(flipped);
  out.steiner_counts = JsonObject::array(steiner);
  out.bijective_per_input = bijective + "]";
  out.feature_locations = locations.str();
  out.outputs = JsonObject::array(outputs);
  out.first = result.first;
  out.json.add("grid", args.grid)
      .add("restarts", args.restarts)
      .add("align", args.align)
      .add("restart", result.restart)
      .add_json("restart_suitability", JsonObject::array(result.restart_suitability))
      .add("seconds_compute", result.seconds);
  add_settings(out.json, args);

  const auto [lo, hi] = std::minmax_element(efficiency.begin(), efficiency.end());
  int flips = 0, added = 0;
  for (std::size_t i = 0; i < members.size(); ++i) flips += flipped[i], added += steiner[i];
  char line[320];
  std::snprintf(line, sizeof line,
                "%zu meshes, %zu features on common points (input %d first), stretch efficiency %.4f..%.4f, "
                "%d flipped, %d Steiner vertices",
                members.size(), set.names.size(), result.first, *lo, *hi, flips, added);
  out.summary = "wrote " + std::to_string(outputs.size()) + " files to " + args.output + ": " + line;
}

}  // namespace cmaps::cli
