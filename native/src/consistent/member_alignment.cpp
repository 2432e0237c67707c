#include "consistent/member_alignment.h"

#include "consistent/parameterize_with_reference.h"
#include "intersurface/sphere_pair.h"

namespace cmaps {
namespace {

// Weight of the consistency term (sets/cactus, 8 features: 0.1 / 0.25 / 0.5
// gave 2.4 / 2.0 / 1.9 % mean ground-truth error).
constexpr double kConsistencyWeight = 0.5;

}  // namespace

void align_members(const std::vector<ConsistentMember>& members, ConsistentResult& result,
                   const ConsistentOptions& options, const ProgressCallback& progress) {
  const int n = int(members.size()), r = result.first, threads = options.sphere.threads;
  const TriangleMesh& reference = members[r].mesh;
  const ConstrainedResult& reference_map = result.members[r];
  if (reference_map.holes > 0) return;
  const ParameterizedSurface on_sphere = parameterized_surface(reference, reference_map);
  const ReferenceMap towards{&on_sphere.surface, &on_sphere.sphere, kConsistencyWeight};
  for (int j = 0, done = 0; j < n; ++j) {
    ConstrainedResult& map = result.members[j];
    if (j == r || map.holes > 0) continue;
    double energy = composition_dirichlet(members[j].mesh, map, reference, reference_map, threads);
    const std::vector<Vec3> current = map.sphere;
    int attempt = 0;
    for (const std::vector<Vec3>* guide : {static_cast<const std::vector<Vec3>*>(nullptr), &current}) {
      ProgressCallback share;
      if (progress)
        share = [&, attempt](double f, const std::string& stage) {
          return progress((done + (attempt + f) / 2) / (n - 1), stage);
        };
      ConstrainedResult refit =
          parameterize_to_locations(members[j], result.feature_locations, options.sphere, share, towards, guide);
      const double e = composition_dirichlet(members[j].mesh, refit, reference, reference_map, threads);
      if (e < energy) energy = e, map = std::move(refit);
      ++attempt;
    }
    ++done;
  }
}

}  // namespace cmaps
