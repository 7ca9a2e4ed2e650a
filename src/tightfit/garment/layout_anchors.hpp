#pragma once
/// Layouts anchored on the skeleton, made absolute on one body. A layout's planes may
/// name bones instead of points (garment/layout_spec.hpp: a point at a fraction of a
/// bone, a normal along a bone, a bone region), so that one layout file lays out every
/// body of a rig. This module turns such a spec into an absolute one on a given body,
/// before layout_from_rules (layout.hpp) cuts it; the cutting code only sees planes and,
/// for bone regions, a field per body-surface vertex.
///
/// Bone regions: each body-surface vertex takes the skin weights of its closest point on
/// the rig mesh (barycentric over its triangle; body/skin_transfer.hpp, the transfer the
/// simulated body's pose weights use), so cropped and remeshed bodies work; the field
/// is the bones' summed weight (weights normalized per point) minus ½.
#include <map>
#include <string>

#include "tightfit/body/skeleton.hpp"
#include "tightfit/body/skin_weights.hpp"
#include "tightfit/garment/layout_spec.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// The skeleton and skin weights of the body a layout is laid out on (either may be
/// null when the layout does not need it).
struct LayoutRig {
  const std::map<std::string, BoneSegment>* skeleton = nullptr;  ///< bones (m, body frame)
  const SkinWeights* weights = nullptr;  ///< skin weights on the rig mesh (bone regions)
  std::string source;  ///< where the rig is declared, for messages ("scene.json: /rig")
};

/// A copy of `spec` whose planes are absolute on the body whose closed surface is
/// `body_surface` (m): anchored points and bone normals from `rig.skeleton`, bone regions
/// as fields over `body_surface`'s vertices (header comment). Every plane of a rules
/// layout (region planes, dividers) and every pin's inline plane, anchored or not, must
/// cross the body surface (vertices on both sides; for a bone region: the bones dominate
/// part of the surface, not all of it).
/// Throws InputError naming the spec's file and the plane's JSON path for: an unknown
/// bone (with the nearest known name when one is close), a bone of zero length used as
/// a normal, anchors without a skeleton or bone regions without skin weights, a plane
/// that misses the body. A spec resolved before keeps its bone regions' fields (they
/// must have one value per vertex of `body_surface`, else std::invalid_argument).
LayoutSpec resolve_layout_anchors(const LayoutSpec& spec, const TriMesh& body_surface,
                                  const LayoutRig& rig);

}  // namespace tightfit
