#include "tightfit/common/subtree_partition.hpp"

#include <algorithm>
#include <numeric>

namespace tightfit {
namespace {

/// Splitting stops after this many steps (each moves one node to the top).
constexpr int kMaximumSplits = 512;

/// Longest-processing-time packing of the subtrees rooted at `roots` into `parts` bins:
/// heaviest first, each to the lightest bin (ties: lower numbers). Returns the bin of
/// each root and the heaviest bin's work.
double pack(const std::vector<int>& roots, const std::vector<double>& subtree, int parts,
            std::vector<int>& bin_of_root) {
  std::vector<int> order(roots.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const double wa = subtree[static_cast<std::size_t>(roots[static_cast<std::size_t>(a)])];
    const double wb = subtree[static_cast<std::size_t>(roots[static_cast<std::size_t>(b)])];
    return wa != wb ? wa > wb
                    : roots[static_cast<std::size_t>(a)] < roots[static_cast<std::size_t>(b)];
  });
  std::vector<double> load(static_cast<std::size_t>(parts), 0.0);
  bin_of_root.assign(roots.size(), 0);
  for (const int k : order) {
    const auto lightest =
        static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    bin_of_root[static_cast<std::size_t>(k)] = static_cast<int>(lightest);
    load[lightest] += subtree[static_cast<std::size_t>(roots[static_cast<std::size_t>(k)])];
  }
  return *std::max_element(load.begin(), load.end());
}

}  // namespace

SubtreePartition partition_subtrees(const std::vector<int>& parent, const std::vector<double>& work,
                                    int parts, double minimum_work, double worth) {
  SubtreePartition result;
  const int n = static_cast<int>(parent.size());
  result.top.resize(static_cast<std::size_t>(n));
  std::iota(result.top.begin(), result.top.end(), 0);
  if (parts < 2 || n == 0 || work.size() != parent.size()) return result;

  // Subtree work, sizes and first nodes; parents come after their children.
  std::vector<double> subtree(work);
  std::vector<int> size(static_cast<std::size_t>(n), 1), first(static_cast<std::size_t>(n));
  std::iota(first.begin(), first.end(), 0);
  std::vector<std::vector<int>> children(static_cast<std::size_t>(n));
  std::vector<int> roots;
  for (int s = 0; s < n; ++s) {
    const int p = parent[static_cast<std::size_t>(s)];
    if (p >= n || (p >= 0 && p <= s)) return result;
    if (p < 0) {
      roots.push_back(s);
      continue;
    }
    const auto ps = static_cast<std::size_t>(p), ss = static_cast<std::size_t>(s);
    subtree[ps] += subtree[ss];
    size[ps] += size[ss];
    first[ps] = std::min(first[ps], first[ss]);
    children[ps].push_back(s);
  }
  for (int s = 0; s < n; ++s)
    if (size[static_cast<std::size_t>(s)] != s - first[static_cast<std::size_t>(s)] + 1)
      return result;  // not a postorder: subtrees are not ranges
  const double total = std::accumulate(work.begin(), work.end(), 0.0);
  if (!(total >= minimum_work) || !(total > 0.0)) return result;

  // Split the heaviest subtree while the critical path (largest bin + top) shortens.
  std::vector<int> candidates = roots, best = roots, bins;
  double top_work = 0.0;
  double best_critical = pack(candidates, subtree, parts, bins);
  for (int step = 0; step < kMaximumSplits; ++step) {
    const auto heaviest = std::max_element(candidates.begin(), candidates.end(), [&](int a, int b) {
      const double wa = subtree[static_cast<std::size_t>(a)];
      const double wb = subtree[static_cast<std::size_t>(b)];
      return wa != wb ? wa < wb : a > b;
    });
    const int h = *heaviest;
    const std::vector<int>& below = children[static_cast<std::size_t>(h)];
    if (below.empty()) break;
    candidates.erase(heaviest);
    candidates.insert(candidates.end(), below.begin(), below.end());
    top_work += work[static_cast<std::size_t>(h)];
    if (top_work >= best_critical) break;
    const double critical = pack(candidates, subtree, parts, bins) + top_work;
    if (critical < best_critical) {
      best_critical = critical;
      best = candidates;
    }
  }
  result.critical_fraction = best_critical / total;
  if (result.critical_fraction > worth || best.size() < 2) {
    result.critical_fraction = 1.0;
    return result;
  }

  pack(best, subtree, parts, bins);
  result.parts.assign(static_cast<std::size_t>(parts), {});
  std::vector<char> in_part(static_cast<std::size_t>(n), 0);
  for (std::size_t k = 0; k < best.size(); ++k) {
    const int root = best[k];
    const SubtreeRange range{first[static_cast<std::size_t>(root)], root};
    result.parts[static_cast<std::size_t>(bins[k])].push_back(range);
    std::fill(in_part.begin() + range.first, in_part.begin() + range.last + 1, 1);
  }
  for (auto& part : result.parts)
    std::sort(part.begin(), part.end(),
              [](const SubtreeRange& a, const SubtreeRange& b) { return a.first < b.first; });
  result.top.clear();
  for (int s = 0; s < n; ++s)
    if (!in_part[static_cast<std::size_t>(s)]) result.top.push_back(s);
  return result;
}

}  // namespace tightfit
