#include "tightfit/geometry/point_cloud_index.hpp"

#include <nanoflann.hpp>

#include <cstddef>
#include <utility>

namespace tightfit {
/// The kd-tree with its nanoflann dataset adaptor over the rows of its own copy of the
/// points (nested types, not an anonymous namespace: the layer compiles as a unity build).
struct PointCloudIndex::Tree {
  struct Cloud {
    const Points3* points = nullptr;
    std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(points->rows()); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const {
      return (*points)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(d));
    }
    template <class Box>
    bool kdtree_get_bbox(Box& /*box*/) const {
      return false;
    }
  };
  using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>,
                                                     Cloud, 3, std::size_t>;

  Points3 points;  // the tree refers to it
  Cloud cloud;
  std::unique_ptr<KdTree> tree;

  explicit Tree(Points3 p) : points(std::move(p)) {
    cloud.points = &points;
    tree = std::make_unique<KdTree>(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  }
};

PointCloudIndex::PointCloudIndex(Points3 points)
    : tree_(std::make_unique<Tree>(std::move(points))) {}
PointCloudIndex::~PointCloudIndex() = default;

std::vector<PointCloudIndex::Neighbour> PointCloudIndex::within(const Vec3& x,
                                                                double radius) const {
  const double h2 = radius * radius;
  std::vector<std::pair<std::size_t, double>> found;
  tree_->tree->radiusSearch(x.data(), h2, found, nanoflann::SearchParams(32, 0.0f, false));
  std::vector<Neighbour> near;
  near.reserve(found.size());
  for (const auto& [k, d2_tree] : found) {
    const auto kk = static_cast<Eigen::Index>(k);
    const double u = 1.0 - (x - tree_->points.row(kk).transpose()).squaredNorm() / h2;
    if (u > 0.0) near.push_back({kk, u});
  }
  return near;
}

Eigen::Index PointCloudIndex::nearest(const Vec3& x) const {
  std::size_t k = 0;
  double d2 = 0.0;
  tree_->tree->knnSearch(x.data(), 1, &k, &d2);
  return static_cast<Eigen::Index>(k);
}

}  // namespace tightfit
