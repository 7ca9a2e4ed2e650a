#include "tightfit/patterns/scene_options.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>
#include <vector>

#include "tightfit/physics/fabric_law.hpp"
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

namespace {

/// The [5th, 95th] rest-area percentiles of a stretch per pattern triangle.
std::array<double, 2> percentile_range(std::vector<std::pair<double, double>> value_area) {
  std::sort(value_area.begin(), value_area.end());
  double total = 0.0;
  for (const auto& [v, a] : value_area) total += a;
  std::array<double, 2> out = {0.0, 0.0};
  if (!(total > 0.0)) return out;
  double below = 0.0;
  bool low_set = false;
  for (const auto& [v, a] : value_area) {
    below += a;
    if (!low_set && below >= 0.05 * total) {
      out[0] = v;
      low_set = true;
    }
    if (below >= 0.95 * total) {
      out[1] = v;
      break;
    }
  }
  return out;
}

}  // namespace

GrainStretchRanges grain_stretch_ranges(const Garment& garment, const Points3& positions) {
  const GarmentTopology& topology = *garment.topology;
  const Points2 rest = garment.rest_positions();
  std::vector<std::pair<double, double>> course, wale;
  for (Eigen::Index t = 0; t < topology.pattern_triangles.rows(); ++t) {
    const auto corner = [&](int k) { return topology.pattern_triangles(t, k); };
    Mat2 dm;
    dm.col(0) = (rest.row(corner(1)) - rest.row(corner(0))).transpose();
    dm.col(1) = (rest.row(corner(2)) - rest.row(corner(0))).transpose();
    const double area = 0.5 * std::abs(dm.determinant());
    if (!(area > 0.0)) continue;
    const auto placed = [&](int k) {
      return Vec3(positions.row(topology.pattern_to_garment[static_cast<std::size_t>(corner(k))]));
    };
    Mat32 ds;
    ds.col(0) = placed(1) - placed(0);
    ds.col(1) = placed(2) - placed(0);
    const Mat32 f = ds * dm.inverse();
    course.emplace_back(f.col(0).norm(), area);
    wale.emplace_back(f.col(1).norm(), area);
  }
  return {percentile_range(std::move(course)), percentile_range(std::move(wale))};
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
  label.thickness = scene.materials.fabric.thickness;
  if (const MeasuredFabric* knit = scene.materials.fabric.measured.get()) {
    label.fabric_name = knit->name;
    const GrainStretchRanges ranges = grain_stretch_ranges(garment, positions);
    label.course_stretch = ranges.course;
    label.wale_stretch = ranges.wale;
  } else {
    label.youngs_modulus = scene.materials.fabric.youngs_modulus / (1.0 - relaxation);
  }
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
