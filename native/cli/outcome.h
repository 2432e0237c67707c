// What a command learned before it finished or failed: `cmaps` prints it
// either way (as JSON with --json), so a failure still reports what was known.
#pragma once

#include <optional>
#include <string>

#include "json_writer.h"

namespace cmaps::cli {

struct Outcome {
  JsonObject json;
  std::optional<int> faces;
  std::optional<double> efficiency;
  std::optional<int> flipped;
  std::string summary;  // human-readable result, printed on success
  // `constrained` only: its --json keys, null until known.
  bool constrained = false;
  std::optional<bool> bijective;
  std::optional<int> degenerate, steiner_vertices, auxiliary_vertices, retraced_paths, layout_flips;
  std::optional<double> steiner_fraction, max_constraint_error, seconds_paths, seconds_simplify, seconds_optimize;
  std::optional<JsonObject> targets;
  // `consistent` only: its --json keys (JSON text: per-input lists, objects), null until known.
  bool consistent = false;
  std::optional<std::string> faces_per_input, efficiencies, flips, steiner_counts, bijective_per_input,
      feature_locations, outputs;
  std::optional<int> first;
  // `intersurface` only: per direction (A to B, B to A) or per mesh (A, B), null until known.
  bool intersurface = false;
  std::optional<std::string> dirichlet, steiner_per_mesh, added_features;
  std::optional<int> feature_count;
  // `transfer` only (with the intersurface keys above: TARGET onto SOURCE).
  bool transfer = false;
  std::optional<std::string> transferred;
};

}  // namespace cmaps::cli
