#pragma once
/// The plot of a fabric fit (scene/fabric_fit.hpp) as an SVG document: per direction
/// (wale orange, course blue, bias green) the strip-test samples of the fitted cycle as a
/// thin line and the fitted curves through their points — loading solid, unloading
/// dashed — as the fabric law interpolates them; tension (N/m) against strain (%).
#include <string>

#include "tightfit/scene/fabric_fit.hpp"

namespace tightfit {

/// The SVG text (a standalone document, 720 × 440 px) titled `title`.
std::string fabric_fit_svg(const FabricFit& fit, const std::string& title);

}  // namespace tightfit
