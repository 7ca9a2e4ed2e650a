#include "tightfit/patterns/scene_options.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "tightfit/scene/body_up.hpp"

namespace tightfit {
namespace {

Vec3 position_of(const Garment& garment, const Points3& positions, int piece, int vertex) {
  const int global = garment.topology->piece_offset[static_cast<size_t>(piece)] + vertex;
  return positions.row(garment.topology->pattern_to_garment[static_cast<size_t>(global)])
      .transpose();
}

/// Reads "min" (default 1) and "max" of a stretch objective into the label.
void read_stretch(const nlohmann::json& objective, PatternLabelInfo& label) {
  if (!objective.is_object()) return;
  label.stretch_min = objective.value("min", 1.0);
  label.stretch_max = objective.contains("max") && objective["max"].is_number()
                          ? objective["max"].get<double>()
                          : 0.0;
}

/// A seam is on the back when the garment there faces more than 60° away from the front
/// (its outward normal · front < −cos 60°): side seams and inseams face sideways.
constexpr double kBackFacing = 0.5;

}  // namespace

Vec3 body_front_direction(const BodySpec& spec) {
  return spec.source == BodySource::kMesh ? Vec3(Vec3::UnitZ()) : Vec3(Vec3::Zero());
}

std::map<std::string, NotchStyle> classify_seam_notches(const Garment& garment,
                                                        const Points3& positions,
                                                        const Vec3& front) {
  std::map<std::string, NotchStyle> out;
  const Vec3 centroid =
      positions.rows() > 0 ? Vec3(positions.colwise().mean().transpose()) : Vec3(Vec3::Zero());
  // Area-weighted normals of the garment surface at its vertices, turned outward: the
  // orientation whose triangles face away from the centroid on the whole (positive
  // signed volume, as the body's surface is oriented).
  Points3 normals = Points3::Zero(positions.rows(), 3);
  const Triangles& faces = garment.topology->garment_triangles;
  double volume = 0.0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Vec3 a = positions.row(faces(f, 0)).transpose(),
               b = positions.row(faces(f, 1)).transpose(),
               c = positions.row(faces(f, 2)).transpose();
    const Vec3 n = (b - a).cross(c - a);
    volume += n.dot((a + b + c) / 3.0 - centroid);
    for (int k = 0; k < 3; ++k) normals.row(faces(f, k)) += n.transpose();
  }
  if (volume < 0.0) normals = -normals;
  for (const Seam& seam : garment.pattern.seams) {
    Vec3 normal = Vec3::Zero();
    for (int v : seam.a.vertices) {
      const int global = garment.topology->piece_offset[static_cast<size_t>(seam.a.piece)] + v;
      normal += normals.row(garment.topology->pattern_to_garment[static_cast<size_t>(global)])
                    .transpose();
    }
    const double facing = normal.norm() > 0.0 ? normal.normalized().dot(front) : 0.0;
    const bool back = front.norm() > 0.0 && facing < -kBackFacing;
    out[seam.name] = back ? NotchStyle::kDouble : NotchStyle::kSingle;
  }
  return out;
}

std::map<std::string, bool> seam_upper_ends(const Garment& garment, const Points3& positions,
                                            const Vec3& up, double min_rise) {
  std::map<std::string, bool> out;
  for (const Seam& seam : garment.pattern.seams) {
    if (seam.a.vertices.empty()) continue;
    const Vec3 first = position_of(garment, positions, seam.a.piece, seam.a.vertices.front());
    const Vec3 last = position_of(garment, positions, seam.a.piece, seam.a.vertices.back());
    const double rise = (last - first).dot(up);
    if (std::abs(rise) >= min_rise) out[seam.name] = rise > 0.0;
  }
  return out;
}

PatternExportOptions scene_pattern_export_options(const SceneSpec& scene, const Garment& garment,
                                                  const Points3& positions,
                                                  const std::string& date) {
  check_pattern_export_spec(scene.patterns, garment.pattern);
  PatternExportOptions options = scene.patterns.options;
  const std::map<std::string, NotchStyle> explicit_styles = options.seam_notch_styles;
  options.seam_notch_styles =
      classify_seam_notches(garment, positions, body_front_direction(scene.body));
  for (const auto& [name, style] : explicit_styles) options.seam_notch_styles[name] = style;
  if (scene.body.source != BodySource::kSphere)
    options.seam_last_end_up = seam_upper_ends(garment, positions, body_up_direction(scene.body));

  PatternLabelInfo& label = options.label;
  label.style = scene.patterns.style.empty() ? std::filesystem::path(scene.file).stem().string()
                                             : scene.patterns.style;
  label.size = scene.patterns.size;
  if (label.size.empty()) {
    switch (scene.body.source) {
      case BodySource::kMesh:
        label.size = scene.body.mesh.path.stem().string();
        break;
      case BodySource::kCylinder:
        label.size = "cylinder";
        break;
      case BodySource::kSphere:
        label.size = "sphere";
        break;
    }
  }
  label.date = date;
  double relaxation = 0.0;
  if (const auto fabric = scene.document.find("fabric");
      fabric != scene.document.end() && fabric->is_object())
    relaxation = fabric->value("relaxation", 0.0);
  label.youngs_modulus = scene.materials.fabric.youngs_modulus / (1.0 - relaxation);
  label.thickness = scene.materials.fabric.thickness;
  if (scene.optimize.is_object()) {
    if (const auto objectives = scene.optimize.find("objectives");
        objectives != scene.optimize.end() && objectives->is_object()) {
      if (objectives->contains("directional_stretch"))
        read_stretch((*objectives)["directional_stretch"], label);
      if (objectives->contains("stretch")) read_stretch((*objectives)["stretch"], label);
    }
  }
  return options;
}

}  // namespace tightfit
