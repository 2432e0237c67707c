// Point location throughput on a ~100k-face spherical parameterization:
// 1M random directions located on one and on two threads; then closest
// points on the mesh itself (SurfaceLocator, what a pair's normal-map bake
// asks per pixel): 1M points near the surface (vertices moved by up to 2 %
// of the diagonal) and 1M points anywhere in the box around it.
// Usage: locate_benchmark [mesh] (default: the shared large/gargoyle.off)
#include <chrono>
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <random>

#include "consistent_maps/mesh_io.h"
#include "consistent_maps/sphere_locator.h"
#include "consistent_maps/spherical_parameterization.h"
#include "consistent_maps/surface_locator.h"

using namespace cmaps;

static double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : CMAPS_SHARED_MESHES "/large/gargoyle.off";
  const TriangleMesh mesh = read_mesh(path);
  auto start = std::chrono::steady_clock::now();
  const SphereResult param = spherical_parameterization(mesh);
  const double param_seconds = seconds_since(start);

  start = std::chrono::steady_clock::now();
  const SphereLocator locator(param.sphere, mesh.triangles);
  const double build_seconds = seconds_since(start);

  std::mt19937 rng(1);
  std::normal_distribution<double> normal;
  std::vector<Vec3> queries(1000000);
  for (Vec3& q : queries) q = Vec3(normal(rng), normal(rng), normal(rng)).normalized();

  // Wall-clock rates, and rates per CPU second (what one core does when the
  // machine is shared); best of three runs each.
  struct Rate {
    double wall = 0, cpu = 0;
  };
  auto measure = [&](auto&& run) {
    Rate best;
    for (int repeat = 0; repeat < 3; ++repeat) {
      const std::clock_t cpu_start = std::clock();
      start = std::chrono::steady_clock::now();
      run();
      best.wall = std::max(best.wall, queries.size() / seconds_since(start));
      best.cpu = std::max(best.cpu, queries.size() / (double(std::clock() - cpu_start) / CLOCKS_PER_SEC));
    }
    return best;
  };
  std::vector<SphereLocation> found(queries.size());
  const Rate single = measure([&] {
    for (size_t q = 0; q < queries.size(); ++q) found[q] = locator.locate(queries[q]);
  });
  const Rate one = measure([&] { found = locator.locate_all(queries, 1); });
  const Rate two = measure([&] { found = locator.locate_all(queries, 2); });

  std::printf("| mesh | faces | param s | locator build s | locate() loop M/s (per CPU s) "
              "| locate_all 1 thread M/s (per CPU s) | locate_all 2 threads M/s (per CPU s) |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  std::printf("| %s | %zu | %.2f | %.3f | %.2f (%.2f) | %.2f (%.2f) | %.2f (%.2f) |\n", path.c_str(),
              mesh.triangles.size(), param_seconds, build_seconds, single.wall / 1e6, single.cpu / 1e6,
              one.wall / 1e6, one.cpu / 1e6, two.wall / 1e6, two.cpu / 1e6);

  start = std::chrono::steady_clock::now();
  const SurfaceLocator surface(mesh.vertices, mesh.triangles);
  const double surface_build_seconds = seconds_since(start);
  Vec3 low = mesh.vertices[0], high = low;
  for (const Vec3& v : mesh.vertices) low = low.cwiseMin(v), high = high.cwiseMax(v);
  const double diagonal = (high - low).norm();
  std::uniform_real_distribution<double> unit(0, 1);
  std::uniform_int_distribution<std::size_t> vertex(0, mesh.vertices.size() - 1);
  for (Vec3& q : queries) {
    const Vec3 direction = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    q = mesh.vertices[vertex(rng)] + 0.02 * diagonal * unit(rng) * direction;
  }
  std::vector<SurfaceLocation> nearest;
  const Rate near_one = measure([&] { nearest = surface.locate_all(queries, 1); });
  const Rate near_two = measure([&] { nearest = surface.locate_all(queries, 2); });
  for (Vec3& q : queries) q = low + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(high - low);
  const Rate box_one = measure([&] { nearest = surface.locate_all(queries, 1); });
  std::printf("\n| mesh | faces | surface locator build s | near the surface, 1 thread M/s (per CPU s) "
              "| near, 2 threads M/s (per CPU s) | anywhere in the box, 1 thread M/s (per CPU s) |\n");
  std::printf("|---|---|---|---|---|---|\n");
  std::printf("| %s | %zu | %.3f | %.2f (%.2f) | %.2f (%.2f) | %.2f (%.2f) |\n", path.c_str(), mesh.triangles.size(),
              surface_build_seconds, near_one.wall / 1e6, near_one.cpu / 1e6, near_two.wall / 1e6, near_two.cpu / 1e6,
              box_one.wall / 1e6, box_one.cpu / 1e6);
  return 0;
}
