#pragma once
/// Patch compactness regularizer on the pattern rest positions (paper Sec. 4.1,
/// Eq. 25-26): keeps pieces from becoming arbitrarily thin. For two boundary vertices
/// p_i, p_j of the same piece,
///   ρ_ij = ‖p_i − p_j‖ / (length of the boundary path from p_i to p_j),
///   R = Σ_ij w_ij (ρ_ij − r_D)⁴ where ρ_ij < r_D, 0 otherwise   (dimensionless)
/// with the pair weights w_ij of Pair (about 1 on the design's initial mesh,
/// objectives/resolution.hpp), so that a remeshing does not change R.
/// The path is whichever of the two boundary arcs between them was SHORTER at
/// construction; the choice is kept afterwards (paper). r_D is the minimum admissible
/// ratio (a straight path has ρ = 1, the opposite points of a circle 2/π ≈ 0.64, the
/// middles of the long sides of a 1:5 rectangle ≈ 0.17). R is C³ in ρ.
///
/// Pairs: all pairs of loop vertices whose kept path has at least 2 edges (a single
/// edge has ρ = 1), or, with `pair_stride` s > 1, only pairs of loop positions that are
/// multiples of s (about s² times fewer pairs). Cost O(pairs) per evaluation (prefix
/// sums of edge lengths along the loop; path-length gradients by a cyclic difference
/// array). Independent of the garment positions x.
#include <vector>

#include "tightfit/garment/garment.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/objectives/resolution.hpp"

namespace tightfit {

struct CompactnessOptions {
  double min_ratio = 0.1;  ///< r_D in (0, 1]: ratios below it are penalized
  int pair_stride = 1;     ///< >= 1; 1 = all pairs
};

class CompactnessRegularizer : public DesignTerm {
 public:
  /// Chooses the pairs and their paths from the garment's current rest positions, and
  /// each loop's weight from its mean rest edge and `reference` (the garment's own
  /// resolution when not known). Throws std::invalid_argument for r_D outside (0, 1] or a
  /// stride < 1.
  explicit CompactnessRegularizer(const Garment& garment, CompactnessOptions options = {},
                                  const ResolutionReference& reference = {});

  std::string name() const override { return "compactness"; }
  double value(const DesignState& state) const override;
  void add_gradient(const DesignState& state, VecX& d_x, VecX& d_rest) const override;
  bool depends_on_positions() const override { return false; }

  /// A pair of loop positions and its kept path: edges start, start+1, ... (count of
  /// them, cyclic), edge k joining loop positions k and k+1.
  struct Pair {
    int i = 0;  ///< loop position of one end (the path starts here when forward)
    int j = 0;  ///< loop position of the other end
    int start = 0;
    int count = 0;
    /// w_ij = σ_i σ_j / h²: σ the rest boundary length around each end at construction
    /// (half its two edges, times the stride), h the reference boundary edge. A loop has
    /// ~n² pairs; so weighted, R is the same on any mesh of the loop.
    double weight = 1.0;
  };
  /// One boundary loop: its global pattern vertices and pairs.
  struct Loop {
    std::vector<int> vertices;
    std::vector<Pair> pairs;
  };
  const std::vector<Loop>& loops() const { return loops_; }

  /// ρ of every pair at `rest`, loop after loop (for reports and tests).
  std::vector<double> ratios(const Points2& rest) const;

 private:
  CompactnessOptions options_;
  std::vector<Loop> loops_;
  int num_pattern_ = 0;
};

}  // namespace tightfit
