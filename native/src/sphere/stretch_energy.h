// The stretch energy a spherical parameterization minimizes, in the form the
// optimizer evaluates it around one vertex.
//
// For a chordal triangle (p, a, b) on the sphere and its surface triangle,
// A_m * L2^2 = (sum_i W_i w_i) / (2 |n|^2), where n = (a - p) x (b - p),
// w_i is the dot product of the two domain edges at corner i, and
// W_i = A_m * |opposite surface edge|^2 (summed over several geometries when
// one connectivity carries many shapes). The sum over all triangles is
// A_M * L2(M)^2, so with A_M = 4 pi the efficiency is 4 pi / energy.
//
// The optimizer uses |n| * det(p, a, b) in place of |n|^2: the same for the
// small triangles of a fine mesh (det = |n| * the plane's distance from the
// centre, nearly 1), but a barrier as a large coarse-level triangle grows
// towards a hemisphere, where the chordal energy alone stays finite.
#pragma once
#include <array>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

using FaceWeights = std::array<double, 3>;

// W_i for the surface triangle t, summed over the geometries.
// With `regularizer_only` (the temporary triangles closing a hole, which may
// shrink freely on the sphere), only the small regularizing term is kept.
FaceWeights face_weights(const Triangle& t, const std::vector<const std::vector<Vec3>*>& geometries,
                         bool regularizer_only = false);

// Energy of one triangle whose corner at p moves, with (p, a, b) counter-
// clockwise; w = the triangle's weights rotated so that w[0] belongs to p.
// Returns +inf when the triangle is flipped or nearly degenerate on the
// sphere; adds the gradient with respect to p to *gradient when given.
double corner_energy(const Vec3& p, const Vec3& a, const Vec3& b, const FaceWeights& w, Vec3* gradient);

// True when the chordal triangle (p, a, b) is positively oriented with a
// margin that survives rounding.
bool chordal_triangle_valid(const Vec3& p, const Vec3& a, const Vec3& b);

}  // namespace cmaps
