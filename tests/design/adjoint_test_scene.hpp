#pragma once
/// Small sleeve-on-cylinder scenes and test-only design terms for the adjoint and
/// optimizer tests. The design layer's tests cannot use the objectives layer (it is
/// built on top of design), so the x-dependent terms here are local: a target-position
/// term (x only) and the cloth elastic energy as a design term (x and Xbar).
#include <memory>
#include <string>

#include "tightfit/body/body_builder.hpp"
#include "tightfit/body/generators.hpp"
#include "tightfit/garment/primitive_garments.hpp"
#include "tightfit/objectives/design_term.hpp"
#include "tightfit/objectives/regularizer_compactness.hpp"
#include "tightfit/objectives/regularizer_edge_lengths.hpp"
#include "tightfit/objectives/regularizer_smoothness.hpp"
#include "tightfit/physics/cloth_energy.hpp"
#include "tightfit/physics/fabric_law.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit::test {

/// A body, its limit surface and a sleeve simulation on it (not movable: the
/// simulation refers to the body and surface).
struct SleeveScene {
  Body body;
  std::unique_ptr<LimitSurface> surface;
  std::unique_ptr<GarmentSimulation> sim;
};

struct SleeveSceneOptions {
  bool soft_body = false;      ///< tetrahedral Neo-Hookean body instead of a rigid one
  double hoop_scale = 0.9;     ///< rest circumference / body circumference
  double axial_scale = 0.95;   ///< rest length / sleeve length (< 1: axially taut)
  double edge_length = 0.016;  ///< sleeve rest edge (m)
  double jitter = 0.3;         ///< irregularity of the sleeve mesh (SleeveParams::jitter)
  double relative_force_tolerance = 1e-12;
  /// A measured knit instead of the isotropic fabric (null: isotropic).
  std::shared_ptr<const MeasuredFabric> measured;
};

/// A sleeve of length 8 cm around a capsule of radius 5 cm, both end rings pinned.
inline std::unique_ptr<SleeveScene> make_sleeve_scene(const SleeveSceneOptions& o = {}) {
  auto scene = std::make_unique<SleeveScene>();
  CylinderParams cyl;
  cyl.radius = 0.05;
  cyl.length = 0.16;
  cyl.edge_length = 0.014;
  if (o.soft_body) {
    scene->body = cylinder_body(cyl);  // core: vertices deeper than 15 mm pinned
  } else {
    scene->body.surface = cylinder_surface(cyl);
    scene->body.volume.vertices = scene->body.surface.vertices;
    scene->body.volume.tets.resize(0, 4);
  }
  scene->surface = std::make_unique<LimitSurface>(scene->body.surface);
  SleeveParams sleeve;
  sleeve.radius = cyl.radius;
  sleeve.axial_begin = -0.04;
  sleeve.axial_end = 0.04;
  sleeve.hoop_scale = o.hoop_scale;
  sleeve.axial_scale = o.axial_scale;
  sleeve.edge_length = o.edge_length;
  sleeve.jitter = o.jitter;
  sleeve.pin_first_ring = sleeve.pin_last_ring = true;
  Garment garment = make_sleeve(sleeve, *scene->surface, scene->body.surface.vertices);
  SimulationMaterials materials;
  materials.rigid_body = !o.soft_body;
  if (o.measured) {
    materials.fabric.measured = o.measured;
    materials.fabric.thickness = 5e-4;
  }
  materials.seam.youngs_modulus = 1e6;  // seam springs on: a second rest-dependent energy
  NewtonOptions newton;
  newton.relative_force_tolerance = o.relative_force_tolerance;
  newton.absolute_force_tolerance = 0.0;
  scene->sim = std::make_unique<GarmentSimulation>(scene->body, *scene->surface, std::move(garment),
                                                   materials, newton);
  return scene;
}

/// T = ½ Σ_i ‖x_i − t_i‖² (m²): garment positions towards fixed targets. Depends on x only.
class TargetPositionTerm : public DesignTerm {
 public:
  explicit TargetPositionTerm(VecX targets) : targets_(std::move(targets)) {}
  std::string name() const override { return "target positions"; }
  double value(const DesignState& s) const override { return 0.5 * (s.x - targets_).squaredNorm(); }
  void add_gradient(const DesignState& s, VecX& d_x, VecX&) const override {
    d_x += s.x - targets_;
  }
  bool depends_on_positions() const override { return true; }

 private:
  VecX targets_;
};

/// The cloth's elastic energy U_cloth(x, Xbar) (J) as a design term: depends on x and
/// Xbar, with FD-tested derivatives from the physics layer.
class ClothEnergyTerm : public DesignTerm {
 public:
  explicit ClothEnergyTerm(const Garment& g, ClothMaterial material = {})
      : topology_(g.topology), material_(material) {}
  std::string name() const override { return "cloth energy"; }
  double value(const DesignState& s) const override { return at(s).value(s.x); }
  void add_gradient(const DesignState& s, VecX& d_x, VecX& d_rest) const override {
    const ClothEnergy e = at(s);
    e.add_gradient(s.x, d_x);
    e.add_gradient_rest(s.x, d_rest);
  }
  bool depends_on_positions() const override { return true; }

 private:
  ClothEnergy at(const DesignState& s) const { return ClothEnergy(topology_, s.rest, material_); }
  std::shared_ptr<const GarmentTopology> topology_;
  ClothMaterial material_;
};

/// Targets: the current garment positions turned by `angle` (rad) about the z axis and
/// shifted by `dz` (m) along it (tangential on the cylinder, so reachable by sliding).
inline VecX turned_targets(const GarmentSimulation& sim, double angle, double dz) {
  const Points3& x = sim.garment_positions();
  VecX t(x.size());
  const double c = std::cos(angle), s = std::sin(angle);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    t.segment<3>(3 * i) = Vec3(c * x(i, 0) - s * x(i, 1), s * x(i, 0) + c * x(i, 1), x(i, 2) + dz);
  return t;
}

/// The four regularizers of paper Sec. 4.1 on the garment, named by their term names.
inline std::vector<std::shared_ptr<const DesignTerm>> regularizers(const Garment& g) {
  return {std::make_shared<EdgeLengthDifferenceTerm>(seam_length_regularizer(g)),
          std::make_shared<EdgeLengthDifferenceTerm>(even_spacing_regularizer(g)),
          std::make_shared<BoundarySmoothnessRegularizer>(g),
          std::make_shared<CompactnessRegularizer>(g, CompactnessOptions{0.5, 1})};
}

}  // namespace tightfit::test
