#include "consistent/member_alignment.h"

#include "consistent_maps/spherical_parameterization.h"
#include "consistent/parameterize_with_reference.h"
#include "intersurface/sphere_pair.h"

namespace cmaps {
namespace {

// Weight of the consistency term (sets/cactus, 8 features, three passes, no
// efficiency floor; seeds 1 / 4 / 7: 0.5 gave 1.66 / 2.12 / 2.64 % mean
// ground-truth error, 0.12 gave 1.59 / 2.02 / 2.33 % and kept more
// efficiency; 0.06 on seeds 4 / 7: 2.57 / 2.91 %).
constexpr double kConsistencyWeight = 0.12;
// Passes over the members whose map the previous pass changed (sets/cactus,
// weight 0.5: 1.85 / 1.70 / 1.66 % mean error after 1 / 2 / 3; a member
// left unchanged would be refitted exactly alike again).
constexpr int kPasses = 3;
// A refit must keep this share of the efficiency of the member's own
// unconstrained map (the set's target is 85 %; a refit along the own map
// can wind around the features the other way and keep only 64 %).
constexpr double kEfficiencyKept = 0.85;

}  // namespace

void align_members(const std::vector<ConsistentMember>& members, ConsistentResult& result,
                   const ConsistentOptions& options, const ProgressCallback& progress) {
  const int n = int(members.size()), r = result.first, threads = options.sphere.threads;
  const TriangleMesh& reference = members[r].mesh;
  const ConstrainedResult& reference_map = result.members[r];
  if (reference_map.holes > 0) return;
  const ParameterizedSurface on_sphere = parameterized_surface(reference, reference_map);
  const ReferenceMap towards{&on_sphere.surface, &on_sphere.sphere, kConsistencyWeight};
  std::vector<char> open(n, 0);
  std::vector<double> energy(n, 0);  // of each member's map against the reference's
  std::vector<double> least_efficiency(n, 0);  // a refit may keep no less
  for (int j = 0; j < n; ++j) {
    open[j] = j != r && result.members[j].holes == 0;
    if (!open[j]) continue;
    energy[j] = composition_dirichlet(members[j].mesh, result.members[j], reference, reference_map, threads);
    const double own = spherical_parameterization(members[j].mesh, options.sphere).report.efficiency;
    least_efficiency[j] = kEfficiencyKept * own;
  }
  for (int pass = 0; pass < kPasses; ++pass) {
    for (int j = 0; j < n; ++j) {
      if (!open[j]) continue;
      open[j] = 0;
      ConstrainedResult& map = result.members[j];
      const std::vector<Vec3> current = map.sphere;
      // Along the member's own map (nullptr) once: later passes would repeat it exactly.
      std::vector<const std::vector<Vec3>*> guides{&current};
      if (pass == 0) guides.insert(guides.begin(), nullptr);
      for (std::size_t attempt = 0; attempt < guides.size(); ++attempt) {
        const std::vector<Vec3>* guide = guides[attempt];
        ProgressCallback share;
        if (progress)
          share = [&, j, pass, attempt](double f, const std::string& stage) {
            return progress((pass + (j + (attempt + f) / guides.size()) / n) / kPasses, stage);
          };
        ConstrainedResult refit =
            parameterize_to_locations(members[j], result.feature_locations, options.sphere, share, towards, guide);
        const double e = composition_dirichlet(members[j].mesh, refit, reference, reference_map, threads);
        if (e < energy[j] && refit.report.efficiency >= least_efficiency[j])
          energy[j] = e, map = std::move(refit), open[j] = 1;
      }
    }
  }
}

}  // namespace cmaps
