#pragma once
/// The fabric as a run reports it (result.json's "fabric", the report's fabric section):
/// the model and its parameters, for a measured knit its strip-test curves (loading and
/// the worn branch the simulation used), and the working points of the fitted garment —
/// per pressure region (and for the whole garment) the area-weighted median strain across
/// the grain (course) and along it (wale) and, for a measured knit, the worn curves'
/// tension at those strains.
///
///   {"model": "isotropic" | "measured", "name", "source", "thickness_m", "relaxation",
///    isotropic: "youngs_modulus_pa_simulated", "youngs_modulus_pa_new", "poisson_ratio";
///    measured: "coupling", "shear_n_per_m",
///              "curves": {"course" | "wale": {"loading": {"strain", "tension_n_per_m"},
///                                             "worn": {...},
///                                             "sampled": {"strain", "loading", "worn"}}},
///    "working_points": [{"region", "area_m2", "course": {"strain", "tension_n_per_m"},
///                        "wale": {...}}]}
/// Strains are engineering strains (stretch − 1); tensions N/m of rest width.
#include <nlohmann/json.hpp>
#include <vector>

#include "tightfit/physics/cloth_analysis.hpp"
#include "tightfit/physics/relaxed_stvk.hpp"
#include "tightfit/report/fit_view.hpp"

namespace tightfit {

/// `worn` is the fabric the simulation used, `document` the scene's "fabric" object (its
/// name, source and relaxation; may be null), `elements` the fitted garment's faces and
/// `regions` the pressure regions (the first working point is the whole garment's).
nlohmann::json fabric_json(const ClothMaterial& worn, const nlohmann::json& document,
                           const std::vector<ClothElementFit>& elements,
                           const std::vector<FitRegion>& regions);

}  // namespace tightfit
