// The `cmaps` command-line tool: check a mesh, or compute its spherical
// parameterization. Every failure ends as exit code 1 (2 for usage errors)
// with one line "cmaps: error: ..." on stderr, and with --json also as one
// JSON object carrying "error" on stdout.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/spherical_parameterization.h"
#include "consistent_maps/version.h"
#include "json_writer.h"

namespace {

using cmaps::JsonObject;

const char* const kUsage = R"(usage:
  cmaps check IN [--json]
  cmaps sphere IN -o OUT [--seed N] [--effort 0|1|2] [--threads N] [--json]
  cmaps --help | --version

commands:
  check    read IN (.obj .off .ply .stl), print its topology and exit 0 if it
           can be mapped to the sphere (one closed, manifold, consistently
           oriented genus-0 surface); otherwise exit 1 naming the defect.
  sphere   compute a stretch-minimizing bijective map of IN onto the unit
           sphere and write OUT (.obj .ply .off): the input triangles and vertex
           order, with each position replaced by its unit vector.

options:
  -o, --output OUT   output file of `sphere`
  --seed N           random seed; equal seeds give equal results (default 1)
  --effort E         0 = fast preview, 1 = default, 2 = best quality
  --threads N        worker threads (default 2)
  --json             print exactly one JSON object on stdout (also on failure,
                     with an "error" string); no progress output
  -h, --help         show this help
  --version          show the version
)";

// A command-line mistake: reported like any error, but with exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Arguments {
  std::string command, input, output;
  std::uint64_t seed = 1;
  int effort = 1;
  int threads = 2;
  bool json = false;
};

long long parse_integer(const std::string& option, const std::string& text, long long low, long long high) {
  std::size_t used = 0;
  long long value = 0;
  try {
    value = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || value < low || value > high)
    throw UsageError(option + " expects an integer in [" + std::to_string(low) + ", " + std::to_string(high) +
                     "], got '" + text + "'");
  return value;
}

Arguments parse(const std::vector<std::string>& args) {
  Arguments a;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    const auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError(arg + " needs a value");
      return args[++i];
    };
    if (arg == "--json") a.json = true;
    else if (arg == "-o" || arg == "--output") a.output = value();
    else if (arg == "--seed") a.seed = std::uint64_t(parse_integer(arg, value(), 0, 1LL << 62));
    else if (arg == "--effort") a.effort = int(parse_integer(arg, value(), 0, 2));
    else if (arg == "--threads") a.threads = int(parse_integer(arg, value(), 1, 256));
    else if (arg.size() > 1 && arg[0] == '-') throw UsageError("unknown option '" + arg + "' (see cmaps --help)");
    else if (a.command.empty()) a.command = arg;
    else if (a.input.empty()) a.input = arg;
    else throw UsageError("unexpected argument '" + arg + "' (see cmaps --help)");
  }
  if (a.command.empty()) throw UsageError("missing command (see cmaps --help)");
  if (a.command != "check" && a.command != "sphere")
    throw UsageError("unknown command '" + a.command + "' (see cmaps --help)");
  if (a.input.empty()) throw UsageError("missing input mesh (see cmaps --help)");
  if (a.command == "sphere" && a.output.empty()) throw UsageError("sphere needs -o OUT (see cmaps --help)");
  if (a.command == "check" && !a.output.empty()) throw UsageError("check takes no -o");
  return a;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

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

// What a command learned before it finished or failed; printed either way.
struct Outcome {
  JsonObject json;
  std::optional<int> faces;
  std::optional<double> efficiency;
  std::optional<int> flipped;
  std::string summary;  // human-readable result, printed on success
};

void run_check(const Arguments& args, Outcome& out) {
  const cmaps::TriangleMesh mesh = cmaps::read_mesh(args.input);
  const cmaps::MeshReport report = cmaps::check_mesh(mesh);
  out.faces = report.faces;
  add_report(out.json, report);
  out.summary = args.input + ": " + cmaps::summarize(report);
  cmaps::require_sphere_topology(mesh);
  out.summary += "\nok: suitable for spherical parameterization";
}

// Progress on an interactive terminal only: logs and pipes get the result alone.
cmaps::ProgressCallback terminal_progress(bool enabled) {
  if (!enabled) return {};
  return [](double fraction, const std::string& stage) {
    std::fprintf(stderr, "\r%3d%% %-40.40s", int(100 * std::clamp(fraction, 0.0, 1.0)), stage.c_str());
    std::fflush(stderr);
    return true;
  };
}

void run_sphere(const Arguments& args, Outcome& out) {
  // Reject an unusable output path before a long computation, not after it.
  std::string ext = std::filesystem::path(args.output).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".obj" && ext != ".ply" && ext != ".off")
    throw UsageError("output '" + args.output + "' must end in .obj, .ply or .off");
  const std::filesystem::path parent = std::filesystem::path(args.output).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw cmaps::IoError("cannot write '" + args.output + "': directory '" + parent.string() + "' does not exist");

  cmaps::TriangleMesh mesh = cmaps::read_mesh(args.input);
  out.faces = int(mesh.triangles.size());
  out.json.add("vertices", int(mesh.vertices.size()));

  cmaps::SphereOptions options;
  options.seed = args.seed;
  options.effort = args.effort;
  options.threads = args.threads;
  const bool show_progress = !args.json && isatty(STDERR_FILENO);
  cmaps::SphereResult result;
  try {
    result = cmaps::spherical_parameterization(mesh, options, terminal_progress(show_progress));
  } catch (...) {
    if (show_progress) std::fputs("\r\033[K", stderr);
    throw;
  }
  if (show_progress) std::fputs("\r\033[K", stderr);

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
      .add("seconds_optimize", result.seconds_optimize)
      .add("seed", static_cast<unsigned long long>(args.seed))
      .add("effort", args.effort)
      .add("threads", args.threads)
      .add("output", args.output);

  mesh.vertices = std::move(result.sphere);
  cmaps::write_mesh(args.output, mesh);

  char line[256];
  std::snprintf(line, sizeof line, "stretch efficiency %.4f, L2 stretch %.4f, Linf stretch %.4f, %d flipped, %s",
                r.efficiency, r.l2_stretch, r.linf_stretch, r.flipped, r.bijective() ? "bijective" : "NOT bijective");
  out.summary = "wrote " + args.output + ": " + line;
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
    else run_sphere(args, out);
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
    out.json.add("faces", out.faces)
        .add("seconds", seconds_since(start))
        .add("stretch_efficiency", out.efficiency)
        .add("flipped", out.flipped);
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
