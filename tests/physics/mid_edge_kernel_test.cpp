// The templated mid-edge and element pressure kernels (physics/mid_edge_kernel.hpp,
// physics/element_pressure.hpp) and the shared edge topology (mid_edge_topology.hpp):
// the autodiff scalar gives the double values, its derivatives match finite
// differences, and the face-local form matches MidEdgeShapeOperator on a mesh.
#include "tightfit/physics/mid_edge_kernel.hpp"

#include <gtest/gtest.h>

#include <memory>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "support/finite_difference.hpp"
#include "test_surfaces.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/physics/autodiff.hpp"
#include "tightfit/physics/element_pressure.hpp"
#include "tightfit/physics/mid_edge_shape_operator.hpp"
#include "tightfit/physics/mid_edge_topology.hpp"

namespace tightfit::mid_edge_kernel_test {

using autodiff::Mat32T;
using autodiff::Mat3T;
using autodiff::Vec3T;
using mid_edge::FaceOperator;

constexpr int kPoints = 18;  // six 3D points
using Ad = autodiff::Scalar<kPoints>;

/// A bent patch: face (0, 1, 2) and the three vertices across its edges, off its plane
/// on both sides (positions in m, 18 entries: point k at 3k..3k+2).
VecX patch_points() {
  VecX p(kPoints);
  p << 0.0, 0.0, 0.0,         //
      0.011, 0.001, 0.0,      //
      0.004, 0.009, 0.001,    //
      0.009, -0.008, 0.003,   // across edge 0 (0 → 1)
      0.013, 0.011, 0.004,    // across edge 1 (1 → 2)
      -0.007, 0.004, -0.002;  // across edge 2 (2 → 0; unused, a boundary edge here)
  return p;
}

template <typename S>
std::array<Vec3T<S>, 6> as_array(const Eigen::Matrix<S, Eigen::Dynamic, 1>& p) {
  std::array<Vec3T<S>, 6> a;
  for (int v = 0; v < 6; ++v) a[v] = p.template segment<3>(3 * v);
  return a;
}

constexpr std::array<bool, 3> kAllAcross = {true, true, false};  // edge 2 on the boundary
constexpr std::array<int, 3> kSigns = {1, -1, 1};
constexpr std::array<double, 3> kPhi = {0.03, -0.02, 0.05};

/// Λ (9 entries, column-major), area, θ_0..2 of the patch as one vector.
template <typename S>
Eigen::Matrix<S, 13, 1> kernel_outputs(const FaceOperator<S>& op) {
  Eigen::Matrix<S, 13, 1> out;
  const Mat3T<S> lambda = mid_edge::shape_operator(op, kSigns, kPhi);
  for (int k = 0; k < 9; ++k) out[k] = lambda(k % 3, k / 3);
  out[9] = op.area;
  for (int i = 0; i < 3; ++i) out[10 + i] = op.theta[i];
  return out;
}

VecX outputs_of(const VecX& p) {
  return kernel_outputs(mid_edge::face_operator<double>(as_array<double>(p), kAllAcross, 0));
}

TEST(MidEdgeKernel, AutodiffScalarGivesTheDoubleValues) {
  const VecX p = patch_points();
  Eigen::Matrix<Ad, Eigen::Dynamic, 1> pa(kPoints);
  for (int k = 0; k < kPoints; ++k) pa[k] = autodiff::variable<kPoints>(p[k], k);
  const FaceOperator<double> op =
      mid_edge::face_operator<double>(as_array<double>(p), kAllAcross, 0);
  const FaceOperator<Ad> opa = mid_edge::face_operator<Ad>(as_array<Ad>(pa), kAllAcross, 0);
  EXPECT_NEAR(opa.area.value(), op.area, 1e-15 * op.area);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(opa.theta[i].value(), op.theta[i], 1e-14) << i;
    for (int k = 0; k < 9; ++k)
      EXPECT_NEAR(opa.b[i](k).value(), op.b[i](k), 1e-13 * op.b[i].norm()) << i << " " << k;
  }
  EXPECT_GT(std::abs(op.theta[0]), 0.1);  // the patch is bent
  EXPECT_GT(std::abs(op.theta[1]), 0.1);
  EXPECT_EQ(op.theta[2], 0.0);  // boundary edge
  const Mat3 g = mid_edge::gram(op);
  const Mat3T<Ad> ga = mid_edge::gram(opa);
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(ga(k).value(), g(k), 1e-13 * g.norm());
}

TEST(MidEdgeKernel, AutodiffDerivativesMatchFiniteDifferences) {
  const VecX p = patch_points();
  Eigen::Matrix<Ad, Eigen::Dynamic, 1> pa(kPoints);
  for (int k = 0; k < kPoints; ++k) pa[k] = autodiff::variable<kPoints>(p[k], k);
  const Eigen::Matrix<Ad, 13, 1> out =
      kernel_outputs(mid_edge::face_operator<Ad>(as_array<Ad>(pa), kAllAcross, 0));
  Eigen::MatrixXd jacobian(13, kPoints);
  for (int r = 0; r < 13; ++r) jacobian.row(r) = out[r].derivatives().transpose();
  const test::FdCheck check = test::check_jacobian(outputs_of, jacobian, p, 1e-6);
  EXPECT_LT(check.relative_error, 1e-7) << check.analytic << "\n\n" << check.numeric;
  EXPECT_GT(check.fd_norm, 1.0);
}

/// `v` with every coordinate moved by up to `amount` (m).
Points3 jittered(const Points3& v, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  Points3 out = v;
  for (Eigen::Index k = 0; k < out.size(); ++k) out.data()[k] += u(rng);
  return out;
}

TEST(MidEdgeKernel, FaceLocalFormMatchesTheMeshOperator) {
  // An irregular open cylinder: interior and boundary edges, both signs.
  const test::CylinderMesh m = test::cylinder_mesh(0.05, 0.1, 2.0, 12, 6, 0.3, true, 3);
  const Points3 v = jittered(m.garment, 1e-3, 5);
  MidEdgeShapeOperator op(m.garment_faces, static_cast<int>(v.rows()));
  const std::vector<Mat3> lambda = op.compute(v);
  const MidEdgeTopology& topo = op.topology();
  const VecX& phi = op.edge_variables();
  double scale = 0.0;
  for (const Mat3& l : lambda) scale = std::max(scale, l.norm());
  EXPECT_GT(scale, 5.0);
  for (int f = 0; f < topo.num_faces(); ++f) {
    std::array<Vec3, 6> p;
    std::array<bool, 3> has_across;
    std::array<double, 3> phi_f;
    for (int i = 0; i < 3; ++i) {
      p[i] = v.row(m.garment_faces(f, i)).transpose();
      const int a = topo.across_vertex(f, i);
      has_across[i] = a >= 0;
      EXPECT_EQ(has_across[i], !topo.is_boundary(f, i));
      p[3 + i] = a >= 0 ? Vec3(v.row(a).transpose()) : Vec3::Zero();
      phi_f[i] = phi[topo.edge(f, i)];
    }
    const FaceOperator<double> local = mid_edge::face_operator<double>(p, has_across, f);
    const FaceOperator<double>& global = op.face_operators()[f];
    EXPECT_NEAR(local.area, global.area, 1e-12 * global.area);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(local.theta[i], global.theta[i], 1e-12) << f << " " << i;
      EXPECT_LT((local.b[i] - global.b[i]).norm(), 1e-12 * global.b[i].norm());
    }
    const Mat3 l = mid_edge::shape_operator(local, topo.signs(f), phi_f);
    EXPECT_LT((l - lambda[f]).norm(), 1e-10 * scale) << f;
  }
}

TEST(MidEdgeTopology, EdgeUnknownsSignsAndVerticesAcross) {
  // The unit square split along its diagonal 0-2.
  Triangles faces(2, 3);
  faces << 0, 1, 2, 0, 2, 3;
  const MidEdgeTopology topo(faces, 4);
  EXPECT_EQ(topo.num_faces(), 2);
  EXPECT_EQ(topo.num_edges(), 5);
  // The diagonal: face 0 edge 2 (2 → 0), face 1 edge 0 (0 → 2).
  EXPECT_EQ(topo.edge(0, 2), topo.edge(1, 0));
  EXPECT_EQ(topo.sign(0, 2), 1);
  EXPECT_EQ(topo.sign(1, 0), -1);
  EXPECT_EQ(topo.across(0, 2), 3);
  EXPECT_EQ(topo.across(1, 0), 2);
  EXPECT_EQ(topo.across_vertex(0, 2), 3);
  EXPECT_EQ(topo.across_vertex(1, 0), 1);
  EXPECT_EQ(topo.edge_face_edges()[topo.edge(0, 2)], 2);
  for (int i : {0, 1}) {
    EXPECT_TRUE(topo.is_boundary(0, i));
    EXPECT_EQ(topo.across_vertex(0, i), -1);
    EXPECT_EQ(topo.sign(0, i), 1);
  }
  EXPECT_EQ(topo.signs(1), (std::array<int, 3>{-1, 1, 1}));
  std::vector<bool> seen(topo.num_edges(), false);
  for (int f = 0; f < 2; ++f)
    for (int e : topo.edges(f)) seen[e] = true;
  EXPECT_EQ(std::count(seen.begin(), seen.end(), true), 5);
}

TEST(MidEdgeTopology, RejectsBadMeshes) {
  Triangles inconsistent(2, 3);
  inconsistent << 0, 1, 2, 0, 1, 3;
  EXPECT_THROW(MidEdgeTopology(inconsistent, 4), InputError);
  Triangles out_of_range(1, 3);
  out_of_range << 0, 1, 4;
  EXPECT_THROW(MidEdgeTopology(out_of_range, 4), InputError);
  Triangles repeated(1, 3);
  repeated << 0, 1, 1;
  EXPECT_THROW(MidEdgeTopology(repeated, 4), InputError);
}

/// A taut element: F stretches 15 % along one in-plane direction, 5 % across, sheared.
Mat32 taut_gradient() {
  Mat32 F;
  F << 1.12, 0.06, 0.04, 1.03, 0.1, -0.2;
  return F;
}

Mat3 some_shape_operator() {
  Mat3 l;
  l << 20.0, 1.5, -2.0, 1.5, 8.0, 0.5, -2.0, 0.5, 3.0;
  return l;
}

constexpr int kEntries = 6;  // entries of F
using AdF = autodiff::Scalar<kEntries>;

/// A measured knit (fabric_law.hpp) with unloading branches, so the worn curves are used.
ClothMaterial measured_knit() {
  ClothMaterial m;
  m.thickness = 5e-4;
  m.measured = std::make_shared<MeasuredFabric>(
      MeasuredFabric{"test knit", FabricCurve({0.0, 0.2, 0.5, 1.0}, {0.0, 40.0, 130.0, 420.0}),
                     FabricCurve({0.0, 0.2, 0.5, 1.0}, {0.0, 25.0, 80.0, 260.0}),
                     FabricCurve({0.0, 0.2, 0.5, 1.0}, {0.0, 30.0, 100.0, 400.0}),
                     FabricCurve({0.0, 0.2, 0.5, 1.0}, {0.0, 18.0, 60.0, 250.0}), 0.3, 30.0});
  return m;
}

void expect_autodiff_pressure_matches(const FabricLaw& law) {
  const Mat32 F = taut_gradient();
  const Mat3 lambda = some_shape_operator();
  const Mat2 C = F.transpose() * F;
  const Mat3 sigma = *cauchy_stress<double>(law, F);
  const Mat3 reference = F * law.second_piola(C) * F.transpose() / std::sqrt(C.determinant());
  EXPECT_LT((sigma - reference).norm(), 1e-12 * reference.norm());
  EXPECT_GT(reference.norm(), 1e4);  // taut: Pa
  const double p = *element_pressure<double>(law, F, lambda);
  EXPECT_NEAR(p, law.material().thickness * sigma.cwiseProduct(lambda).sum(), 1e-12 * std::abs(p));

  Mat32T<AdF> Fa;
  for (int k = 0; k < kEntries; ++k) Fa(k) = autodiff::variable<kEntries>(F(k), k);
  const AdF pa = *element_pressure<AdF>(law, Fa, lambda.cast<AdF>());
  EXPECT_NEAR(pa.value(), p, 1e-13 * std::abs(p));
  const Mat3T<AdF> sigma_a = *cauchy_stress<AdF>(law, Fa);
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(sigma_a(k).value(), sigma(k), 1e-12 * sigma.norm());

  const test::ScalarFunction pressure = [&](const VecX& f) {
    return *element_pressure<double>(law, Eigen::Map<const Mat32>(f.data()), lambda);
  };
  const VecX f0 = Eigen::Map<const VecX>(F.data(), kEntries);
  const test::FdCheck check = test::check_gradient(pressure, pa.derivatives(), f0, 1e-6);
  EXPECT_LT(check.relative_error, 1e-7) << check.analytic << "\n\n" << check.numeric;
}

TEST(ElementPressure, AutodiffScalarGivesTheDoubleValuesAndTheirDerivatives) {
  expect_autodiff_pressure_matches(FabricLaw(ClothMaterial{}));
  expect_autodiff_pressure_matches(FabricLaw(measured_knit()));
}

TEST(ElementPressure, DegenerateElementHasNoStress) {
  const FabricLaw law(ClothMaterial{});
  Mat32 F;
  F << 1.0, 2.0, 0.0, 0.0, 0.0, 0.0;  // rank one
  EXPECT_FALSE(cauchy_stress<double>(law, F).has_value());
  EXPECT_FALSE(element_pressure<double>(law, F, some_shape_operator()).has_value());
}

}  // namespace tightfit::mid_edge_kernel_test
