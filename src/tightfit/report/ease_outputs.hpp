#pragma once
/// The ease table of a fit (garment/ease_table.hpp) at the levels its scene asks for:
/// the scene's "measurements"; without that key the standard levels of the body's
/// skeleton (the body's "skeleton", else the scene's rig) that the garment reaches;
/// without a skeleton, or when the garment reaches none of them, planes normal to the
/// body's up direction (scene/body_up.hpp) every kMeasurementSpacing across the garment.
#include "tightfit/garment/ease_table.hpp"
#include "tightfit/scene/spec.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit {

/// Spacing of the levels by planes (m).
constexpr double kMeasurementSpacing = 0.05;

/// The ease table of `sim`'s fitted garment, measured on the body's limit surface at
/// rest (sampled at its control vertices). Garments with more pieces than
/// kMaxReportedPieces (covers) get no per-piece widths.
EaseTable fit_ease_table(const GarmentSimulation& sim, const SceneSpec& scene);

}  // namespace tightfit
