#pragma once
/// Skin weights for the bodies tightfit simulates. A rig's weights (SkinWeights) live on
/// the vertices of the rig mesh (a full MakeHuman body); the simulated body is cropped,
/// capped and remeshed, and its tet mesh has interior vertices, so the weights are carried
/// over:
///  * surface points take the weights of the CLOSEST POINT of the rig mesh, interpolated
///    barycentrically over the rig triangle that holds it;
///  * interior tet vertices take HARMONIC weights: each bone's weight solves the graph
///    Laplace equation over the tet edges (uniform edge weights) with the surface
///    vertices' weights as boundary values. Why harmonic and not the nearest surface
///    point: the nearest surface point jumps across the body's medial axis (a vertex in
///    the middle of the thigh would take the front's or the back's weights at random, and
///    the tets there shear in a pose), while harmonic weights are smooth; and with uniform
///    (positive) edge weights they obey the maximum principle, so they stay in [0, 1] and
///    still sum to 1 (constants are harmonic). Cotangent weights would be more accurate
///    on irregular tets but can be negative and break both properties.
/// Interior weights below 1e-4 are dropped and the rest renormalized (a vertex deep in
/// the thigh otherwise carries every bone of the leg at 1e-9).
#include <string>

#include "tightfit/body/body.hpp"
#include "tightfit/body/skin_weights.hpp"
#include "tightfit/body/skinning.hpp"

namespace tightfit {

/// How well a body fits the rig its weights came from.
struct SkinTransferReport {
  double max_distance = 0.0;   ///< largest distance (m) from a surface point to the rig mesh
  double mean_distance = 0.0;  ///< mean of those distances (m)
};

/// Weights of `points` (n×3, m, in the rig's frame) from the rig, by closest point.
/// Throws InputError (source rig.source) when the rig has no faces, or when a point's
/// closest rig triangle has no weighted corner.
PointWeights transfer_skin_weights(const SkinWeights& rig, const Points3& points,
                                   SkinTransferReport* report = nullptr);

/// Weights of every volume vertex of `body` (surface vertices first, as in Body):
/// surface by closest point, interior harmonic (header comment).
PointWeights body_skin_weights(const Body& body, const SkinWeights& rig,
                               SkinTransferReport* report = nullptr);

}  // namespace tightfit
