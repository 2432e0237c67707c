// Inter-surface maps between two meshes of the same genus (issue 5), closed
// or with as many holes on both:
// for every vertex of A its image on B (an input triangle of B and
// barycentric weights) and vice versa, with corresponding feature vertices
// mapped exactly onto each other.
//
// Genus 0: the composition through the common sphere. Both meshes get a
// consistent spherical parameterization (thesis 3.2) with the feature pairs
// as features, so each pair lands on one point of the sphere; a vertex of A
// is mapped onto B by locating its sphere point in B's map. Stretch-minimizing
// maps of two different shapes do not agree between the features, so A's map
// is computed again with a second energy, the symmetric distortion of its
// triangles against their images on B, optimized coarse to fine during the
// refinement as Schreiner et al. 2004 do, then B's likewise against A's (each
// kept only if it lowers the median distortion); then the composition is optimized
// directly for symmetric distortion in both directions: each mesh's sphere
// points move so that its triangles map onto the other surface as
// isometrically as possible, never leaving the kernel of their spherical stars. The result stays
// continuous and bijective as a map between the surfaces (both spherical
// maps remain embeddings); what is sampled here is its value at the vertices.
//
// With fewer than 3 pairs (the consistent parameterization needs 3), pairs
// are added automatically until there are 4: both meshes are mapped to the
// sphere unconstrained, B's map is rotated onto A's by the given pairs (least
// squares; with no pair the two maps are taken as they are), and well-spread
// vertices of A (farthest points on the sphere from the given features) are
// paired with the vertex of B nearest to where they land. So a pair with zero
// features still gets a valid, bijective map, only with an arbitrary
// correspondence where nothing constrains it.
//
// Genus 0 pairs can go either way (IntersurfaceOptions::method): by default
// both maps are computed, side by side on two threads (the direct map's
// parallel loops taking half of options.sphere.threads), and the less
// distorted one is kept: the lower summed median, except that medians within
// 5 % of each other are a tie, broken by fewer folded samples when the counts
// differ by more than 0.5 % of the triangles, else won by the direct map. The
// direct map follows the surfaces where they are alike, its paths being
// shortest on both (sets/cactus poses: ground-truth errors 0.3-0.9 % against
// 0.9-17 % through the sphere; sets/faces' expressions: nearer the truth in
// tied pairs); the sphere spreads the distortion better between different
// shapes (cow - horse: summed medians 9.9 against 13.6 direct).
//
// Genus 1 and higher: a direct map from a consistent partition (thesis 5.4,
// Schreiner et al. 2004). Corresponding path networks between the feature
// pairs cut both meshes into triangular patches of identical connectivity
// (features are added automatically where the partition needs them); each
// patch and its partner are parameterized onto one canonical triangle
// (boundary by arc length, interior by a convex-combination embedding), and
// a vertex of A maps to the point of B with the same canonical coordinates.
// Paths on B are kept near A's paths with B brought into A's frame by a
// transform fitted to the pairs (intersurface/path_guide.h), so that the
// handles' cycles correspond for meshes posed alike. Paths traced on two
// different shapes can give a patch a far larger share of one surface than
// of the other, which no map inside the patches undoes; so the map is also
// computed through a partition whose paths are moved to balance the patches'
// areas (intersurface/patch_balance.h), and kept if that lowers the median
// distortion. A's embedding is locally optimized inside the patches and
// along the paths, then across them: its vertices move over the base mesh
// glued flat around the features, into the neighbouring patch when a move
// crosses a path (IntersurfaceOptions::cross_sweeps), then B's against A's
// embedding as it is then (cross_turns), so the paths where the partition
// was traced stop being walls on both meshes (as in Schreiner et al., though
// on the full meshes, not during a progressive refinement). Continuous and
// bijective. With zero pairs, one pair is chosen: A's vertex farthest from
// its centroid and B's vertex nearest it with centroids and areas matched.
// Genus 0 gets at least 4 pairs: A's vertices farthest from those paired
// (the first as above), each partner the one of B's 8 farthest-point
// extremities nearest A's vertex in A's frame, B turned onto A's principal
// axes while the pairs are too few to fix a rotation, if that matches
// clearly closer.
// Holes (thesis 5.4, boundaries): each is closed by a fan around a temporary
// centre, holes are paired (by pairs on their rims, else by nearest centres
// in A's frame), each rim pair gets at least 3 corresponding features, and
// the rims and spokes to the centres are laid before any other path; so a
// hole maps onto its partner and a rim onto its partner rim
// (intersurface/hole_rims.h).
#pragma once
#include <array>
#include <optional>
#include <string>
#include <cstdint>
#include <vector>

#include "consistent_maps/mesh.h"
#include "consistent_maps/progress.h"
#include "consistent_maps/spherical_parameterization.h"

namespace cmaps {

// Corresponding vertices: vertex `a` of mesh A and vertex `b` of mesh B.
struct FeaturePair {
  int a = -1;
  int b = -1;
};

// A point on a mesh: one of its input triangles (index into its triangle
// array) and barycentric weights w.r.t. that triangle's corners in their
// order (each >= 0, summing to 1).
struct SurfacePoint {
  int triangle = -1;
  std::array<double, 3> barycentric{0, 0, 0};
};

// How a pair of genus 0 is mapped: through the common sphere, directly
// through a consistent partition (as every pair of genus >= 1 is), or both,
// keeping the less distorted map: the lower summed median distortion (A -> B
// plus B -> A), or within 5 % of each other clearly fewer folded samples,
// else the direct map.
enum class IntersurfaceMethod { automatic, sphere, partition };

// "auto", "sphere", "partition": the names the CLI and Python use.
const char* method_name(IntersurfaceMethod method);
// The method of that name, or nothing for another name.
std::optional<IntersurfaceMethod> parse_method(const std::string& name);

struct IntersurfaceOptions {
  IntersurfaceMethod method = IntersurfaceMethod::automatic;
  SphereOptions sphere;  // seed, effort, threads of the underlying parameterizations
  int grid = 64;         // genus 0: octahedral grid of the consistent parameterization (even)
  // Genus 0: the composed map is then optimized for symmetric distortion,
  // `rounds` times A -> B (moving A's sphere points over B) and B -> A, each
  // at most `sweeps` sweeps over the vertices. 0 keeps the plain composition.
  // The direct map: rounds > 0 optimizes it (each patch's areas matched to
  // its partner's, then at most `sweeps` sweeps, then cross_sweeps below).
  int optimize_rounds = 2;
  int optimize_sweeps = 20;
  // Genus 0: the first round's sweeps follow smooth deformations of whole
  // spherical caps, coarse to fine, which carry parts whose image is too small
  // or too large as one piece (a tail squeezed into a rump) where moving one
  // vertex at a time cannot (false: vertex moves only).
  bool optimize_regions = true;
  // Genus 0: before that, A's spherical map is computed again with this
  // weight on its consistency with B's map, then B's with A's, each kept
  // only if the median energy drops (0: not at all). With neither, the
  // result is the plain composition.
  double correspondence_weight = 0.25;
  // Genus 0: the whole map is computed this many times and the least
  // distorted kept (as for `method`: the lowest median symmetric Dirichlet
  // energy, both directions summed, or clearly fewer folded samples when
  // medians lie within 5 %): the means rank the maps by their few worst
  // sampled triangles.
  // Restarts lay out the pair's consistent parameterization in turn in one
  // pass, with carried guides, and with carried guides and B's map aligned
  // to A's (ConsistentOptions::carry_guides, align; the last instead of the
  // refit above); restart k uses seed + k / 3. The
  // optimization is local, and which minimum it ends in depends on the
  // starting parameterization: with few features the spread is wide
  // (sets/cactus 0 -> 3, 8 features: ground-truth error 2.2-7.9 % over six
  // starts), and the energy ranks the maps nearly like the true error does.
  // The direct map (any genus) is traced and optimized from both sides,
  // the less distorted kept; for a pair given no features and without
  // holes, restarts optimize the maps from that many of the `starts` below
  // (the least distorted before optimization), each from one side.
  int restarts = 1;
  // The direct map of a pair given no features and without holes: its
  // automatic first pair (A's k-th vertex of a farthest-point spread from
  // the one farthest from its centroid, B's nearest in A's frame; for genus
  // 0, B's extremity nearest it, as described above) decides
  // how the partition pairs the surfaces' handles and parts, and between
  // different shapes the maps differ widely (kitten - rocker-arm, eight
  // starts: summed medians 19.8, 16.7, 13.2, 26.0, 14.0, 33.5, 13.3, 16.9)
  // but rank alike once each patch's areas are matched to its partner's,
  // before the local sweeps (27.0, 23.4, 16.1, 33.7, 17.1, 39.7, 16.2, 20.3;
  // the plain embeddings pick the fifth: 28.6, 25.7, 18.3, 40.6, 17.7, ...).
  // So this many first pairs are each mapped that far (from both sides,
  // balanced and as traced, see max_traced_ratio), and the least distorted
  // ones optimized (IntersurfaceResult::start_median_dirichlet), each from
  // the side and through the partition its screened map kept (the optimized
  // maps rank the sides alike on 21 of 22 pairs, BENCHMARKS.md, and one side
  // takes all threads). Over the five unfeatured pairs of the genus >= 1
  // benchmark, cow - horse and bunny - gargoyle, the start so picked ended
  // with the lowest summed median of the eight in all seven (the plain
  // embeddings' pick in three; on the kittens' pairs the lower medians came
  // with more folded samples, BENCHMARKS.md).
  // Eight rather than four: the five featureless pairs of the genus >= 1
  // benchmark, summed medians -7 % and folded samples -28 % (eight - skull
  // and cup - skull find better first pairs, the kittens' maps move by under
  // 7 %) for 5-10 s more each.
  int starts = 8;
  // Also map every triangle corner of A and of B (IntersurfaceResult::
  // a_corners_to_b, b_corners_to_a), for transferring per-corner values such
  // as texture coordinates.
  bool corner_images = false;
  // The direct map (any genus): after its patch-wise optimization, at most
  // this many sweeps of moving A's vertices across the partition's paths
  // (each into the neighbouring patch when a move crosses one), so the
  // paths where the partition was traced stop being walls; 0: they stay.
  int cross_sweeps = 20;
  // The direct map: the two meshes take turns crossing the paths, A's
  // vertices first (each turn at most cross_sweeps sweeps), each against the
  // other's embedding as the turn before left it. With one turn, B's
  // embedding stays as its patches laid it out, each path straight along
  // its base edge: the triangles beside B's paths stay sheared, and most of
  // the map's folds sit there (BENCHMARKS.md).
  int cross_turns = 2;
  // Genus >= 1: rounds of moving the partition's paths so that corresponding
  // patches take equal shares of their surfaces (intersurface/patch_balance.h);
  // the map through the moved partition is kept only if its summed median
  // symmetric Dirichlet energy is lower. 0: the partition as traced.
  int balance_rounds = 4;
  // Genus >= 1: the partition as traced is not mapped, only the balanced
  // one, when the traced one's patches take shares of the two surfaces'
  // areas more than this factor apart (the largest over its patches): such
  // maps do not compete. Screening the 22 unfeatured pairs of BENCHMARKS.md
  // (session 52), the map through the partition as traced beat the balanced
  // one's, or came within 5 %, on 28 of 349 sides; above this ratio it would
  // have been kept on 6, all of starts the screening dropped (summed medians
  // 1.7 to 4.8 times the start kept's). Of the benchmarks' optimized maps,
  // the one kept through the partition as traced with the largest ratio had
  // 11.9 (cow - horse with 19 pairs, directly). Not mapping the others spares
  // about 40 % of the screening's maps on the feline's pairs. Infinity: both
  // always mapped.
  double max_traced_ratio = 12;
};

// How far the point of a triangle next to a corner (corner images) lies
// from it: this fraction of the way to each of the other two corners.
constexpr double kCornerNudge = 1e-3;

// Distortion of the map sampled at the vertices: each triangle of the source
// is mapped linearly onto the triangle its corners' images form on the
// target (a chord of the target surface, not the common refinement), with
// the target scaled to the source's total area. The symmetric Dirichlet
// energy |J|^2 + |J^-1|^2 is averaged over the source's area (optimum 4, an
// isometry). Image triangles of zero area are left out of the average and
// counted in `degenerate`; `flipped` counts image triangles whose normal
// points against the target surface's normal there (the normal of a target
// triangle holding all three images, else the unit normals of the triangles
// holding each, summed, as the map optimizers judge folds; the target's
// normals turned when one mesh, its holes closed, lists its triangles
// inwards and the other outwards). Both are properties of this vertex
// sampling: the map itself is bijective (see map_flipped).
// The mean is dominated by the few most distorted triangles (often
// near-degenerate samples); `median_symmetric_dirichlet`, the median
// triangle's energy (degenerate images counted as infinite), says how
// distorted the map is over most of the surface.
struct MapDistortion {
  double symmetric_dirichlet = 0;
  double median_symmetric_dirichlet = 0;
  int flipped = 0;
  int degenerate = 0;
};

struct IntersurfaceResult {
  std::vector<SurfacePoint> a_to_b;  // per vertex of A: its image on B (B's input triangles)
  std::vector<SurfacePoint> b_to_a;  // per vertex of B: its image on A
  // With options.corner_images: per triangle of A, per corner (3 t + k), the
  // image on B of the point of that triangle next to the corner (moved into
  // it by kCornerNudge of the way to the other corners: genus 0 on A's
  // spherical map, genus >= 1 in A's input triangle). Corners of one vertex
  // in triangles on both sides of a seam of B's per-corner values thus land
  // on their own side of it. b_corners_to_a: likewise B's corners on A.
  std::vector<SurfacePoint> a_corners_to_b;
  std::vector<SurfacePoint> b_corners_to_a;
  std::vector<Vec3> a_on_b;          // per vertex of A: the position of its image on B
  std::vector<Vec3> b_on_a;          // per vertex of B: the position of its image on A
  MapDistortion distortion_a_to_b, distortion_b_to_a;
  // The map kept: sphere or partition (genus >= 1: always the partition).
  IntersurfaceMethod method = IntersurfaceMethod::partition;
  // Genus 0: the summed median distortion (A -> B plus B -> A) of each map
  // computed (-1 where it was not), so the two can be compared.
  double sphere_median_dirichlet = -1, partition_median_dirichlet = -1;
  std::vector<FeaturePair> features;  // the pairs used: the given ones, then any added automatically
  int added_features = 0;             // how many of `features` were added
  int genus = 0;
  // Genus >= 1: the base triangulation (all its vertices, including added
  // ones that are Steiner vertices and so not listed in `features`).
  int base_vertices = 0, base_triangles = 0;
  // Genus 0: the two spherical maps after optimization (their stretch
  // efficiency, flipped chordal triangles, Steiner vertices inserted on each
  // mesh) and the distortion of the plain composition of the consistent
  // parameterization's two maps (genus >= 1: the final distortion); genus
  // >= 1: the Steiner vertices of the partition and its patches' refinement.
  double efficiency_a = 0, efficiency_b = 0;
  int sphere_flipped = 0;
  // The map's own folds, 0 when it is bijective as computed (unlike
  // MapDistortion::flipped, which counts folds of the vertex sampling):
  // through the sphere, sphere_flipped; directly, A's triangles turned over
  // in their patches' canonical triangles, B's turned over in its patch
  // embeddings, and B's vertices outside the triangle of A said to hold them.
  int map_flipped = 0;
  // Genus 0: whether A's map, then B's, was kept refitted against the
  // other's (IntersurfaceOptions::correspondence_weight).
  bool refitted_a = false, refitted_b = false;
  int steiner_a = 0, steiner_b = 0;
  // Genus >= 1: whether the map went through the partition with balanced
  // patch areas (IntersurfaceOptions::balance_rounds; a screened start's
  // optimization maps only the one its screened map kept), and the largest ratio
  // between a patch's shares of A's and of B's area in the partition used
  // (1: every patch takes the same share of both).
  bool balanced_patches = false;
  double patch_area_ratio = 1;
  // The direct map (kept): per input triangle of A and of B, where it lies
  // against the partition's paths: 0 away from them, 1 a corner on a path,
  // 2 cut by one (its pieces in two patches). Empty for the sphere's map.
  // The direct map's distortion and folds gather along its paths, where
  // the patch embeddings lay each path straight (BENCHMARKS.md).
  std::vector<std::int8_t> a_along_paths, b_along_paths;
  // The direct map kept was traced and optimized from B's side: B's
  // vertices moved first (then A's, and so on: cross_turns); false: A's.
  bool moved_b = false;
  // Per restart through the sphere (genus 0), or of the direct map (genus
  // >= 1 or method partition, a pair without features or holes, more than
  // one restart), the final symmetric Dirichlet energy A -> B plus B -> A:
  // the means, and the medians and folded samples (both directions), which
  // choose the restart kept (the sphere's reported also when the direct map
  // is kept instead).
  std::vector<double> restart_dirichlet, restart_median_dirichlet;
  std::vector<int> restart_flipped;
  // The direct map of a pair without features and holes, optimized: per
  // automatic first pair tried (IntersurfaceOptions::starts), the summed
  // median symmetric Dirichlet energy of its screened map (each patch's areas
  // matched to its partner's, before the local sweeps).
  std::vector<double> start_median_dirichlet;
  MapDistortion composition_a_to_b, composition_b_to_a;
  // Wall time per stage: unconstrained maps for added features (genus 0),
  // the consistent partition and its balancing (genus >= 1), the consistent or patch
  // parameterization, the distortion optimization, point location and
  // conversion, measures (genus >= 1: summed over both maps when the
  // balanced partition was mapped too).
  double seconds_features = 0, seconds_partition = 0, seconds_parameterize = 0, seconds_optimize = 0,
         seconds_locate = 0, seconds_measure = 0, seconds = 0;
};

// Vertices that no triangle uses are left out of the computation; each takes
// the image of the nearest used vertex (a feature on one is refused).
// Genus 0 meshes may have holes (thesis 3.5), each ringed by at least 3
// features, the same pairs around corresponding holes: boundaries map onto
// boundaries; the map is then optimized with the boundary vertices held on
// their arcs, without the refit (which does not keep them there).
// Throws TopologyError for a mesh that is not one manifold, consistently
// oriented surface, closed or genus 0 with holes (naming A or B), for meshes of different
// genus ("A has genus 1, B has genus 2; an inter-surface map needs equal
// genus"); InvalidInput for a feature vertex out of range or used by two
// pairs, or the sphere method asked of genus >= 1; Error when a partition
// gets stuck (genus 0, automatic method: the sphere's map is returned, and
// the partition's when the sphere refuses a hole ringed by too few pairs);
// Cancelled when `progress` says so.
IntersurfaceResult intersurface_map(const TriangleMesh& a, const TriangleMesh& b,
                                    const std::vector<FeaturePair>& features,
                                    const IntersurfaceOptions& options = {},
                                    const ProgressCallback& progress = {});

// The distortion measure above for any per-vertex map of `source` onto
// `target` (one SurfacePoint per source vertex). Throws TopologyError when
// either mesh is not a manifold, consistently oriented surface.
MapDistortion measure_intersurface_map(const TriangleMesh& source, const TriangleMesh& target,
                                       const std::vector<SurfacePoint>& image);

// The same measure per source triangle, to show where a map distorts (the
// mean and median above summarize it): each triangle's symmetric Dirichlet
// density onto the chord triangle of its corners' images (target scaled to
// the source's area; optimum 4; +inf when the image is degenerate, NaN for
// a source triangle of zero area), whether that image faces against the
// target surface (a folded sample), and the triangle's area. Throws as
// measure_intersurface_map.
struct TriangleDistortion {
  std::vector<double> symmetric_dirichlet;
  std::vector<char> flipped;
  std::vector<double> area;
};
TriangleDistortion triangle_distortion(const TriangleMesh& source, const TriangleMesh& target,
                                       const std::vector<SurfacePoint>& image);
// What measure_intersurface_map reports, summarized from the per-triangle measure.
MapDistortion summarize(const TriangleDistortion& per_triangle);

// Positions of the images: sum of weight * corner position on `target`.
std::vector<Vec3> surface_positions(const TriangleMesh& target, const std::vector<SurfacePoint>& points);

}  // namespace cmaps
