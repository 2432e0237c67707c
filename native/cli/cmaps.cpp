// The `cmaps` command-line tool: check a mesh, map it to the sphere (with or
// without feature points), parameterize a set consistently, map two meshes of
// the same genus onto each other or carry attributes across (one file per
// command). Every failure ends as exit code 1 (2 for usage errors) with one
// line "cmaps: error: ..." on stderr, and with --json also as one JSON object
// carrying "error" on stdout.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "arguments.h"
#include "commands.h"
#include "consistent_maps/version.h"

namespace {

using namespace cmaps::cli;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string one_line(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::replace(message.begin(), message.end(), '\r', ' ');
  return message;
}

int run(const std::vector<std::string>& argv) {
  const bool json = std::find(argv.begin(), argv.end(), "--json") != argv.end();
  const auto start = std::chrono::steady_clock::now();
  Outcome out;
  std::string error;
  int code = 0;
  try {
    const Arguments args = parse(argv);
    out.json.add("command", args.command).add("input", args.input);
    if (args.command == "check") run_check(args, out);
    else if (args.command == "sphere") run_sphere(args, out);
    else if (args.command == "consistent") run_consistent(args, out);
    else if (args.command == "intersurface") run_intersurface(args, out);
    else if (args.command == "transfer") run_transfer(args, out);
    else run_constrained(args, out);
  } catch (const UsageError& e) {
    error = e.what(), code = 2;
  } catch (const std::bad_alloc&) {
    error = "out of memory", code = 1;
  } catch (const std::exception& e) {
    error = e.what(), code = 1;
  } catch (...) {
    error = "unknown internal error", code = 1;
  }
  error = one_line(error);

  if (json) {
    if (out.consistent) {
      out.json.add_json("faces", out.faces_per_input)
          .add("seconds", seconds_since(start))
          .add_json("stretch_efficiency", out.efficiencies)
          .add_json("flipped", out.flips)
          .add_json("steiner_vertices", out.steiner_counts)
          .add_json("bijective", out.bijective_per_input)
          .add_json("feature_locations", out.feature_locations)
          .add("first", out.first)
          .add_json("outputs", out.outputs);
    } else if (out.intersurface) {
      out.json.add_json("faces", out.faces_per_input)
          .add("seconds", seconds_since(start))
          .add_json("stretch_efficiency", out.efficiencies)
          .add_json("symmetric_dirichlet", out.dirichlet)
          .add_json("flipped", out.flips)
          .add_json("steiner", out.steiner_per_mesh)
          .add("features", out.feature_count)
          .add_json("added_features", out.added_features)
          .add_json("outputs", out.outputs);
      if (out.transfer) out.json.add_json("transferred", out.transferred);
    } else {
      out.json.add("faces", out.faces)
          .add("seconds", seconds_since(start))
          .add("stretch_efficiency", out.efficiency)
          .add("flipped", out.flipped);
    }
    if (out.constrained) {
      out.json.add("degenerate", out.degenerate)
          .add("bijective", out.bijective)
          .add("steiner_vertices", out.steiner_vertices)
          .add("steiner_fraction", out.steiner_fraction)
          .add("auxiliary_vertices", out.auxiliary_vertices)
          .add("retraced_paths", out.retraced_paths)
          .add("layout_flips", out.layout_flips)
          .add("max_constraint_error", out.max_constraint_error)
          .add("targets", out.targets)
          .add("seconds_paths", out.seconds_paths)
          .add("seconds_simplify", out.seconds_simplify)
          .add("seconds_optimize", out.seconds_optimize);
    }
    if (code != 0) out.json.add("error", error);
    else out.json.null("error");
    std::cout << out.json.str() << std::endl;
  } else if (!out.summary.empty()) {
    std::cout << out.summary << std::endl;  // for a failed check: the report behind the error
  }
  if (code != 0) std::cerr << "cmaps: error: " << error << std::endl;
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  const auto has = [&](const char* flag) { return std::find(args.begin(), args.end(), flag) != args.end(); };
  if (has("-h") || has("--help") || (!args.empty() && args[0] == "help")) {
    std::cout << kUsage;
    return 0;
  }
  if (has("--version")) {
    std::cout << "cmaps " << cmaps::kVersion << std::endl;
    return 0;
  }
  return run(args);
}
