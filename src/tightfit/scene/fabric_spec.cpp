#include "tightfit/scene/fabric_spec.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "tightfit/physics/fabric_law.hpp"

namespace tightfit {
namespace {

/// The stiffest material a scene may name (Pa): beyond any fabric, skin or foam by far,
/// and low enough that energies, forces and their derivatives stay finite.
constexpr double kMaxModulus = 1e12;
constexpr const char* kModulusWhy = "stiffer than steel, about 2e11 Pa: not a garment or a body";
/// The thickest fabric a scene may name (m).
constexpr double kMaxThickness = 0.1;
/// The most points a strip-test curve may have (a fitted curve needs a few dozen).
constexpr std::size_t kMaxCurvePoints = 10000;
/// The highest tension a curve may reach (N/m): far beyond any textile (a seat belt
/// webbing breaks at about 5e5 N/m).
constexpr double kMaxTension = 1e7;

std::vector<double> number_array(JsonFields& f, const std::string& key) {
  const nlohmann::json& a = f.raw(key);
  if (a.is_null()) f.fail("is required", key);
  if (!a.is_array()) f.fail(std::string("expected an array of numbers, got ") + a.type_name(), key);
  if (a.size() > kMaxCurvePoints)
    f.fail(
        "has " + std::to_string(a.size()) + " points, more than " + std::to_string(kMaxCurvePoints),
        key);
  std::vector<double> out;
  out.reserve(a.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (!a[k].is_number())
      f.fail(std::string("expected a number, got ") + a[k].type_name(),
             key + "/" + std::to_string(k));
    out.push_back(a[k].get<double>());
  }
  return out;
}

FabricCurve parse_curve(JsonFields& f, double smoothing) {
  std::vector<double> strain = number_array(f, "strain");
  std::vector<double> tension = number_array(f, "tension_n_per_m");
  f.finish();
  for (std::size_t k = 0; k < tension.size(); ++k)
    if (std::abs(tension[k]) > kMaxTension)
      f.fail("is " + format_number(tension[k]) + " N/m, more than " + format_number(kMaxTension) +
                 " (no textile is that strong)",
             "tension_n_per_m/" + std::to_string(k));
  try {
    return FabricCurve(std::move(strain), std::move(tension), smoothing);
  } catch (const std::invalid_argument& e) {
    f.fail(e.what());
  }
}

FabricCurve required_curve(JsonFields& f, const std::string& key, double smoothing) {
  auto c = f.object(key, true);
  return parse_curve(*c, smoothing);
}

/// The loading curve scaled by (1 − r): the unloading branch that `relaxation` stands for.
FabricCurve relaxed(const FabricCurve& loading, double relaxation, double smoothing) {
  std::vector<double> tension = loading.tensions();
  for (double& t : tension) t *= 1.0 - relaxation;
  return FabricCurve(loading.strains(), std::move(tension), smoothing);
}

double relaxation_of(JsonFields& f) {
  const double relaxation = f.number("relaxation", 0.0);
  if (!(relaxation >= 0.0 && relaxation < 1.0)) f.fail("must lie in [0, 1)", "relaxation");
  return relaxation;
}

void parse_isotropic(JsonFields& f, FabricSpec& s) {
  ClothMaterial& m = s.material;
  for (const char* key : {"wale", "course", "coupling", "shear_n_per_m", "bias", "unloading"})
    if (f.has(key)) f.fail("belongs to a measured fabric (\"model\": \"measured\")", key);
  m.youngs_modulus = f.at_most("youngs_modulus", f.positive("youngs_modulus", m.youngs_modulus),
                               kMaxModulus, kModulusWhy);
  m.poisson_ratio = f.number("poisson_ratio", m.poisson_ratio);
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 1.0))
    f.fail("must lie in (-1, 1) for a membrane", "poisson_ratio");
  s.relaxation = relaxation_of(f);
  m.youngs_modulus *= 1.0 - s.relaxation;
}

void parse_measured(JsonFields& f, FabricSpec& s) {
  for (const char* key : {"youngs_modulus", "poisson_ratio"})
    if (f.has(key))
      f.fail("belongs to the isotropic model; a measured fabric has curves instead", key);
  const double smoothing = s.material.regime_smoothing;
  auto fabric = std::make_shared<MeasuredFabric>(MeasuredFabric{
      f.string("name", std::string("measured fabric")), required_curve(f, "wale", smoothing),
      required_curve(f, "course", smoothing), std::nullopt, std::nullopt, 0.0, 0.0});
  fabric->coupling = f.number("coupling", 0.0);
  if (!(fabric->coupling >= 0.0 && fabric->coupling < 1.0))
    f.fail("must lie in [0, 1)", "coupling");
  s.relaxation = relaxation_of(f);
  if (auto u = f.object("unloading")) {
    if (s.relaxation > 0.0)
      f.fail(
          "give either unloading curves or a relaxation, not both (a relaxation r is the "
          "unloading curves (1 - r) times the loading ones)",
          "unloading");
    if (!u->has("wale") && !u->has("course")) u->fail("needs a \"wale\" or a \"course\" curve");
    if (auto c = u->object("wale")) fabric->wale_unloading = parse_curve(*c, smoothing);
    if (auto c = u->object("course")) fabric->course_unloading = parse_curve(*c, smoothing);
    u->finish();
  } else if (s.relaxation > 0.0) {
    fabric->wale_unloading = relaxed(fabric->wale, s.relaxation, smoothing);
    fabric->course_unloading = relaxed(fabric->course, s.relaxation, smoothing);
  }
  const bool has_shear = f.has("shear_n_per_m"), has_bias = f.has("bias");
  if (has_shear == has_bias)
    f.fail(
        "needs exactly one of \"shear_n_per_m\" (N/m) and \"bias\" (a strip-test curve at "
        "45 degrees to the grain) for the in-plane shear stiffness");
  if (has_shear) {
    fabric->shear_n_per_m =
        f.at_most("shear_n_per_m", f.positive("shear_n_per_m"), kMaxTension, "N/m");
  } else {
    auto b = f.object("bias", true);
    const FabricCurve bias = parse_curve(*b, smoothing);
    fabric->shear_n_per_m = shear_from_bias(
        fabric->worn_course().initial_stiffness(), fabric->worn_wale().initial_stiffness(),
        fabric->coupling, bias.initial_stiffness() * (1.0 - s.relaxation));
    if (!(fabric->shear_n_per_m > 0.0))
      f.fail(
          "the bias strip is at least as stiff as the course, wale and coupling allow (its "
          "initial stiffness must lie below the series of the two directions): check the "
          "curves or give \"shear_n_per_m\"",
          "bias");
  }
  s.material.measured = std::move(fabric);
}

FabricSpec parse_fabric_object(JsonFields& f, const ClothMaterial& defaults) {
  FabricSpec s;
  s.material = defaults;
  s.material.measured = nullptr;
  const std::string model = f.choice("model", {"isotropic", "measured"}, "isotropic");
  f.string("source", std::string());
  f.string("description", std::string());
  if (model == "isotropic") f.string("name", std::string());
  ClothMaterial& m = s.material;
  m.thickness = f.at_most("thickness", f.positive("thickness", m.thickness), kMaxThickness,
                          "a fabric is thinner than 10 cm");
  m.regime_smoothing = f.positive("regime_smoothing", m.regime_smoothing);
  if (model == "isotropic")
    parse_isotropic(f, s);
  else
    parse_measured(f, s);
  f.finish();
  return s;
}

}  // namespace

double shear_from_bias(double course_stiffness, double wale_stiffness, double coupling,
                       double bias_stiffness) {
  const double kappa = coupling * std::sqrt(course_stiffness * wale_stiffness);
  const double det = course_stiffness * wale_stiffness - kappa * kappa;
  const double series = (course_stiffness + wale_stiffness - 2.0 * kappa) / (4.0 * det);
  const double shear_compliance = 4.0 * (1.0 / bias_stiffness - series);
  return shear_compliance > 0.0 ? 1.0 / shear_compliance : 0.0;
}

FabricSpec read_fabric_file(const std::filesystem::path& file, const ClothMaterial& defaults) {
  const nlohmann::json document = read_json_file(file.string());
  if (!document.is_object())
    throw InputError(file.string(),
                     std::string("a fabric file holds a JSON object, got ") + document.type_name());
  JsonFields f(document, file.string(), "");
  FabricSpec s = parse_fabric_object(f, defaults);
  s.file = file;
  s.document = document;
  return s;
}

FabricSpec parse_fabric_spec(const nlohmann::json& value, const std::string& scene_file,
                             const std::string& json_path, const std::filesystem::path& base_dir,
                             const ClothMaterial& defaults) {
  if (value.is_null())
    throw InputError(scene_file, json_path +
                                     ": is null (expected an object or the path of a "
                                     "fabric file)");
  if (value.is_string()) {
    const std::string name = value.get<std::string>();
    if (name.empty()) throw InputError(scene_file, json_path + ": must name a fabric file");
    std::filesystem::path file(name);
    if (file.is_relative()) file = base_dir / file;
    if (!std::filesystem::is_regular_file(file))
      throw InputError(scene_file, json_path + ": no such fabric file: " + file.string());
    return read_fabric_file(file, defaults);
  }
  if (!value.is_object())
    throw InputError(scene_file, json_path +
                                     ": expected an object or the path of a fabric file, "
                                     "got " +
                                     std::string(value.type_name()));
  JsonFields f(value, scene_file, json_path);
  FabricSpec s = parse_fabric_object(f, defaults);
  s.document = value;
  return s;
}

}  // namespace tightfit
