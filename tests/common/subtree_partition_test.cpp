#include "tightfit/common/subtree_partition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

namespace tightfit::subtree_partition_test {

/// Every node exactly once: in one part's ranges or in the top; a top node's descendants
/// (parent chain) are never after it in a part of its own.
void expect_cover(const SubtreePartition& p, const std::vector<int>& parent) {
  std::vector<int> seen(parent.size(), 0);
  for (const auto& part : p.parts)
    for (const SubtreeRange& r : part) {
      ASSERT_LE(r.first, r.last);
      for (int s = r.first; s <= r.last; ++s) ++seen[static_cast<std::size_t>(s)];
      // The range is the whole subtree of its root: every node in it leads to the root.
      for (int s = r.first; s <= r.last; ++s) {
        int a = s;
        while (a != r.last && a >= 0) a = parent[static_cast<std::size_t>(a)];
        EXPECT_EQ(a, r.last) << "node " << s << " is not below the range's root";
      }
    }
  for (const int s : p.top) ++seen[static_cast<std::size_t>(s)];
  for (std::size_t s = 0; s < seen.size(); ++s) EXPECT_EQ(seen[s], 1) << "node " << s;
  EXPECT_TRUE(std::is_sorted(p.top.begin(), p.top.end()));
}

// A root separator (node 6) over two equal subtrees (0–2 and 3–5, each a chain of 3):
// one subtree per part, the root on top.
TEST(SubtreePartition, SplitsTwoEqualSubtreesUnderARoot) {
  const std::vector<int> parent{1, 2, 6, 4, 5, 6, -1};
  const std::vector<double> work{1, 1, 1, 1, 1, 1, 0.5};
  const SubtreePartition p = partition_subtrees(parent, work, 2, 0.0, 0.9);
  ASSERT_EQ(p.parts.size(), 2u);
  expect_cover(p, parent);
  EXPECT_EQ(p.top, std::vector<int>{6});
  ASSERT_EQ(p.parts[0].size(), 1u);
  ASSERT_EQ(p.parts[1].size(), 1u);
  EXPECT_EQ(p.parts[0][0].first, 0);
  EXPECT_EQ(p.parts[0][0].last, 2);
  EXPECT_EQ(p.parts[1][0].first, 3);
  EXPECT_EQ(p.parts[1][0].last, 5);
  EXPECT_NEAR(p.critical_fraction, 3.5 / 6.5, 1e-15);
}

// Unbalanced children: the heavy one is split further until the parts balance.
TEST(SubtreePartition, SplitsTheHeavySubtreeFurther) {
  // 0,1 -> 2 (heavy subtree 0–2 under 2), 3 light, 2 and 3 -> 4 (root).
  const std::vector<int> parent{2, 2, 4, 4, -1};
  const std::vector<double> work{4, 4, 0.5, 3, 0.5};
  const SubtreePartition p = partition_subtrees(parent, work, 2, 0.0, 0.9);
  ASSERT_EQ(p.parts.size(), 2u);
  expect_cover(p, parent);
  EXPECT_EQ(p.top, (std::vector<int>{2, 4}));
  EXPECT_NEAR(p.critical_fraction, (4.0 + 3.0 + 1.0) / 12.0, 1e-15);
}

TEST(SubtreePartition, GivesNoPartsWhereSplittingDoesNotPay) {
  const std::vector<int> chain{1, 2, 3, -1};  // a path: nothing independent
  const std::vector<double> work{1, 1, 1, 1};
  const SubtreePartition path = partition_subtrees(chain, work, 2, 0.0, 0.9);
  EXPECT_TRUE(path.parts.empty());
  EXPECT_EQ(path.top, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(path.critical_fraction, 1.0);

  const std::vector<int> parent{1, 2, 6, 4, 5, 6, -1};
  const std::vector<double> even{1, 1, 1, 1, 1, 1, 0.5};
  EXPECT_TRUE(partition_subtrees(parent, even, 1, 0.0, 0.9).parts.empty());    // one part
  EXPECT_TRUE(partition_subtrees(parent, even, 2, 100.0, 0.9).parts.empty());  // too small
  EXPECT_TRUE(partition_subtrees(parent, even, 2, 0.0, 0.5).parts.empty());    // not worth it
  // Not a postorder (a parent before its child): no parts.
  const std::vector<int> unordered{-1, 0};
  EXPECT_TRUE(partition_subtrees(unordered, {1, 1}, 2, 0.0, 0.9).parts.empty());
  // Subtrees that are not ranges (node 1's subtree {0, 2} skips node 1's sibling).
  const std::vector<int> interleaved{2, 3, 3, -1};
  const SubtreePartition gaps = partition_subtrees(interleaved, {1, 1, 1, 1}, 2, 0.0, 0.9);
  EXPECT_TRUE(gaps.parts.empty());
}

// A forest: the roots themselves are independent.
TEST(SubtreePartition, SpreadsTheTreesOfAForest) {
  const std::vector<int> parent{1, -1, 3, -1, -1};
  const std::vector<double> work{2, 1, 1, 1, 1};
  const SubtreePartition p = partition_subtrees(parent, work, 2, 0.0, 0.9);
  ASSERT_EQ(p.parts.size(), 2u);
  expect_cover(p, parent);
  EXPECT_TRUE(p.top.empty());
  EXPECT_NEAR(p.critical_fraction, 3.0 / 6.0, 1e-15);
}

}  // namespace tightfit::subtree_partition_test
