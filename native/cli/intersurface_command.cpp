// `cmaps intersurface`: the inter-surface map of two meshes of the same genus,
// written as surface points both ways and as each mesh mapped onto the other.
#include <cstdio>
#include <filesystem>
#include <optional>

#include "command_io.h"
#include "commands.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/pair_remesh.h"
#include "intersurface_common.h"

namespace cmaps::cli {

namespace {

// One line per source vertex: target triangle, then its three barycentric weights.
std::string surface_points_text(const std::vector<cmaps::SurfacePoint>& points) {
  std::string text;
  char line[128];
  for (std::size_t i = 0; i < points.size(); ++i) {
    const cmaps::SurfacePoint& p = points[i];
    std::snprintf(line, sizeof line, "%s%d %.17g %.17g %.17g", i ? "\n" : "", p.triangle, p.barycentric[0],
                  p.barycentric[1], p.barycentric[2]);
    text += line;
  }
  return text;
}

// remesh_features.json: each given pair's remesh vertex, by its name in the features file.
std::string remesh_features_text(const std::vector<std::string>& names, const cmaps::PairRemesh& remesh) {
  JsonObject vertices;
  for (std::size_t k = 0; k < remesh.feature_vertices.size(); ++k) vertices.add(names[k], remesh.feature_vertices[k]);
  return vertices.str();
}

}  // namespace

void run_intersurface(const Arguments& args, Outcome& out) {
  out.intersurface = true;
  check_output_directory(args.output);
  out.json.add_json("inputs", JsonObject::array(args.inputs));
  const cmaps::TriangleMesh a = cmaps::read_mesh(args.inputs[0]);
  const cmaps::TriangleMesh b = cmaps::read_mesh(args.inputs[1]);
  out.faces_per_input = JsonObject::array(std::vector<int>{int(a.triangles.size()), int(b.triangles.size())});
  std::vector<std::string> names;
  const std::vector<cmaps::FeaturePair> features = read_feature_pairs(args, a, b, &names);
  out.feature_count = int(features.size());

  const cmaps::IntersurfaceOptions options = intersurface_options(args);
  const cmaps::IntersurfaceResult result =
      with_terminal_progress(args, [&](const cmaps::ProgressCallback& progress) {
        return cmaps::intersurface_map(a, b, features, options, progress);
      });
  if (result.a_to_b.size() != a.vertices.size() || result.b_to_a.size() != b.vertices.size())
    throw cmaps::Error("internal error: the inter-surface map returned " + std::to_string(result.a_to_b.size()) +
                       " and " + std::to_string(result.b_to_a.size()) + " images for " +
                       std::to_string(a.vertices.size()) + " and " + std::to_string(b.vertices.size()) + " vertices");

  // Only the given pairs are held: locking the added ones too (arbitrary
  // points matched by position) folded as many or more remesh triangles.
  std::optional<cmaps::PairRemesh> remesh;
  if (args.remesh_given)
    remesh = cmaps::remesh_pair(a, b, result.a_to_b, result.b_to_a, features, args.remesh * args.remesh + 2);

  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(args.output, error);
  if (error) throw cmaps::IoError("cannot create '" + args.output + "': " + error.message());
  const auto path = [&](const char* name) { return (fs::path(args.output) / name).string(); };
  std::vector<std::string> outputs{path("A_to_B.txt"), path("B_to_A.txt"), path("A_on_B.obj"), path("B_on_A.obj")};
  write_text(outputs[0], surface_points_text(result.a_to_b));
  write_text(outputs[1], surface_points_text(result.b_to_a));
  cmaps::write_mesh(outputs[2], cmaps::TriangleMesh{result.a_on_b, a.triangles});
  cmaps::write_mesh(outputs[3], cmaps::TriangleMesh{result.b_on_a, b.triangles});
  if (remesh) {
    outputs.insert(outputs.end(), {path("A_remesh.obj"), path("B_remesh.obj"), path("remesh_features.json")});
    cmaps::write_mesh(outputs[4], cmaps::TriangleMesh{remesh->a_positions, remesh->triangles});
    cmaps::write_mesh(outputs[5], cmaps::TriangleMesh{remesh->b_positions, remesh->triangles});
    write_text(outputs[6], remesh_features_text(names, *remesh));
    out.json.add("remesh", args.remesh)
        .add("remesh_vertices", int(remesh->carrier_vertex.size()))
        .add("remesh_carrier", remesh->b_carries ? "B" : "A")
        .add("remesh_folded", remesh->folded_triangles);
  } else {
    out.json.null("remesh").null("remesh_vertices").null("remesh_carrier").null("remesh_folded");
  }

  report_map(result, features.size(), false, out);
  const cmaps::MapDistortion &ab = result.distortion_a_to_b, &ba = result.distortion_b_to_a;
  out.outputs = JsonObject::array(outputs);
  const auto computed = [](double median) { return median < 0 ? std::nullopt : std::optional<double>(median); };
  out.json.add("genus", result.genus)
      .add("method", cmaps::method_name(result.method))
      .add("sphere_median_dirichlet", computed(result.sphere_median_dirichlet))
      .add("partition_median_dirichlet", computed(result.partition_median_dirichlet))
      .add_json("degenerate", JsonObject::array(std::vector<int>{ab.degenerate, ba.degenerate}))
      .add_json("median_symmetric_dirichlet", JsonObject::array(std::vector<double>{
                                                  ab.median_symmetric_dirichlet, ba.median_symmetric_dirichlet}))
      .add("sphere_flipped", result.sphere_flipped)
      .add("map_flipped", result.map_flipped)
      .add_json("refitted", std::string(result.refitted_a ? "[true, " : "[false, ") +
                                (result.refitted_b ? "true]" : "false]"))
      .add("balanced_patches", result.balanced_patches)
      .add("patch_area_ratio", result.patch_area_ratio)
      .add("base_vertices", result.base_vertices)
      .add("base_triangles", result.base_triangles)
      .add("seconds_features", result.seconds_features)
      .add_json("composition_dirichlet",
                JsonObject::array(std::vector<double>{result.composition_a_to_b.symmetric_dirichlet,
                                                      result.composition_b_to_a.symmetric_dirichlet}))
      .add("restart_dirichlet", result.restart_dirichlet)
      .add("restart_median_dirichlet", result.restart_median_dirichlet)
      .add_json("restart_flipped", JsonObject::array(result.restart_flipped))
      .add("start_median_dirichlet", result.start_median_dirichlet)
      .add("seconds_partition", result.seconds_partition)
      .add("seconds_parameterize", result.seconds_parameterize)
      .add("seconds_optimize", result.seconds_optimize)
      .add("seconds_locate", result.seconds_locate)
      .add("seconds_measure", result.seconds_measure)
      .add("seconds_compute", result.seconds);
  add_settings(out.json, args);

  char line[320];
  std::snprintf(line, sizeof line,
                "%zu feature pairs (%d added), symmetric Dirichlet %.4f (A to B) / %.4f (B to A), %d map folds "
                "(%d / %d flipped samples), %d + %d Steiner vertices",
                result.features.size(), result.added_features, ab.symmetric_dirichlet, ba.symmetric_dirichlet,
                result.map_flipped, ab.flipped, ba.flipped, result.steiner_a, result.steiner_b);
  out.summary = "wrote " + std::to_string(outputs.size()) + " files to " + args.output + ": " + line;
  if (remesh)
    out.summary += "; remeshes of " + std::to_string(remesh->carrier_vertex.size()) + " vertices (" +
                   (remesh->b_carries ? "B" : "A") + "'s), " + std::to_string(remesh->folded_triangles) +
                   " triangles folded";
}

}  // namespace cmaps::cli
