#pragma once
/// Fit analysis of the cloth at a state x: per element principal stretches and their
/// 3D directions, regime, stresses and membrane tension; pressure on the body from the
/// generalized Young-Laplace equation (paper Eq. 31) and, for comparison, from vertex
/// forces over vertex areas.
///
/// Units: stretches dimensionless (1.3 = 30 % stretch); stress Pa; tension N/m (force
/// per unit deformed length); shape operators 1/m; pressure Pa (1 mmHg = kPascalPerMmHg Pa).
/// Pressure sign: positive when the fabric presses onto a convex body, i.e. with the
/// garment faces oriented counter-clockwise seen from outside (outward normals). A
/// negative pressure means the fabric would lift off; it is reported, never clamped.
#include <vector>

#include "tightfit/physics/cloth_energy.hpp"
#include "tightfit/physics/mid_edge_shape_operator.hpp"

namespace tightfit {

/// State of one cloth element.
struct ClothElementFit {
  Vec2 stretch = Vec2::Ones();  ///< principal stretches s1 >= s2 (sqrt of eig(C))
  /// Stretches of the pattern's axes, (√C_xx, √C_yy): across the grain (the course of a
  /// knit) and along it (the wale), every piece lying in its grain frame.
  Vec2 grain_stretch = Vec2::Ones();
  Vec3 direction1 = Vec3::UnitX();           ///< unit 3D direction of s1 in the deformed element
  Vec3 direction2 = Vec3::UnitY();           ///< unit 3D direction of s2 (= normal × direction1)
  Vec3 normal = Vec3::UnitZ();               ///< unit normal of the deformed element (vertex order)
  ClothRegime regime = ClothRegime::kSlack;  ///< unsmoothed regime of Eq. 10
  /// Cauchy stress σ = F S Fᵀ / J (3×3, Pa, tangent to the element) of the relaxed
  /// material, S = 2 ∂W/∂C, J = s1 s2 the area ratio; uses the rest thickness t.
  Mat3 cauchy_stress = Mat3::Zero();
  /// Membrane tension T = t σ (3×3, N/m): the force per unit deformed length across a
  /// line with unit in-plane normal m is T m. Exact whatever the thickness change.
  Mat3 tension = Mat3::Zero();
  Vec2 principal_tension =
      Vec2::Zero();            ///< eigenvalues of T in the tangent plane (N/m), descending
  double rest_area = 0.0;      ///< m²
  double deformed_area = 0.0;  ///< m²
};

/// Per-element analysis of the cloth at x (3·n_garment), one entry per cloth triangle.
/// A degenerate deformed element (zero area) gets zero stress and tension.
std::vector<ClothElementFit> analyze_cloth(const ClothEnergy& cloth, const VecX& x);

/// Young-Laplace pressure per element (Eq. 31): p_e = t tr(σ_e Λ_e) = tr(T_e Λ_e) (Pa).
/// `shape_operators` one 3×3 world-frame operator per element (1/m), e.g. from
/// MidEdgeShapeOperator on the garment mesh, or the exact second fundamental form of the
/// limit surface expressed as the derivative of the unit outward normal.
VecX young_laplace_pressure(const std::vector<ClothElementFit>& fit,
                            const std::vector<Mat3>& shape_operators);

/// Mixed Voronoi area per vertex (Meyer et al. 2003; m²): Voronoi regions in
/// non-obtuse triangles, A/2 to the obtuse corner and A/4 to the others otherwise.
VecX mixed_voronoi_areas(const Points3& vertices, const Triangles& faces);

/// Unit area-weighted vertex normals (n×3) of a triangle mesh.
Points3 vertex_normals(const Points3& vertices, const Triangles& faces);

/// Discrete pressure per vertex (Pa): the normal component of the force the cloth
/// exerts on the body at the vertex, over its mixed Voronoi area. `gradient` is dU/dx
/// (3n) of the garment energies (cloth, seams): the internal force on the cloth is
/// -gradient, and the cloth pushes the body with the opposite of the body's reaction,
/// so p_i = (gradient_i · n_i) / A_i with n_i the outward vertex normal. Vertices with
/// no faces get 0.
VecX vertex_area_pressure(const Points3& vertices, const Triangles& faces, const VecX& gradient);

}  // namespace tightfit
