// Inter-surface maps between two meshes of the same genus.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "consistent_maps/intersurface_map.h"
#include "consistent_maps/pair_remesh.h"
#include "conversions.h"
#include "python_progress.h"

namespace cmaps::python {

namespace py = pybind11;

namespace {

// (k, 2) integer pairs [index_in_A, index_in_B]; empty lists are allowed. The
// library checks the ranges and repeats.
std::vector<cmaps::FeaturePair> to_feature_pairs(const py::handle& data) {
  const py::array array = as_array(data, "feature_pairs");
  if (array.size() == 0 && (array.ndim() == 1 || (array.ndim() == 2 && array.shape(1) == 2))) return {};
  const auto pairs = to_integers(array, "feature_pairs");
  if (pairs.ndim() != 2 || pairs.shape(1) != 2)
    raise(PyExc_ValueError, "feature_pairs must have shape (k, 2), got " + shape_of(pairs));
  const auto p = pairs.unchecked<2>();
  std::vector<cmaps::FeaturePair> result(p.shape(0));
  const auto index = [](std::int64_t v) { return int(std::clamp<std::int64_t>(v, -1, 1LL << 30)); };
  for (py::ssize_t k = 0; k < p.shape(0); ++k) result[k] = {index(p(k, 0)), index(p(k, 1))};
  return result;
}

// Per source vertex: (triangles (n,) int32, barycentric (n, 3) float64).
std::pair<py::array_t<std::int32_t>, py::array_t<double>> surface_point_arrays(
    const std::vector<cmaps::SurfacePoint>& points) {
  std::vector<int> triangles(points.size());
  py::array_t<double> barycentric({py::ssize_t(points.size()), py::ssize_t(3)});
  auto b = barycentric.mutable_unchecked<2>();
  for (std::size_t i = 0; i < points.size(); ++i) {
    triangles[i] = points[i].triangle;
    for (int k = 0; k < 3; ++k) b(i, k) = points[i].barycentric[k];
  }
  return {to_numpy(triangles), barycentric};
}

py::dict intersurface_map(const py::handle& mesh_a, const py::handle& mesh_b, const py::handle& pairs_data, int grid,
                          int optimize, int restarts, bool corner_images, int balance_rounds, int cross_sweeps,
                          int cross_turns,                           int starts, const std::string& method,
                          std::uint64_t seed, int effort, int threads, const py::object& progress) {
  cmaps::IntersurfaceOptions options;
  const std::optional<cmaps::IntersurfaceMethod> chosen = cmaps::parse_method(method);
  if (!chosen) raise(PyExc_ValueError, "method must be 'auto', 'sphere' or 'partition', got '" + method + "'");
  options.method = *chosen;
  options.corner_images = corner_images;
  if (balance_rounds < 0)
    raise(PyExc_ValueError, "balance_rounds must be at least 0, got " + std::to_string(balance_rounds));
  options.balance_rounds = balance_rounds;
  if (cross_sweeps < 0) raise(PyExc_ValueError, "cross_sweeps must be at least 0, got " + std::to_string(cross_sweeps));
  options.cross_sweeps = cross_sweeps;
  if (cross_turns < 1) raise(PyExc_ValueError, "cross_turns must be at least 1, got " + std::to_string(cross_turns));
  options.cross_turns = cross_turns;
  if (optimize < 0) raise(PyExc_ValueError, "optimize must be at least 0, got " + std::to_string(optimize));
  if (restarts < 1) raise(PyExc_ValueError, "restarts must be at least 1, got " + std::to_string(restarts));
  options.restarts = restarts;
  if (starts < 1) raise(PyExc_ValueError, "starts must be at least 1, got " + std::to_string(starts));
  options.starts = starts;
  options.optimize_rounds = optimize;
  if (optimize == 0) options.correspondence_weight = 0;  // the plain composition
  options.sphere = sphere_options(seed, effort, threads, progress);
  require_grid_resolution(grid, "grid");
  options.grid = grid;
  const cmaps::TriangleMesh a = to_mesh_pair(mesh_a, "mesh_a"), b = to_mesh_pair(mesh_b, "mesh_b");
  const std::vector<cmaps::FeaturePair> pairs = to_feature_pairs(pairs_data);
  const auto [result, seconds] = run_released(progress, [&](const cmaps::ProgressCallback& callback) {
    return cmaps::intersurface_map(a, b, pairs, options, callback);
  });

  py::dict d;
  // Points on a mesh as '<name>_triangle' (n,) and '<name>_barycentric' (n, 3).
  const auto put = [&d](const std::string& name, const std::vector<cmaps::SurfacePoint>& points) {
    const auto [triangles, barycentric] = surface_point_arrays(points);
    d[(name + "_triangle").c_str()] = triangles;
    d[(name + "_barycentric").c_str()] = barycentric;
  };
  put("a_to_b", result.a_to_b);
  put("b_to_a", result.b_to_a);
  if (corner_images) {
    put("a_corners_to_b", result.a_corners_to_b);
    put("b_corners_to_a", result.b_corners_to_a);
  }
  d["a_on_b"] = to_numpy(result.a_on_b);
  d["b_on_a"] = to_numpy(result.b_on_a);
  py::array_t<std::int32_t> features({py::ssize_t(result.features.size()), py::ssize_t(2)});
  auto f = features.mutable_unchecked<2>();
  for (std::size_t k = 0; k < result.features.size(); ++k)
    f(k, 0) = result.features[k].a, f(k, 1) = result.features[k].b;
  d["features"] = features;
  d["added_features"] = result.added_features;
  d["genus"] = result.genus;
  d["method"] = cmaps::method_name(result.method);
  const auto computed = [](double median) {
    return median < 0 ? py::object(py::none()) : py::object(py::float_(median));
  };
  d["sphere_median_dirichlet"] = computed(result.sphere_median_dirichlet);
  d["partition_median_dirichlet"] = computed(result.partition_median_dirichlet);
  const cmaps::MapDistortion &ab = result.distortion_a_to_b, &ba = result.distortion_b_to_a;
  d["symmetric_dirichlet"] = py::make_tuple(ab.symmetric_dirichlet, ba.symmetric_dirichlet);
  d["flipped"] = py::make_tuple(ab.flipped, ba.flipped);
  d["degenerate"] = py::make_tuple(ab.degenerate, ba.degenerate);
  d["sphere_flipped"] = result.sphere_flipped;
  d["map_flipped"] = result.map_flipped;
  d["refitted"] = py::make_tuple(result.refitted_a, result.refitted_b);
  d["balanced_patches"] = result.balanced_patches;
  d["patch_area_ratio"] = result.patch_area_ratio;
  d["a_along_paths"] = py::array_t<std::int8_t>(result.a_along_paths.size(), result.a_along_paths.data());
  d["b_along_paths"] = py::array_t<std::int8_t>(result.b_along_paths.size(), result.b_along_paths.data());
  d["moved"] = result.a_along_paths.empty() ? py::object(py::none()) : py::object(py::str(result.moved_b ? "B" : "A"));
  d["stretch_efficiency"] = py::make_tuple(result.efficiency_a, result.efficiency_b);
  d["steiner"] = py::make_tuple(result.steiner_a, result.steiner_b);
  d["restart_dirichlet"] = to_numpy(result.restart_dirichlet);
  d["restart_median_dirichlet"] = to_numpy(result.restart_median_dirichlet);
  d["restart_flipped"] = py::array_t<int>(result.restart_flipped.size(), result.restart_flipped.data());
  d["start_median_dirichlet"] = to_numpy(result.start_median_dirichlet);
  d["median_symmetric_dirichlet"] = py::make_tuple(ab.median_symmetric_dirichlet, ba.median_symmetric_dirichlet);
  d["seconds"] = seconds;
  d["base_vertices"] = result.base_vertices;
  d["base_triangles"] = result.base_triangles;
  d["seconds_features"] = result.seconds_features;
  d["composition_dirichlet"] = py::make_tuple(result.composition_a_to_b.symmetric_dirichlet,
                                              result.composition_b_to_a.symmetric_dirichlet);
  d["seconds_partition"] = result.seconds_partition;
  d["seconds_parameterize"] = result.seconds_parameterize;
  d["seconds_optimize"] = result.seconds_optimize;
  d["seconds_locate"] = result.seconds_locate;
  d["seconds_measure"] = result.seconds_measure;
  return d;
}

// A (triangles (n,), barycentric (n, 3)) pair: each of n points on `mesh`'s triangles.
std::vector<cmaps::SurfacePoint> to_surface_points(const py::handle& data, const cmaps::TriangleMesh& mesh,
                                                   const std::string& name) {
  const py::tuple pair = py::cast<py::tuple>(data);
  if (pair.size() != 2) raise(PyExc_ValueError, name + " must be (triangles, barycentric)");
  const std::vector<int> triangles =
      to_index_vector(pair[0], (name + " triangles").c_str(), std::int64_t(mesh.triangles.size()));
  const std::vector<cmaps::Vec3> weights = to_points(pair[1], (name + " barycentric").c_str());
  if (weights.size() != triangles.size())
    raise(PyExc_ValueError, name + " has " + std::to_string(weights.size()) + " barycentric rows for " +
                                std::to_string(triangles.size()) + " triangles");
  std::vector<cmaps::SurfacePoint> points(triangles.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = {triangles[i], {weights[i].x(), weights[i].y(), weights[i].z()}};
  return points;
}

py::dict remesh_pair(const py::handle& mesh_a, const py::handle& mesh_b, const py::handle& a_to_b_data,
                     const py::handle& b_to_a_data, const py::handle& pairs_data, int target_vertices) {
  const cmaps::TriangleMesh a = to_mesh_pair(mesh_a, "mesh_a"), b = to_mesh_pair(mesh_b, "mesh_b");
  const std::vector<cmaps::SurfacePoint> a_to_b = to_surface_points(a_to_b_data, b, "a_to_b");
  const std::vector<cmaps::SurfacePoint> b_to_a = to_surface_points(b_to_a_data, a, "b_to_a");
  const std::vector<cmaps::FeaturePair> pairs = to_feature_pairs(pairs_data);
  cmaps::PairRemesh remesh;
  {
    py::gil_scoped_release release;
    remesh = cmaps::remesh_pair(a, b, a_to_b, b_to_a, pairs, target_vertices);
  }
  py::dict d;
  d["b_carries"] = remesh.b_carries;
  d["carrier_vertex"] = to_numpy(remesh.carrier_vertex);
  d["triangles"] = to_numpy(remesh.triangles);
  d["a_positions"] = to_numpy(remesh.a_positions);
  d["b_positions"] = to_numpy(remesh.b_positions);
  d["feature_vertices"] = to_numpy(remesh.feature_vertices);
  d["folded_triangles"] = remesh.folded_triangles;
  return d;
}

py::dict map_distortion(const py::handle& source_mesh, const py::handle& target_mesh, const py::handle& image_data) {
  const cmaps::TriangleMesh source = to_mesh_pair(source_mesh, "source"), target = to_mesh_pair(target_mesh, "target");
  const std::vector<cmaps::SurfacePoint> image = to_surface_points(image_data, target, "image");
  cmaps::TriangleDistortion distortion;
  {
    py::gil_scoped_release release;
    distortion = cmaps::triangle_distortion(source, target, image);
  }
  py::dict d;
  d["symmetric_dirichlet"] = to_numpy(distortion.symmetric_dirichlet);
  py::array_t<bool> flipped(distortion.flipped.size());
  std::copy(distortion.flipped.begin(), distortion.flipped.end(), flipped.mutable_data());
  d["flipped"] = flipped;
  d["area"] = to_numpy(distortion.area);
  const cmaps::MapDistortion summary = cmaps::summarize(distortion);
  d["mean"] = summary.symmetric_dirichlet;
  d["median"] = summary.median_symmetric_dirichlet;
  d["folded"] = summary.flipped;
  return d;
}

}  // namespace

void bind_intersurface(py::module_& m) {
  m.def("intersurface_map", &intersurface_map, py::arg("mesh_a"), py::arg("mesh_b"),
        py::arg("feature_pairs") = py::list(), py::kw_only(), py::arg("grid") = 64,
        py::arg("optimize") = cmaps::IntersurfaceOptions{}.optimize_rounds,
        py::arg("restarts") = 1, py::arg("corner_images") = false, py::arg("balance_rounds") = 4,
        py::arg("cross_sweeps") = cmaps::IntersurfaceOptions{}.cross_sweeps,
        py::arg("cross_turns") = cmaps::IntersurfaceOptions{}.cross_turns,
        py::arg("starts") = cmaps::IntersurfaceOptions{}.starts,
        py::arg("method") = "auto", py::arg("seed") = 1, py::arg("effort") = 1, py::arg("threads") = 2,
        py::arg("progress") = py::none(),
        "Inter-surface map between two meshes of equal genus, closed or with as many holes (genus >= 1:\n"
        "through a consistent partition into triangular patches, 'base_vertices' and 'base_triangles' of its\n"
        "base mesh, 'seconds_partition'; genus 0: method 'sphere' through a consistent spherical\n"
        "parameterization of both, 'partition' directly as for genus >= 1, 'auto' both, keeping the lower\n"
        "summed median distortion; 'method' says which was kept, 'sphere_median_dirichlet' and\n"
        "'partition_median_dirichlet' the summed medians of the maps computed, None for one not). "
        "mesh_a, mesh_b: (vertices, triangles); feature_pairs: (k, 2)\n"
        "[vertex of A, vertex of B], mapped exactly onto each other (fewer than 3: pairs are added\n"
        "automatically up to 4). Returns a dict: 'a_to_b_triangle' (nA,) int32 and 'a_to_b_barycentric'\n"
        "(nA, 3): each vertex of A on an input triangle of B with weights w.r.t. its corners; likewise\n"
        "'b_to_a_*'; with corner_images, also 'a_corners_to_b_triangle' (3 mA,) int32 and\n"
        "'a_corners_to_b_barycentric' (3 mA, 3): row 3 t + k, the image on B of the point of A's triangle t\n"
        "next to its corner k (1e-3 of the way towards the other two), so per-corner values (UVs) are taken\n"
        "from the corner's own side of a seam; likewise 'b_corners_to_a_*' (3 mB rows);\n"
        "'a_on_b' (nA, 3), 'b_on_a' (nB, 3) the mapped positions; 'features' (k', 2) the pairs\n"
        "used (given, then added), 'added_features'; per direction (A to B, B to A) 'symmetric_dirichlet'\n"
        "(area-normalized, optimum 4, each source triangle mapped linearly onto its corners' images),\n"
        "'flipped', 'degenerate', and 'composition_dirichlet' before the distortion optimization (optimize:\n"
        "its rounds, 0 = no optimization: for genus 0 the plain composition of the spherical maps; the\n"
        "direct map's optimization also moves vertices across the partition's paths, A's then B's and so on,\n"
        "cross_turns turns of at most cross_sweeps sweeps, 0 sweeps = the paths stay walls);\n"
        "'median_symmetric_dirichlet' (the median triangle's; the mean is dominated by a few triangles);\n"
        "'restart_dirichlet', 'restart_median_dirichlet' and 'restart_flipped', the energies and\n"
        "folded samples (both directions summed) of each of the `restarts` maps through the sphere (restart k:\n"
        "layout k % 3 of single pass, carried guides, aligned; seed + k // 3); the least distorted is returned\n"
        "(the lowest summed median; medians within 5 % of each other: the fewer folded samples, 'flipped', if\n"
        "the counts differ by over 0.5 % of the triangles); the direct map (any genus) is computed from A's\n"
        "side and from B's side, for a pair without feature_pairs and holes from the least distorted of\n"
        "`starts` automatic first pairs each mapped with its patches' areas matched, before the local sweeps\n"
        "('start_median_dirichlet': their summed medians; with restarts > 1 that many of them optimized, also\n"
        "reported in 'restart_*'),\n"
        "and method 'auto' computes both maps, each time keeping the less distorted\n"
        "(method 'auto': a tie that folds do not break goes to the direct map);\n"
        "'refitted' (genus 0): whether A's map, then B's, was refitted against the other's (kept only when\n"
        "that lowers the medians);\n"
        "'balanced_patches' (genus >= 1): whether the map went through the partition with its paths moved to\n"
        "balance corresponding patches' areas (balance_rounds rounds, 0 = not tried; kept only when less\n"
        "distorted, as for method), 'patch_area_ratio': the largest ratio of a patch's "
        "shares of A's and B's area in the partition used;\n"
        "'a_along_paths' (mA,) and 'b_along_paths' (mB,) int8, the direct map kept (else empty): where each\n"
        "input triangle lies against the partition's paths, 0 away, 1 a corner on a path, 2 cut by one\n"
        "(the direct map's distortion and folds gather there); 'moved': 'A' or 'B', the mesh whose vertices the\n"
        "direct map's optimization moved first over the other's embedding (None for the sphere's map);\n"
        "'sphere_flipped', 'stretch_efficiency' and 'steiner' of the two spherical maps (genus 0);\n"
        "'map_flipped': the map's own folds, 0 when it is bijective as computed ('flipped' counts those of the\n"
        "vertex sampling): through the sphere 'sphere_flipped', directly the triangles of A and of B turned\n"
        "over in their patches' embeddings and B's vertices outside the triangle of A said to hold them;\n"
        "'seconds' and per stage. Raises InvalidMeshError for different genus,\n"
        "non-manifold meshes or bad pairs, Cancelled when progress returns False.");
  m.def("map_distortion", &map_distortion, py::arg("source"), py::arg("target"), py::arg("image"),
        "Where a map of source onto target distorts, per source triangle (what intersurface_map's\n"
        "'symmetric_dirichlet' and 'flipped' summarize): source, target: (vertices, triangles); image:\n"
        "(triangles (n,), barycentric (n, 3)), each source vertex on target's triangles (intersurface_map's\n"
        "'a_to_b_triangle', 'a_to_b_barycentric'). Returns a dict of (m,) arrays per source triangle:\n"
        "'symmetric_dirichlet' (the triangle mapped linearly onto its corners' images, target scaled to\n"
        "source's area; optimum 4, inf for a degenerate image, nan for a zero-area triangle), 'flipped'\n"
        "(bool: the image faces against target there) and 'area'; and what intersurface_map reports of them:\n"
        "'mean' (area-weighted, degenerate images left out), 'median' and 'folded'. Raises IndexError for\n"
        "image triangles out of range, InvalidMeshError (a ValueError) for a count of images other than\n"
        "source's vertices or meshes that are no manifold, consistently oriented surfaces.");
  m.def("remesh_pair", &remesh_pair, py::arg("mesh_a"), py::arg("mesh_b"), py::arg("a_to_b"), py::arg("b_to_a"),
        py::arg("feature_pairs"), py::arg("target_vertices"),
        "Consistent remeshes of two meshes mapped onto each other (any genus, holes kept): one mesh (the\n"
        "carrier) simplified to target_vertices, or as far as collapses go without folding a triangle on\n"
        "either surface, by collapses judged on both it and its image on the other, so the two remeshes share\n"
        "one connectivity; A and B each carry once, the remesh with fewer folded triangles is kept.\n"
        "mesh_a, mesh_b: (vertices, triangles); a_to_b: (triangles (nA,), barycentric (nA, 3)), each vertex of\n"
        "A on B's triangles (intersurface_map's 'a_to_b_triangle', 'a_to_b_barycentric'), b_to_a likewise;\n"
        "feature_pairs (k, 2): [vertex of A, vertex of B] kept. Returns a dict: 'b_carries' (whose vertices\n"
        "the remesh's are), 'carrier_vertex' (v,) int32, the carrier's vertex each remesh vertex is;\n"
        "'triangles' (f, 3); 'a_positions' and 'b_positions' (v, 3), on A and on B; 'feature_vertices' (k,),\n"
        "the remesh vertex of each pair; 'folded_triangles', those facing against the surface they lie on.\n"
        "Raises InvalidMeshError for a mesh that is not one manifold, consistently oriented surface, a\n"
        "feature out of range or a target below 4. Releases the GIL.");
}

}  // namespace cmaps::python
