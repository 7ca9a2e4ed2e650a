#pragma once
/// Where OpenSubdiv's second-derivative sign bug strikes (docs/design.md §6 item 2).
///
/// Bfr evaluates an irregular triangle (a corner of valence ≠ 6) through a patch tree:
/// the face is split 1-to-4 recursively; a sub-triangle that touches no extraordinary
/// corner is a regular box-spline leaf, the sub-triangle at an extraordinary corner is
/// split again down to depth L, where it becomes a Gregory leaf. The middle child of a
/// split is "rotated" (upside down): its local coordinates run against the face's, and
/// OpenSubdiv 3.5/3.6 scales its second-derivative weights with the (negative) sign of
/// the first-derivative scale. This function replays the tree search of
/// Bfr::PatchTree::searchQuadtree with the same floating-point operations, so it agrees
/// with OpenSubdiv on which leaf a point on a sub-triangle boundary belongs to.
namespace tightfit {

/// True when (u,v) of an irregular face lands in a rotated leaf of the patch tree.
/// `ev_corners`: bit k set when corner k has valence ≠ 6; `depth`: the tree depth L
/// (approx level for smooth features).
inline bool patch_tree_rotated(double u, double v, unsigned ev_corners, int depth) {
  double median = 0.5;
  int corner = -1;
  for (int d = 1; d <= depth; ++d, median *= 0.5) {
    int quadrant = 0;
    if (u >= median) {
      u -= median;
      quadrant = 1;
    } else if (v >= median) {
      v -= median;
      quadrant = 2;
    } else if (u + v >= median) {
      return true;  // the middle child: a regular leaf, rotated
    }
    if (d == 1) corner = quadrant;
    // A corner child is split again only while it still holds an extraordinary corner.
    if (quadrant != corner || !(ev_corners & (1u << corner))) return false;
  }
  return false;  // the Gregory leaf at an extraordinary corner
}

}  // namespace tightfit
