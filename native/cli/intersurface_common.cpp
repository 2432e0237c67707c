#include "intersurface_common.h"

#include <map>
#include <string>

#include "command_io.h"
#include "consistent_maps/errors.h"
#include "json_reader.h"
#include "json_writer.h"

namespace cmaps::cli {

std::vector<cmaps::FeaturePair> read_feature_pairs(const Arguments& args, const cmaps::TriangleMesh& a,
                                                   const cmaps::TriangleMesh& b, std::vector<std::string>* names) {
  if (args.features.empty()) return {};
  std::vector<cmaps::FeaturePair> pairs;
  std::map<int, std::string> seen[2];
  const cmaps::TriangleMesh* meshes[2] = {&a, &b};
  for (const auto& [name, vertices] : cmaps::read_set_feature_file(args.features, 2)) {
    for (int i = 0; i < 2; ++i) {
      const std::string& path = args.inputs[i];
      const int v = vertices[i], n = int(meshes[i]->vertices.size());
      if (v < 0)
        throw cmaps::InvalidInput(args.features + ": feature " + in_quotes(name) + " has no vertex on " + path +
                                  "; an inter-surface feature needs one on both meshes");
      if (v >= n)
        throw cmaps::InvalidInput(args.features + ": feature " + in_quotes(name) + ": vertex " + std::to_string(v) +
                                  " is out of range for " + path + " (" + std::to_string(n) + " vertices)");
      const auto [it, inserted] = seen[i].emplace(v, name);
      if (!inserted)
        throw cmaps::InvalidInput(args.features + ": features " + in_quotes(it->second) + " and " + in_quotes(name) +
                                  " are both vertex " + std::to_string(v) + " of " + path);
    }
    pairs.push_back({vertices[0], vertices[1]});
    if (names) names->push_back(name);
  }
  return pairs;
}

cmaps::IntersurfaceOptions intersurface_options(const Arguments& args) {
  cmaps::IntersurfaceOptions options;
  options.sphere = sphere_options(args);
  options.optimize_rounds = args.optimize;
  if (args.optimize == 0) options.correspondence_weight = 0;  // the plain composition
  options.cross_sweeps = args.cross_sweeps;
  options.cross_turns = args.cross_turns;
  options.restarts = args.restarts;
  options.starts = args.starts;
  options.method = args.method.value_or(cmaps::IntersurfaceMethod::automatic);
  return options;
}

void report_map(const cmaps::IntersurfaceResult& map, std::size_t given, bool swapped, Outcome& out) {
  const auto ordered = [swapped](auto first, auto second) {
    return swapped ? std::vector<decltype(first)>{second, first} : std::vector<decltype(first)>{first, second};
  };
  const cmaps::MapDistortion &forward = map.distortion_a_to_b, &backward = map.distortion_b_to_a;
  out.dirichlet = JsonObject::array(ordered(forward.symmetric_dirichlet, backward.symmetric_dirichlet));
  out.flips = JsonObject::array(ordered(forward.flipped, backward.flipped));
  out.efficiencies = JsonObject::array(ordered(map.efficiency_a, map.efficiency_b));
  out.steiner_per_mesh = JsonObject::array(ordered(map.steiner_a, map.steiner_b));
  std::string added = "[";
  for (std::size_t k = given; k < map.features.size(); ++k)
    added += std::string(k > given ? ", " : "") + JsonObject::array(ordered(map.features[k].a, map.features[k].b));
  out.added_features = added + "]";
}

}  // namespace cmaps::cli
