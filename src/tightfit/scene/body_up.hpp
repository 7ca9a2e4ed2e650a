#pragma once
/// The body's up direction, for exports that have a convention for it (glTF: +y up).
///
/// Rule: a body built from a mesh file is in tightfit's body frame (x to the body's
/// left, y up, z forward; MakeHuman bodies, rigs and poses use it), so up is +y; a
/// generated cylinder is a limb or a torso standing along its axis (`"axis"`, default
/// +z), so up is that axis; a sphere has no up and keeps +y.
#include "tightfit/body/body_spec.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// The unit up direction of the body `spec` builds (see the rule above).
Vec3 body_up_direction(const BodySpec& spec);

}  // namespace tightfit
