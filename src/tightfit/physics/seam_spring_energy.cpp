#include "tightfit/physics/seam_spring_energy.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "tightfit/common/error.hpp"
#include "tightfit/physics/assembly.hpp"

namespace tightfit {
namespace {

const std::string kSeamSource = "seam springs";

/// One spring evaluated at (x, Xbar).
struct Spring {
  std::array<int, 2> garment;
  std::array<int, 2> pattern;
  double l = 0.0;         // deformed length
  double l0 = 0.0;        // rest length
  Vec3 n = Vec3::Zero();  // unit direction A → B (zero when l = 0)
  Vec2 u = Vec2::Zero();  // unit rest direction a → b
};

}  // namespace

SeamSpringEnergy::SeamSpringEnergy(std::shared_ptr<const GarmentTopology> topology,
                                   const Points2& rest, SeamMaterial material)
    : RestDependentEnergy(rest), topology_(std::move(topology)), material_(material) {
  if (!topology_) throw std::invalid_argument("SeamSpringEnergy: null topology");
  if (!(material.width > 0.0) || !(material.depth > 0.0) || !(material.youngs_modulus >= 0.0))
    throw InputError(kSeamSource, "seam width and depth must be > 0 and Young's modulus >= 0");
  check_rest(rest);
}

SeamSpringEnergy::SeamSpringEnergy(std::vector<std::array<int, 2>> edges, const Points2& rest,
                                   std::vector<int> pattern_to_garment, int num_garment_vertices,
                                   SeamMaterial material)
    : SeamSpringEnergy(std::make_shared<const GarmentTopology>(one_piece_topology(
                           kSeamSource, rest.rows(), Triangles(0, 3), std::move(edges),
                           std::move(pattern_to_garment), num_garment_vertices)),
                       rest, material) {}

void SeamSpringEnergy::check_rest(const Points2& rest) const {
  const auto& edges = topology_->seam_edges;
  if (rest.rows() != topology_->num_pattern_vertices())
    throw InputError(kSeamSource, "rest positions have " + std::to_string(rest.rows()) +
                                      " rows, expected " +
                                      std::to_string(topology_->num_pattern_vertices()));
  for (std::size_t s = 0; s < edges.size(); ++s)
    if (!((rest.row(edges[s][1]) - rest.row(edges[s][0])).norm() > 0.0))
      throw InputError(kSeamSource, "seam edge " + std::to_string(s) + " has zero rest length");
}

void SeamSpringEnergy::check_x(const VecX& x) const {
  if (x.size() != 3 * static_cast<Eigen::Index>(topology_->num_garment_vertices))
    throw std::invalid_argument("SeamSpringEnergy: position vector has " +
                                std::to_string(x.size()) + " entries, expected 3 x " +
                                std::to_string(topology_->num_garment_vertices));
}

namespace {

template <typename Fn>
void for_each_spring(const std::vector<std::array<int, 2>>& edges, const Points2& rest,
                     const std::vector<int>& to_garment, const VecX& x, Fn&& fn) {
  for (const auto& e : edges) {
    Spring s;
    s.pattern = e;
    s.garment = {to_garment[e[0]], to_garment[e[1]]};
    const Vec3 d = x.segment<3>(3 * s.garment[1]) - x.segment<3>(3 * s.garment[0]);
    const Vec2 d0 = (rest.row(e[1]) - rest.row(e[0])).transpose();
    s.l = d.norm();
    s.l0 = d0.norm();
    if (s.l > 0.0) s.n = d / s.l;
    s.u = d0 / s.l0;
    fn(s);
  }
}

}  // namespace

double SeamSpringEnergy::value(const VecX& x) const {
  check_x(x);
  double total = 0.0;
  for_each_spring(edges(), rest(), topology_->pattern_to_garment, x,
                  [&](const Spring& s) { total += (s.l - s.l0) * (s.l - s.l0) / s.l0; });
  return 0.5 * axial_stiffness() * total;
}

void SeamSpringEnergy::add_gradient(const VecX& x, VecX& g) const {
  check_x(x);
  check_x(g);
  const double ka = axial_stiffness();
  for_each_spring(edges(), rest(), topology_->pattern_to_garment, x, [&](const Spring& s) {
    const Vec3 f = ka * (s.l - s.l0) / s.l0 * s.n;  // dU/dx_B
    g.segment<3>(3 * s.garment[1]) += f;
    g.segment<3>(3 * s.garment[0]) -= f;
  });
}

void SeamSpringEnergy::add_hessian(const VecX& x, std::vector<Triplet>& H, bool project_psd) const {
  check_x(x);
  H.reserve(H.size() + 36 * edges().size());
  const double ka = axial_stiffness();
  for_each_spring(edges(), rest(), topology_->pattern_to_garment, x, [&](const Spring& s) {
    Mat3 k = Mat3::Zero();
    if (s.l > 0.0) {
      const Mat3 nn = s.n * s.n.transpose();
      k = ka / s.l0 * nn + ka * (s.l - s.l0) / (s.l0 * s.l) * (Mat3::Identity() - nn);
    }
    Eigen::Matrix<double, 6, 6> local;
    local << k, -k, -k, k;
    if (project_psd) tightfit::project_psd(local);
    scatter_hessian<3>(s.garment, local, H);
  });
}

void SeamSpringEnergy::add_gradient_rest(const VecX& x, VecX& g_rest) const {
  check_x(x);
  if (g_rest.size() != 2 * rest().rows())
    throw std::invalid_argument("SeamSpringEnergy::add_gradient_rest: wrong vector size");
  const double ka = axial_stiffness();
  for_each_spring(edges(), rest(), topology_->pattern_to_garment, x, [&](const Spring& s) {
    const double ratio = s.l / s.l0;
    const Vec2 f = 0.5 * ka * (1.0 - ratio * ratio) * s.u;  // dU/dXbar_b
    g_rest.segment<2>(2 * s.pattern[1]) += f;
    g_rest.segment<2>(2 * s.pattern[0]) -= f;
  });
}

void SeamSpringEnergy::add_mixed_rest(const VecX& x, std::vector<Triplet>& H) const {
  check_x(x);
  H.reserve(H.size() + 24 * edges().size());
  const double ka = axial_stiffness();
  for_each_spring(edges(), rest(), topology_->pattern_to_garment, x, [&](const Spring& s) {
    // d²U/dl dl0 = -k_a l / l0², dl/dx_B = n, dl0/dXbar_b = u.
    const Eigen::Matrix<double, 3, 2> b = -ka * s.l / (s.l0 * s.l0) * s.n * s.u.transpose();
    Eigen::Matrix<double, 6, 4> local;
    local << b, -b, -b, b;
    scatter_block<3, 2, 2, 2>(s.garment, s.pattern, local, H);
  });
}

}  // namespace tightfit
