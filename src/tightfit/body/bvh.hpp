#pragma once
/// Reader of BVH ("Biovision Hierarchy") motion-capture files: a skeleton (HIERARCHY)
/// and per-frame channel values (MOTION).
///
/// The subset read: `HIERARCHY`, exactly one `ROOT name { ... }` holding `OFFSET x y z`,
/// `CHANNELS n c1 .. cn` (n in 0..6, each of Xposition Yposition Zposition Xrotation
/// Yrotation Zrotation at most once, any letter case) and nested `JOINT name { ... }` and
/// `End Site { OFFSET x y z }` blocks; then `MOTION`, `Frames: N`, `Frame Time: t` and
/// N × (number of channels) whitespace-separated numbers, split across lines in any way.
/// Tokens are whitespace-separated; "\r\n" line endings are accepted.
///
/// Units: the values are kept as written: offsets and position channels in the file's
/// units (which BVH does not state), rotation channels in degrees, the frame time in
/// seconds.
///
/// Bounds, for hostile files: nesting at most 1000 blocks deep (parsed with an explicit
/// stack, no recursion), no allocation before the file is known to hold what a count in
/// it promises (memory stays proportional to the file size), every number finite.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit {

/// One channel of a joint: a translation along or a rotation about a local axis.
enum class BvhChannel { kXposition, kYposition, kZposition, kXrotation, kYrotation, kZrotation };

/// One ROOT or JOINT block of the hierarchy.
struct BvhJoint {
  std::string name;
  int parent = -1;                   ///< index into BvhMotion::joints, -1 for the ROOT
  Vec3 offset = Vec3::Zero();        ///< OFFSET, file units, in the parent's frame
  std::vector<BvhChannel> channels;  ///< in file order (0..6 channels, each at most once)
  int first_channel = 0;             ///< column of its first channel in a frame row
};

/// A whole BVH file: the skeleton and its frames.
struct BvhMotion {
  std::vector<BvhJoint> joints;  ///< file order: every parent comes before its children. "End Site"
                                 ///< blocks are NOT joints (skipped).
  int num_channels = 0;          ///< total channels = columns of `frames`
  double frame_time = 0.0;       ///< s
  MatX frames;  ///< num_frames × num_channels, the values as written (positions in file units,
                ///< rotations in degrees)
  std::string source;  ///< the file, for messages
  int num_frames() const { return static_cast<int>(frames.rows()); }
  /// Index of the joint called `name`, -1 if none.
  int find(const std::string& name) const;
  /// The local rotation of joint `joint` in frame `frame`: the product of its rotation
  /// channels in file order, R = R_a(θ_a) R_b(θ_b) R_c(θ_c) for "CHANNELS ... Arotation Brotation
  /// Crotation" (the standard BVH convention: the last-listed channel acts on a vector first),
  /// angles in degrees. Identity for a joint without rotation channels. Throws std::out_of_range
  /// for bad indices.
  Mat3 local_rotation(int joint, int frame) const;
};

/// Reads a BVH file. Throws InputError(path, "line N: ...") for anything malformed.
BvhMotion read_bvh(const std::filesystem::path& path);

/// Parses BVH text; `source` names it in errors.
BvhMotion parse_bvh(std::string_view text, const std::string& source);

}  // namespace tightfit
