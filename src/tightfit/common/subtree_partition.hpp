#pragma once
/// Splits an elimination tree into disjoint subtrees for parallel sweeps: a supernodal
/// triangular solve can eliminate independent subtrees on separate threads (forward:
/// the subtrees first, then the rest, "the top", in order; backward: the top first, then
/// the subtrees), the classic subtree-to-thread mapping (Geist and Ng, 1989).
///
/// The tree must be numbered in postorder (every node after its descendants, each
/// subtree a contiguous range of numbers), as CHOLMOD numbers supernodes; the partition
/// is then a list of ranges per part. It is a function of the tree, the work and the
/// part count alone, so sweeps that follow it are repeatable bit for bit.
#include <vector>

namespace tightfit {

/// Subtrees as contiguous node ranges [first, last] (last is the subtree's root).
struct SubtreeRange {
  int first = 0;
  int last = 0;
};

struct SubtreePartition {
  /// Per part: its subtrees, in increasing order. Empty when a split does not pay (the
  /// tree is not in postorder, too small or too unbalanced): then every node is in `top`.
  std::vector<std::vector<SubtreeRange>> parts;
  /// The nodes in no part, increasing (each one's descendants are in parts or before it).
  std::vector<int> top;
  /// Work of the largest part plus the top's, over the total (1: no gain; 1/P: perfect).
  double critical_fraction = 1.0;
};

/// Partitions the tree given by `parent` (parent[s] > s, or −1 at a root) into at most
/// `parts` parts of subtrees balanced by `work` (per node, ≥ 0), splitting the heaviest
/// subtree into its children while that shortens the critical path (largest part plus
/// top). A partition whose critical_fraction exceeds `worth` (e.g. 0.8), or a tree of
/// total work below `minimum_work`, or parts < 2, gives no parts.
SubtreePartition partition_subtrees(const std::vector<int>& parent, const std::vector<double>& work,
                                    int parts, double minimum_work, double worth);

}  // namespace tightfit
