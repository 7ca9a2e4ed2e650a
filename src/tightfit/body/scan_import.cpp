#include "tightfit/body/scan_import.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tightfit/body/scan_repair.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_components.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit {
namespace {

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), pattern, value);
  return buffer;
}

/// A length of the file as "0.123 m" (`metres` per unit), or in the file's units when
/// they are not known (0).
std::string length(double value, double metres) {
  return metres > 0.0 ? format("%.3g m", value * metres) : format("%.4g units", value);
}

std::string point(const Vec3& p, double metres) {
  const double s = metres > 0.0 ? metres : 1.0;
  char buffer[128];
  std::snprintf(buffer, sizeof(buffer), "(%.4g, %.4g, %.4g)%s", p.x() * s, p.y() * s, p.z() * s,
                metres > 0.0 ? " m" : "");
  return buffer;
}

std::string describe(const SurfaceHole& hole, double metres) {
  return "boundary " + length(hole.boundary_length, metres) + ", " + std::to_string(hole.edges) +
         " edges, around " + point(hole.center, metres);
}

std::string describe_filled(const SurfaceHole& hole, double metres) {
  return describe(hole, metres) + (hole.faired ? "" : ", not faired: CGAL's fairing failed");
}

/// Units of a surface for messages: given, guessed, or 0 when the size does not say.
double units_for_messages(const TriMesh& mesh, const std::string& source, double given) {
  if (given > 0.0) return given;
  std::vector<std::string> ignored;
  try {
    return guess_units_to_metres(mesh, source, ignored);
  } catch (const InputError&) {
    return 0.0;
  }
}

/// The warning of a file of several parts: the kept one and the others left out.
std::string parts_warning(const std::string& source, std::size_t count, Eigen::Index kept_faces,
                          const std::string& others) {
  return source + ": the mesh has " + std::to_string(count) +
         " separate parts; kept the largest closed one (" + std::to_string(kept_faces) +
         " faces), left out: " + others;
}

std::string left_out(Eigen::Index faces, bool closed, double area, const std::string& others) {
  return others + (others.empty() ? "" : "; ") + std::to_string(faces) + " faces, " +
         (closed ? "closed" : "open") + ", area " + format("%.4g", area);
}

}  // namespace

TriMesh keep_largest_closed_component(const TriMesh& mesh, const std::string& source,
                                      std::vector<std::string>& warnings) {
  std::vector<MeshComponent> parts = connected_components(mesh);
  if (parts.size() <= 1) return mesh;
  int best = -1;
  double best_volume = 0.0;
  std::vector<bool> closed(parts.size());
  for (std::size_t k = 0; k < parts.size(); ++k) {
    closed[k] = SurfaceTopology(parts[k].mesh.faces, parts[k].mesh.num_vertices()).is_closed();
    const double volume = std::abs(signed_volume(parts[k].mesh));
    if (closed[k] && (best < 0 || volume > best_volume)) {
      best = static_cast<int>(k);
      best_volume = volume;
    }
  }
  if (best < 0)
    throw InputError(source, "the mesh has " + std::to_string(parts.size()) +
                                 " separate parts and none of them is closed (a body must be a "
                                 "closed surface)");
  std::string others;
  for (std::size_t k = 0; k < parts.size(); ++k)
    if (static_cast<int>(k) != best)
      others = left_out(parts[k].mesh.num_faces(), closed[k], surface_area(parts[k].mesh), others);
  warnings.push_back(parts_warning(source, parts.size(), parts[best].mesh.num_faces(), others));
  return std::move(parts[best].mesh);
}

TriMesh import_scan(const TriMesh& mesh, const std::string& source, double metres_per_file_unit,
                    std::vector<std::string>& warnings) {
  std::vector<FilledSurface> parts;
  {
    TriMesh repaired = repair_mesh_elements(mesh, source, warnings);
    std::vector<MeshComponent> components = connected_components(repaired);
    if (components.size() == 1) components[0].mesh = std::move(repaired);  // vertex order kept
    repaired = TriMesh();
    for (MeshComponent& component : components) {
      parts.push_back(fill_small_holes(component.mesh, source));
      component.mesh = TriMesh();
    }
  }
  std::size_t best = 0;
  for (std::size_t k = 1; k < parts.size(); ++k)
    if (parts[k].enclosed_volume > parts[best].enclosed_volume) best = k;
  FilledSurface& body = parts[best];
  if (!body.unfilled.empty()) {
    const double metres = units_for_messages(body.mesh, source, metres_per_file_unit);
    const SurfaceHole& largest = body.unfilled.front();
    throw InputError(
        source, "the body's surface is open: " + std::to_string(body.unfilled.size()) +
                    " hole(s) too large to fill, the largest with " + describe(largest, metres) +
                    " (holes are filled up to a boundary of " + length(body.hole_limit, metres) +
                    ", the circumference of a disc of " +
                    format("%.2g %%", 100 * kSmallHoleAreaShare) +
                    " of the surface's area); close the surface in the scan's software, e.g. "
                    "with a flat cap");
  }
  if (parts.size() > 1) {
    std::string others;
    for (std::size_t k = 0; k < parts.size(); ++k)
      if (k != best)
        others =
            left_out(parts[k].mesh.num_faces(), parts[k].unfilled.empty(), parts[k].area, others);
    warnings.push_back(parts_warning(source, parts.size(), body.mesh.num_faces(), others));
  }
  TriMesh surface = std::move(body.mesh);
  if (signed_volume(surface) < 0.0) {
    surface.faces.col(1).swap(surface.faces.col(2));
    warnings.push_back(source + ": the surface's faces pointed inwards; turned them outwards");
  }
  const double metres = metres_per_file_unit > 0.0
                            ? metres_per_file_unit
                            : guess_units_to_metres(surface, source, warnings);
  if (!body.filled.empty()) {
    std::sort(body.filled.begin(), body.filled.end(),
              [](const SurfaceHole& a, const SurfaceHole& b) {
                return a.boundary_length > b.boundary_length;
              });
    std::string list;
    for (std::size_t k = 0; k < body.filled.size() && k < 5; ++k)
      list += (k ? "; " : "") + describe_filled(body.filled[k], metres);
    warnings.push_back(source + ": filled " + std::to_string(body.filled.size()) +
                       " hole(s) of the surface (" + list +
                       (body.filled.size() > 5 ? "; ..." : "") + "; the limit is a boundary of " +
                       length(body.hole_limit, metres) + ")");
  }
  surface.vertices *= metres;
  return surface;
}

double metres_per_unit(const std::string& units, const std::string& source) {
  if (units == "m") return 1.0;
  if (units == "cm") return 0.01;
  if (units == "mm") return 0.001;
  throw InputError(source, "unknown units \"" + units + "\" (expected m, cm or mm)");
}

double guess_units_to_metres(const TriMesh& mesh, const std::string& source,
                             std::vector<std::string>& warnings) {
  if (mesh.num_vertices() == 0) return 1.0;
  const double extent =
      (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).maxCoeff();
  const std::string size = format("%.4g", extent);
  const std::string ask =
      " (state the file's units in the body spec: \"units\": \"m\", \"cm\" or \"mm\")";
  if (!(extent >= 0.05) || extent > 3000.0)
    throw InputError(source, "the body is " + size +
                                 " units across, no human body or body part "
                                 "in metres, centimetres or millimetres" +
                                 ask);
  if (extent <= 3.0) return 1.0;
  if (extent < 50.0) {
    warnings.push_back(source + ": the body is " + size +
                       " units across: read as centimetres "
                       "(" +
                       format("%.3g", extent / 100) + " m)" + ask);
    return 0.01;
  }
  if (extent > 300.0) {
    warnings.push_back(source + ": the body is " + size +
                       " units across: read as millimetres "
                       "(" +
                       format("%.3g", extent / 1000) + " m)" + ask);
    return 0.001;
  }
  throw InputError(source, "the body is " + size + " units across: centimetres (a whole body of " +
                               format("%.3g", extent / 100) +
                               " m) or millimetres (a body part of " +
                               format("%.3g", extent / 1000) + " m)?" + ask);
}

}  // namespace tightfit
