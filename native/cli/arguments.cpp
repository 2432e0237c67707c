#include "arguments.h"

#include <exception>

namespace cmaps::cli {

const char* const kUsage = R"(usage:
  cmaps check IN [--json]
  cmaps sphere IN -o OUT [--seed N] [--effort 0|1|2] [--threads N] [--json]
  cmaps constrained IN --features FILE [--targets FILE] -o OUT [--refined-mesh PATH]
                    [--seed N] [--effort 0|1|2] [--threads N] [--json]
  cmaps consistent IN IN ... --features FILE -o DIR [--remesh N] [--grid N] [--first K] [--restarts K]
                   [--align] [--seed N] [--effort 0|1|2] [--threads N] [--json]
  cmaps intersurface A B [--features FILE] -o DIR [--remesh N] [--method auto|sphere|partition] [--optimize R]
                     [--cross-sweeps N] [--cross-turns T] [--restarts K] [--starts S] [--seed N]
                     [--effort 0|1|2] [--threads N] [--json]
  cmaps transfer SOURCE TARGET [--features FILE] -o OUT.obj [--positions] [--method auto|sphere|partition]
                 [--optimize R] [--cross-sweeps N] [--cross-turns T] [--restarts K] [--starts S] [--seed N]
                 [--effort 0|1|2] [--threads N] [--json]
  cmaps --help | --version

commands:
  check    read IN (.obj .off .ply .stl), print its topology and exit 0 if it
           can be mapped to the sphere (one closed, manifold, consistently
           oriented genus-0 surface); otherwise exit 1 naming the defect, and
           say whether `intersurface` takes it (any genus, holes allowed).
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
           balanced_patches, patch_area_ratio). With --remesh N also
           DIR/A_remesh.obj and DIR/B_remesh.obj, consistent remeshes of
           N^2 + 2 vertices sharing one connectivity (one mesh simplified,
           its vertices' images on the other giving the other's; JSON:
           remesh_carrier, remesh_folded), and DIR/remesh_features.json.
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
  --remesh N         consistent: remeshes on the octahedral grid of resolution N
                     (even, 2..4096; N^2 + 2 vertices) and their geometry images;
                     intersurface: A and B simplified consistently to N^2 + 2
                     vertices (or as far as that goes without folding a
                     triangle): A's vertices or B's, whichever way folds less
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
  --cross-turns T    intersurface, transfer: the two meshes' vertices take T
                     turns crossing the paths, A's first, each against the
                     other's embedding as it is then (1..100, default
                     2; 1 = B's patches keep their straight paths)
  --starts S         intersurface, transfer: the direct map of a pair without
                     --features and without holes pairs the surfaces' handles
                     and parts as its automatic first pair decides (A's
                     vertex farthest from its centroid and B's nearest in
                     A's frame, or another of A's spread by farthest-point
                     sampling): S first pairs are each mapped with their
                     patches' areas matched but without the local sweeps,
                     and the least distorted one optimized
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
    else if (arg == "--cross-turns")
      a.cross_turns = int(parse_integer(arg, value(), 1, 100)), a.cross_turns_given = true;
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
  if (a.cross_turns_given && a.command != "intersurface" && a.command != "transfer")
    throw UsageError(a.command + " takes no --cross-turns (only intersurface and transfer do)");
  if (a.starts_given && a.command != "intersurface" && a.command != "transfer")
    throw UsageError(a.command + " takes no --starts (only intersurface and transfer do)");
  if (a.restarts_given && a.command != "intersurface" && a.command != "transfer" && a.command != "consistent")
    throw UsageError(a.command + " takes no --restarts (only consistent, intersurface and transfer do)");
  if (a.method && a.command != "intersurface" && a.command != "transfer")
    throw UsageError(a.command + " takes no --method (only intersurface and transfer do)");
  if (a.positions && a.command != "transfer")
    throw UsageError(a.command + " takes no --positions (only transfer does)");
  if (a.align && a.command != "consistent") throw UsageError(a.command + " takes no --align (only consistent does)");
  if (a.remesh_given && a.command != "consistent" && a.command != "intersurface")
    throw UsageError(a.command + " takes no --remesh (only consistent and intersurface do)");
  if (a.remesh_given && a.remesh % 2 != 0)
    throw UsageError("--remesh expects an even resolution, got " + std::to_string(a.remesh));
  if (a.command != "consistent") {
    for (const auto& [option, given] : {std::pair<const char*, bool>{"--grid", a.grid_given},
                                        {"--first", a.first_given}})
      if (given) throw UsageError(a.command + " takes no " + option + " (only consistent does)");
  }
  if (a.command == "consistent") {
    if (a.inputs.size() < 2)
      throw UsageError("consistent needs at least 2 input meshes, got " + std::to_string(a.inputs.size()));
    if (a.features.empty()) throw UsageError("consistent needs --features FILE (see cmaps --help)");
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
                       (a.command == "transfer" ? "SOURCE TARGET" : "A B") + "), got " +
                       std::to_string(a.inputs.size()));
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

}  // namespace cmaps::cli
