// `cmaps transfer`: colours, texture coordinates or the shape of SOURCE carried
// onto TARGET through their inter-surface map.
#include <cstdio>
#include <utility>

#include "command_io.h"
#include "commands.h"
#include "consistent_maps/attribute_transfer.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/obj_attributes.h"
#include "intersurface_common.h"

namespace cmaps::cli {

void run_transfer(const Arguments& args, Outcome& out) {
  out.intersurface = out.transfer = true;
  check_output_path(args.output);
  if (lowercase_extension(args.output) != ".obj")
    throw UsageError("transfer writes OBJ: output '" + args.output + "' must end in .obj");
  out.json.add_json("inputs", JsonObject::array(args.inputs));
  const std::string &source_path = args.inputs[0], &target_path = args.inputs[1];
  const cmaps::TriangleMesh source = cmaps::read_mesh(source_path);
  const cmaps::TriangleMesh target = cmaps::read_mesh(target_path);
  out.faces_per_input = JsonObject::array(std::vector<int>{int(source.triangles.size()), int(target.triangles.size())});
  const std::string source_ext = lowercase_extension(source_path);
  const cmaps::ObjAttributes attributes =
      source_ext == ".obj" ? cmaps::read_obj_attributes(source_path) : cmaps::ObjAttributes{};
  const bool colours = !attributes.colors.empty(), uvs = !attributes.triangle_uvs.empty();
  if (!colours && !uvs && !args.positions)
    throw cmaps::InvalidInput("'" + source_path + "' has no vertex colours or texture coordinates to transfer" +
                              (source_ext == ".obj" ? "" : " (only .obj files carry them)") +
                              "; give --positions to carry its shape over");
  std::vector<cmaps::FeaturePair> features = read_feature_pairs(args, source, target);
  for (cmaps::FeaturePair& f : features) std::swap(f.a, f.b);  // the map goes from TARGET (A) onto SOURCE (B)
  out.feature_count = int(features.size());

  cmaps::IntersurfaceOptions options = intersurface_options(args);
  options.corner_images = uvs;
  const cmaps::IntersurfaceResult map =
      with_terminal_progress(args, [&](const cmaps::ProgressCallback& progress) {
        try {
          return cmaps::intersurface_map(target, source, features, options, progress);
        } catch (const cmaps::InvalidInput& e) {  // the library calls the meshes A and B
          throw cmaps::InvalidInput("mapping TARGET '" + target_path + "' (A) onto SOURCE '" + source_path +
                                    "' (B): " + e.what());
        }
      });
  const cmaps::ObjAttributes carried = cmaps::transfer_obj_attributes(source, attributes, target, map);
  cmaps::write_obj_with_attributes(args.output, {args.positions ? map.a_on_b : target.vertices, target.triangles},
                                   carried);

  std::vector<std::string> transferred;
  if (colours) transferred.push_back("colors");
  if (uvs) transferred.push_back("uvs");
  if (args.positions) transferred.push_back("positions");
  out.transferred = JsonObject::array(transferred);
  report_map(map, features.size(), true, out);
  const cmaps::MapDistortion& ts = map.distortion_a_to_b;
  out.outputs = JsonObject::array(std::vector<std::string>{args.output});
  out.json.add("genus", map.genus)
      .add("method", cmaps::method_name(map.method))
      .add("seconds_compute", map.seconds);
  add_settings(out.json, args);

  std::string what;
  for (const std::string& name : transferred) what += (what.empty() ? "" : ", ") + name;
  char line[256];
  std::snprintf(line, sizeof line,
                " through %zu feature pairs (%d added), symmetric Dirichlet %.4f (target onto source)",
                map.features.size(), map.added_features, ts.symmetric_dirichlet);
  out.summary = "wrote " + args.output + ": " + what + " of " + source_path + " on " + target_path + line;
}

}  // namespace cmaps::cli
