// The `cmaps` command-line tool: check a mesh, compute its spherical
// parameterization (unconstrained or with feature vertices at given points),
// or the consistent parameterization of a set with its remeshes and geometry
// images. Every failure ends as exit code 1 (2 for usage errors) with one line "cmaps: error: ..." on stderr, and with --json also as one
// JSON object carrying "error" on stdout.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "consistent_maps/attribute_transfer.h"
#include "consistent_maps/consistent_parameterization.h"
#include "consistent_maps/constrained_parameterization.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/geometry_image.h"
#include "consistent_maps/intersurface_map.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/obj_attributes.h"
#include "consistent_maps/spherical_parameterization.h"
#include "consistent_maps/version.h"
#include "json_reader.h"
#include "json_writer.h"

namespace {

using cmaps::JsonObject;

const char* const kUsage = R"(usage:
  cmaps check IN [--json]
  cmaps sphere IN -o OUT [--seed N] [--effort 0|1|2] [--threads N] [--json]
  cmaps constrained IN --features FILE [--targets FILE] -o OUT [--refined-mesh PATH]
                    [--seed N] [--effort 0|1|2] [--threads N] [--json]
  cmaps consistent IN IN ... --features FILE -o DIR [--remesh N] [--grid N] [--first K] [--restarts K]
                   [--align] [--seed N] [--effort 0|1|2] [--threads N] [--json]
  cmaps intersurface A B [--features FILE] -o DIR [--method auto|sphere|partition] [--optimize R]
                     [--cross-sweeps N] [--restarts K] [--starts S] [--seed N] [--effort 0|1|2] [--threads N]
                     [--json]
  cmaps transfer SOURCE TARGET [--features FILE] -o OUT.obj [--positions] [--method auto|sphere|partition]
                 [--optimize R] [--cross-sweeps N] [--restarts K] [--starts S] [--seed N] [--effort 0|1|2]
                 [--threads N] [--json]
  cmaps --help | --version

commands:
  check    read IN (.obj .off .ply .stl), print its topology and exit 0 if it
           can be mapped to the sphere (one closed, manifold, consistently
           oriented genus-0 surface); otherwise exit 1 naming the defect.
  sphere   compute a stretch-minimizing bijective map of IN onto the unit
           sphere and write OUT (.obj .ply .off): the input triangles and vertex
           order, with each position replaced by its unit vector.
  constrained
           like `sphere`, with every feature vertex exactly at its target
           point. OUT holds the input vertices first, in input order, then
           any Steiner vertices the map needed, with the faces of the refined
           triangulation the map is piecewise linear on.
  consistent
           map a set of meshes so that each named feature lands on one common
           point of the sphere on every mesh. Writes, for the k-th input
           (0-based), DIR/<k>.sphere.obj (the input's faces and vertex order,
           positions replaced by unit vectors), DIR/<k>.refined_sphere.obj and
           DIR/<k>.refined.obj (the refined triangulation the map is piecewise
           linear on, Steiner vertices included, on the sphere and on the
           surface), DIR/features.json (name -> common unit vector) and, with
           --remesh N, DIR/<k>.remesh.obj (all remeshes share one connectivity),
           geometry images DIR/<k>.geometry.npy, DIR/<k>.geometry.png,
           DIR/<k>.normals.npy and DIR/remesh_features.json (name -> remesh
           vertex). Nothing is written unless the whole computation succeeds.
  intersurface
           map two closed meshes of the same genus onto each other (genus >= 1
           through a consistent partition into patches; genus 0 that way and
           through a common sphere, keeping the less distorted, see --method),
           each feature of A exactly onto its partner on B.
           Genus-0 meshes may have holes, each ringed by at least 3 features
           (the same pairs around corresponding holes). Writes
           DIR/A_to_B.txt and DIR/B_to_A.txt (one line per source vertex: the
           target triangle index in the target's input triangle order, then
           three barycentric weights) and DIR/A_on_B.obj, DIR/B_on_A.obj (the
           source's faces and vertex order, positions mapped onto the other
           surface). Without --features (or with fewer than 3 pairs) pairs are
           added automatically. The map is optimized for symmetric distortion
           (--optimize rounds, each moving A's vertices then B's; the
           direct map's vertices also cross the partition's paths, so
           these stop being walls); genus >= 1
           maps also go through the partition with its patches' areas
           balanced, kept when less distorted (as for --method; JSON:
           balanced_patches, patch_area_ratio).
  transfer map TARGET onto SOURCE as `intersurface` does and write OUT.obj:
           TARGET's faces and vertex order with SOURCE's vertex colours
           ("v x y z r g b") and texture coordinates (vt, per face corner: a
           corner takes the coordinates inside the SOURCE triangle a point of
           its own triangle next to it lands in, so seams stay seams) carried
           over; with --positions, TARGET's vertices moved to where they land
           on SOURCE (TARGET's mesh in SOURCE's shape). SOURCE must be an .obj
           file for colours and texture coordinates; TARGET's own are not kept.

options:
  -o, --output OUT   output file of `sphere` and `constrained`; output
                     directory of `consistent` and `intersurface` (created if missing)
  --features FILE    JSON object {"name": vertex_index, ...} (0-based, at least 3);
                     for `consistent` {"name": [index or null per input], ...};
                     for `intersurface` {"name": [index_in_A, index_in_B], ...},
                     for `transfer` {"name": [index_in_SOURCE, index_in_TARGET], ...}
  --targets FILE     JSON object {"name": [x, y, z], ...} with the same names
                     (normalized; distinct); without it the targets are where
                     the unconstrained map puts the features
  --positions        transfer: also carry SOURCE's positions over
  --refined-mesh PATH
                     also write OUT's mesh with 3D positions (Steiner vertices
                     on the input surface)
  --remesh N         consistent remeshes on the octahedral grid of resolution N
                     (even, 2..4096; N^2 + 2 vertices) and their geometry images
  --grid N           octahedral grid resolution of the intermediate remeshes
                     (even, 2..4096; default 64)
  --first K          input seeding the feature locations (default: the first
                     input that has every feature)
  --optimize R       rounds of distortion optimization of the inter-surface map
                     (0..100, default 2; 0 = the plain composition of the
                     two spherical maps, neither refitted to the other, and
                     the direct map as its patches are embedded)
  --cross-sweeps N   intersurface, transfer: at most N sweeps of the direct
                     map's vertices moving across the partition's paths
                     (0..10000, default 20; 0 = the paths stay walls; more
                     sweeps move paths farther, slowly)
  --starts S         intersurface, transfer: the direct map of a pair without
                     --features and without holes pairs the surfaces' handles
                     and parts as its automatic first pair decides (A's
                     vertex farthest from its centroid and B's nearest in
                     A's frame, or another of A's spread by farthest-point
                     sampling): S first pairs are each mapped without
                     optimization and the least distorted one optimized
                     (1..100, default 8; JSON: start_median_dirichlet)
  --method M         intersurface, transfer (genus 0): map through the common
                     sphere, directly through a consistent partition as for
                     genus >= 1, or auto (default): both, keeping the less
                     distorted: the lower summed median (JSON: method,
                     sphere_median_dirichlet, partition_median_dirichlet),
                     or, for medians within 5 % of each other, the fewer
                     folded samples (JSON: flipped) if the counts differ by
                     more than 0.5 % of the triangles, else the direct map.
                     The direct map follows shapes that are alike (poses or
                     expressions of one shape: its paths are shortest on
                     both); the sphere spreads the distortion between
                     different shapes. The
                     direct map (any genus) is traced and optimized from A's
                     side and from B's, the less distorted kept.
  --restarts K       intersurface, transfer: through the sphere (genus 0),
                     compute the map K times and keep the least distorted
                     (as for --method auto; 1..100,
                     default 1): restart k uses seed N + k/3 and, in turn, a
                     consistent parameterization in one pass, with carried
                     guides, and with carried guides and B aligned to A; the
                     optimization is local, so with few features restarts
                     find better maps. The direct map of a pair without
                     --features and without holes is optimized from the K
                     least distorted of its --starts first pairs.
                     consistent: compute the set K times (seed N + k) and keep
                     the one whose maps keep most of each input's own
                     efficiency (with few features a run can twist one
                     input's map around them)
  --align            consistent: after the six steps, refit each input's map
                     towards the seeding input's (--first) where that lowers the
                     distortion between them: poses of one shape slide less
                     between the features, at some of each input's efficiency
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
  std::vector<std::string> inputs;              // consistent: every input; otherwise just `input`
  std::string features, targets, refined_mesh;  // constrained only (features: consistent too)
  int remesh = 0, grid = 64, first = -1;        // consistent only
  bool remesh_given = false, grid_given = false, first_given = false;
  // optimize, cross_sweeps, starts: intersurface and transfer only, defaults the library's
  int optimize = cmaps::IntersurfaceOptions{}.optimize_rounds, restarts = 1,
      cross_sweeps = cmaps::IntersurfaceOptions{}.cross_sweeps, starts = cmaps::IntersurfaceOptions{}.starts;
  bool optimize_given = false, restarts_given = false, cross_sweeps_given = false, starts_given = false;
  std::optional<cmaps::IntersurfaceMethod> method;  // intersurface and transfer only
  std::uint64_t seed = 1;
  int effort = 1;
  int threads = 2;
  bool json = false;
  bool positions = false;  // transfer only
  bool align = false;      // consistent only
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
    else if (arg == "--positions") a.positions = true;
    else if (arg == "--align") a.align = true;
    else if (arg == "-o" || arg == "--output") a.output = value();
    else if (arg == "--features") a.features = value();
    else if (arg == "--targets") a.targets = value();
    else if (arg == "--refined-mesh") a.refined_mesh = value();
    else if (arg == "--seed") a.seed = std::uint64_t(parse_integer(arg, value(), 0, 1LL << 62));
    else if (arg == "--effort") a.effort = int(parse_integer(arg, value(), 0, 2));
    else if (arg == "--threads") a.threads = int(parse_integer(arg, value(), 1, 256));
    else if (arg == "--remesh") a.remesh = int(parse_integer(arg, value(), 2, 4096)), a.remesh_given = true;
    else if (arg == "--grid") a.grid = int(parse_integer(arg, value(), 2, 4096)), a.grid_given = true;
    else if (arg == "--first") a.first = int(parse_integer(arg, value(), 0, 1 << 20)), a.first_given = true;
    else if (arg == "--optimize") a.optimize = int(parse_integer(arg, value(), 0, 100)), a.optimize_given = true;
    else if (arg == "--cross-sweeps")
      a.cross_sweeps = int(parse_integer(arg, value(), 0, 10000)), a.cross_sweeps_given = true;
    else if (arg == "--starts")
      a.starts = int(parse_integer(arg, value(), 1, 100)), a.starts_given = true;
    else if (arg == "--restarts") a.restarts = int(parse_integer(arg, value(), 1, 100)), a.restarts_given = true;
    else if (arg == "--method") {
      const std::string& name = value();
      a.method = cmaps::parse_method(name);
      if (!a.method) throw UsageError("--method expects auto, sphere or partition, got '" + name + "'");
    }
    else if (arg.size() > 1 && arg[0] == '-') throw UsageError("unknown option '" + arg + "' (see cmaps --help)");
    else if (a.command.empty()) a.command = arg;
    else if (a.inputs.empty() || a.command == "consistent" || a.command == "intersurface" || a.command == "transfer")
      a.inputs.push_back(arg);
    else throw UsageError("unexpected argument '" + arg + "' (see cmaps --help)");
  }
  if (a.command.empty()) throw UsageError("missing command (see cmaps --help)");
  if (a.command != "check" && a.command != "sphere" && a.command != "constrained" && a.command != "consistent" &&
      a.command != "intersurface" && a.command != "transfer")
    throw UsageError("unknown command '" + a.command + "' (see cmaps --help)");
  if (a.inputs.empty()) throw UsageError("missing input mesh (see cmaps --help)");
  a.input = a.inputs.front();
  if (a.command != "check" && a.output.empty())
    throw UsageError(a.command +
                     (a.command == "consistent" || a.command == "intersurface" ? " needs -o DIR"
                                                               : a.command == "transfer" ? " needs -o OUT.obj"
                                                                                         : " needs -o OUT") +
                     " (see cmaps --help)");
  if (a.command == "check" && !a.output.empty()) throw UsageError("check takes no -o");
  if (a.optimize_given && a.command != "intersurface" && a.command != "transfer")
    throw UsageError(a.command + " takes no --optimize (only intersurface and transfer do)");
  if (a.cross_sweeps_given && a.command != "intersurface" && a.command != "transfer")
    throw UsageError(a.command + " takes no --cross-sweeps (only intersurface and transfer do)");
  if (a.starts_given && a.command != "intersurface" && a.command != "transfer")
    throw UsageError(a.command + " takes no --starts (only intersurface and transfer do)");
  if (a.restarts_given && a.command != "intersurface" && a.command != "transfer" && a.command != "consistent")
    throw UsageError(a.command + " takes no --restarts (only consistent, intersurface and transfer do)");
  if (a.method && a.command != "intersurface" && a.command != "transfer")
    throw UsageError(a.command + " takes no --method (only intersurface and transfer do)");
  if (a.positions && a.command != "transfer") throw UsageError(a.command + " takes no --positions (only transfer does)");
  if (a.align && a.command != "consistent") throw UsageError(a.command + " takes no --align (only consistent does)");
  if (a.command != "consistent") {
    for (const auto& [option, given] : {std::pair<const char*, bool>{"--remesh", a.remesh_given},
                                        {"--grid", a.grid_given},
                                        {"--first", a.first_given}})
      if (given) throw UsageError(a.command + " takes no " + option + " (only consistent does)");
  }
  if (a.command == "consistent") {
    if (a.inputs.size() < 2)
      throw UsageError("consistent needs at least 2 input meshes, got " + std::to_string(a.inputs.size()));
    if (a.features.empty()) throw UsageError("consistent needs --features FILE (see cmaps --help)");
    if (a.remesh_given && a.remesh % 2 != 0)
      throw UsageError("--remesh expects an even resolution, got " + std::to_string(a.remesh));
    if (a.grid % 2 != 0) throw UsageError("--grid expects an even resolution, got " + std::to_string(a.grid));
    if (a.first_given && a.first >= int(a.inputs.size()))
      throw UsageError("--first " + std::to_string(a.first) + " is out of range (" + std::to_string(a.inputs.size()) +
                       " inputs, numbered from 0)");
    for (const auto& [option, given] : {std::pair<const char*, const std::string&>{"--targets", a.targets},
                                        {"--refined-mesh", a.refined_mesh}})
      if (!given.empty()) throw UsageError("consistent takes no " + std::string(option) + " (only constrained does)");
  } else if (a.command == "intersurface" || a.command == "transfer") {
    if (a.inputs.size() != 2)
      throw UsageError(a.command + " needs 2 input meshes (" +
                       (a.command == "transfer" ? "SOURCE TARGET" : "A B") + "), got " + std::to_string(a.inputs.size()));
    for (const auto& [option, given] : {std::pair<const char*, const std::string&>{"--targets", a.targets},
                                        {"--refined-mesh", a.refined_mesh}})
      if (!given.empty()) throw UsageError(a.command + " takes no " + std::string(option) + " (only constrained does)");
  } else if (a.command == "constrained") {
    if (a.features.empty()) throw UsageError("constrained needs --features FILE (see cmaps --help)");
  } else {
    for (const auto& [option, given] : {std::pair<const char*, const std::string&>{"--features", a.features},
                                        {"--targets", a.targets},
                                        {"--refined-mesh", a.refined_mesh}})
      if (!given.empty())
        throw UsageError(a.command + " takes no " + option +
                         (std::string(option) == "--features"
                              ? " (only constrained, consistent, intersurface and transfer do)"
                                                              : " (only constrained does)"));
  }
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

// Rejects an unusable output path before a long computation, not after it.
void check_output_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".obj" && ext != ".ply" && ext != ".off")
    throw UsageError("output '" + path + "' must end in .obj, .ply or .off");
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw cmaps::IoError("cannot write '" + path + "': directory '" + parent.string() + "' does not exist");
}

// Runs `compute(progress)` with progress on an interactive terminal, and
// clears the progress line however it ends.
template <class Compute>
auto with_terminal_progress(bool show, Compute&& compute) {
  try {
    auto result = compute(terminal_progress(show));
    if (show) std::fputs("\r\033[K", stderr);
    return result;
  } catch (...) {
    if (show) std::fputs("\r\033[K", stderr);
    throw;
  }
}

void run_sphere(const Arguments& args, Outcome& out) {
  check_output_path(args.output);

  cmaps::TriangleMesh mesh = cmaps::read_mesh(args.input);
  out.faces = int(mesh.triangles.size());
  out.json.add("vertices", int(mesh.vertices.size()));

  cmaps::SphereOptions options;
  options.seed = args.seed;
  options.effort = args.effort;
  options.threads = args.threads;
  const cmaps::SphereResult result =
      with_terminal_progress(!args.json && isatty(STDERR_FILENO), [&](const cmaps::ProgressCallback& progress) {
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

std::string in_quotes(const std::string& name) { return JsonObject::quote(name); }

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
      throw cmaps::InvalidInput(args.features + ": features " + in_quotes(it->second) + " and " + in_quotes(name) + " are both vertex " +
                                std::to_string(vertex));
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
    if (!(p.norm() > 0)) throw cmaps::InvalidInput(args.targets + ": target " + in_quotes(name) + " is the zero vector");
    c.targets.push_back(p);
  }
  // Same tolerance as the library, which would report indices instead of names.
  for (std::size_t i = 0; i < c.targets.size(); ++i)
    for (std::size_t j = i + 1; j < c.targets.size(); ++j)
      if ((c.targets[i].normalized() - c.targets[j].normalized()).norm() < 1e-9)
        throw cmaps::InvalidInput(args.targets + ": targets " + in_quotes(c.names[i]) + " and " + in_quotes(c.names[j]) +
                                  " are equal (after normalization)");
  return c;
}

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

  cmaps::SphereOptions options;
  options.seed = args.seed;
  options.effort = args.effort;
  options.threads = args.threads;
  const cmaps::ConstrainedResult result =
      with_terminal_progress(!args.json && isatty(STDERR_FILENO), [&](const cmaps::ProgressCallback& progress) {
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
      .add("automatic_targets", constraints.targets.empty())
      .add("seed", static_cast<unsigned long long>(args.seed))
      .add("effort", args.effort)
      .add("threads", args.threads)
      .add("output", args.output);
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

// ------------------------------------------------------------------ consistent

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

// Rejects an unusable output directory before a long computation: it must
// be a directory, or not exist yet in an existing directory.
void check_output_directory(const std::string& dir) {
  namespace fs = std::filesystem;
  if (fs::exists(dir)) {
    if (!fs::is_directory(dir)) throw cmaps::IoError("cannot write into '" + dir + "': it is not a directory");
    return;
  }
  const fs::path parent = fs::path(dir).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw cmaps::IoError("cannot create '" + dir + "': directory '" + parent.string() + "' does not exist");
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  file << text << '\n';
  if (!file) throw cmaps::IoError("cannot write '" + path + "'");
}

void run_consistent(const Arguments& args, Outcome& out) {
  out.consistent = true;
  check_output_directory(args.output);
  out.json.add("inputs_count", int(args.inputs.size())).add_json("inputs", JsonObject::array(args.inputs));
  const SetInput set = read_set(args, out);
  const std::vector<cmaps::ConsistentMember>& members = set.members;
  out.json.add("features", int(set.names.size()));

  cmaps::ConsistentOptions options;
  options.sphere.seed = args.seed;
  options.sphere.effort = args.effort;
  options.sphere.threads = args.threads;
  options.first = args.first;
  options.grid = args.grid;
  options.restarts = args.restarts;
  options.align = args.align;
  const cmaps::ConsistentResult result =
      with_terminal_progress(!args.json && isatty(STDERR_FILENO), [&](const cmaps::ProgressCallback& progress) {
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
      .add("seconds_compute", result.seconds)
      .add("seed", static_cast<unsigned long long>(args.seed))
      .add("effort", args.effort)
      .add("threads", args.threads)
      .add("output", args.output);

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

// ------------------------------------------------------------------ intersurface

// Feature pairs of `intersurface`: {"name": [index_in_A, index_in_B], ...},
// every name with a vertex on both meshes; ranges and repeats are checked by
// the library (by pair index), here with the name.
std::vector<cmaps::FeaturePair> read_feature_pairs(const Arguments& args, const cmaps::TriangleMesh& a,
                                                   const cmaps::TriangleMesh& b) {
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
  }
  return pairs;
}

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

// Options of the inter-surface map shared by intersurface and transfer.
cmaps::IntersurfaceOptions intersurface_options(const Arguments& args) {
  cmaps::IntersurfaceOptions options;
  options.sphere.seed = args.seed;
  options.sphere.effort = args.effort;
  options.sphere.threads = args.threads;
  options.optimize_rounds = args.optimize;
  if (args.optimize == 0) options.correspondence_weight = 0;  // the plain composition
  options.cross_sweeps = args.cross_sweeps;
  options.restarts = args.restarts;
  options.starts = args.starts;
  options.method = args.method.value_or(cmaps::IntersurfaceMethod::automatic);
  return options;
}

void run_intersurface(const Arguments& args, Outcome& out) {
  out.intersurface = true;
  check_output_directory(args.output);
  out.json.add_json("inputs", JsonObject::array(args.inputs));
  const cmaps::TriangleMesh a = cmaps::read_mesh(args.inputs[0]);
  const cmaps::TriangleMesh b = cmaps::read_mesh(args.inputs[1]);
  out.faces_per_input = JsonObject::array(std::vector<int>{int(a.triangles.size()), int(b.triangles.size())});
  const std::vector<cmaps::FeaturePair> features = read_feature_pairs(args, a, b);
  out.feature_count = int(features.size());

  const cmaps::IntersurfaceOptions options = intersurface_options(args);
  const cmaps::IntersurfaceResult result =
      with_terminal_progress(!args.json && isatty(STDERR_FILENO), [&](const cmaps::ProgressCallback& progress) {
        return cmaps::intersurface_map(a, b, features, options, progress);
      });
  if (result.a_to_b.size() != a.vertices.size() || result.b_to_a.size() != b.vertices.size())
    throw cmaps::Error("internal error: the inter-surface map returned " + std::to_string(result.a_to_b.size()) +
                       " and " + std::to_string(result.b_to_a.size()) + " images for " +
                       std::to_string(a.vertices.size()) + " and " + std::to_string(b.vertices.size()) + " vertices");

  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(args.output, error);
  if (error) throw cmaps::IoError("cannot create '" + args.output + "': " + error.message());
  const auto path = [&](const char* name) { return (fs::path(args.output) / name).string(); };
  const std::vector<std::string> outputs{path("A_to_B.txt"), path("B_to_A.txt"), path("A_on_B.obj"),
                                         path("B_on_A.obj")};
  write_text(outputs[0], surface_points_text(result.a_to_b));
  write_text(outputs[1], surface_points_text(result.b_to_a));
  cmaps::write_mesh(outputs[2], cmaps::TriangleMesh{result.a_on_b, a.triangles});
  cmaps::write_mesh(outputs[3], cmaps::TriangleMesh{result.b_on_a, b.triangles});

  const cmaps::MapDistortion &ab = result.distortion_a_to_b, &ba = result.distortion_b_to_a;
  out.dirichlet = JsonObject::array(std::vector<double>{ab.symmetric_dirichlet, ba.symmetric_dirichlet});
  out.flips = JsonObject::array(std::vector<int>{ab.flipped, ba.flipped});
  out.efficiencies = JsonObject::array(std::vector<double>{result.efficiency_a, result.efficiency_b});
  out.steiner_per_mesh = JsonObject::array(std::vector<int>{result.steiner_a, result.steiner_b});
  std::string added = "[";
  for (std::size_t k = features.size(); k < result.features.size(); ++k)
    added += std::string(k > features.size() ? ", " : "") + JsonObject::array(std::vector<int>{
                                                                 result.features[k].a, result.features[k].b});
  out.added_features = added + "]";
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
      .add("seconds_compute", result.seconds)
      .add("seed", static_cast<unsigned long long>(args.seed))
      .add("effort", args.effort)
      .add("threads", args.threads)
      .add("output", args.output);

  char line[320];
  std::snprintf(line, sizeof line,
                "%zu feature pairs (%d added), symmetric Dirichlet %.4f (A to B) / %.4f (B to A), %d / %d flipped, "
                "%d + %d Steiner vertices",
                result.features.size(), result.added_features, ab.symmetric_dirichlet, ba.symmetric_dirichlet,
                ab.flipped, ba.flipped, result.steiner_a, result.steiner_b);
  out.summary = "wrote " + std::to_string(outputs.size()) + " files to " + args.output + ": " + line;
}

// ------------------------------------------------------------------ transfer

void run_transfer(const Arguments& args, Outcome& out) {
  out.intersurface = out.transfer = true;
  check_output_path(args.output);
  std::string ext = std::filesystem::path(args.output).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".obj") throw UsageError("transfer writes OBJ: output '" + args.output + "' must end in .obj");
  out.json.add_json("inputs", JsonObject::array(args.inputs));
  const std::string &source_path = args.inputs[0], &target_path = args.inputs[1];
  const cmaps::TriangleMesh source = cmaps::read_mesh(source_path);
  const cmaps::TriangleMesh target = cmaps::read_mesh(target_path);
  out.faces_per_input = JsonObject::array(std::vector<int>{int(source.triangles.size()), int(target.triangles.size())});
  std::string source_ext = std::filesystem::path(source_path).extension().string();
  std::transform(source_ext.begin(), source_ext.end(), source_ext.begin(), [](unsigned char c) { return std::tolower(c); });
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
      with_terminal_progress(!args.json && isatty(STDERR_FILENO), [&](const cmaps::ProgressCallback& progress) {
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
  const cmaps::MapDistortion &ts = map.distortion_a_to_b, &st = map.distortion_b_to_a;
  out.dirichlet = JsonObject::array(std::vector<double>{st.symmetric_dirichlet, ts.symmetric_dirichlet});
  out.flips = JsonObject::array(std::vector<int>{st.flipped, ts.flipped});
  out.efficiencies = JsonObject::array(std::vector<double>{map.efficiency_b, map.efficiency_a});
  out.steiner_per_mesh = JsonObject::array(std::vector<int>{map.steiner_b, map.steiner_a});
  std::string added = "[";
  for (std::size_t k = features.size(); k < map.features.size(); ++k)
    added += std::string(k > features.size() ? ", " : "") +
             JsonObject::array(std::vector<int>{map.features[k].b, map.features[k].a});
  out.added_features = added + "]";
  out.outputs = JsonObject::array(std::vector<std::string>{args.output});
  out.json.add("genus", map.genus)
      .add("method", cmaps::method_name(map.method))
      .add("seconds_compute", map.seconds)
      .add("seed", static_cast<unsigned long long>(args.seed))
      .add("effort", args.effort)
      .add("threads", args.threads)
      .add("output", args.output);

  std::string what;
  for (const std::string& name : transferred) what += (what.empty() ? "" : ", ") + name;
  char line[256];
  std::snprintf(line, sizeof line, " through %zu feature pairs (%d added), symmetric Dirichlet %.4f (target onto source)",
                map.features.size(), map.added_features, ts.symmetric_dirichlet);
  out.summary = "wrote " + args.output + ": " + what + " of " + source_path + " on " + target_path + line;
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
