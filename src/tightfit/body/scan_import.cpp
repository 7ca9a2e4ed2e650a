#include "tightfit/body/scan_import.hpp"

#include <cmath>
#include <cstdio>

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
  for (std::size_t k = 0; k < parts.size(); ++k) {
    if (static_cast<int>(k) == best) continue;
    others += (others.empty() ? "" : "; ") + std::to_string(parts[k].faces.size()) + " faces, " +
              (closed[k] ? "closed" : "open") + ", area " +
              format("%.4g", surface_area(parts[k].mesh));
  }
  warnings.push_back(source + ": the mesh has " + std::to_string(parts.size()) +
                     " separate parts; kept the largest closed one (" +
                     std::to_string(parts[best].faces.size()) + " faces), left out: " + others);
  return std::move(parts[best].mesh);
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
  const std::string ask = " (state the file's units in the body spec: \"units\": \"m\", \"cm\" or \"mm\")";
  if (!(extent >= 0.05) || extent > 3000.0)
    throw InputError(source, "the body is " + size + " units across, no human body or body part "
                             "in metres, centimetres or millimetres" + ask);
  if (extent <= 3.0) return 1.0;
  if (extent < 50.0) {
    warnings.push_back(source + ": the body is " + size + " units across: read as centimetres "
                       "(" + format("%.3g", extent / 100) + " m)" + ask);
    return 0.01;
  }
  if (extent > 300.0) {
    warnings.push_back(source + ": the body is " + size + " units across: read as millimetres "
                       "(" + format("%.3g", extent / 1000) + " m)" + ask);
    return 0.001;
  }
  throw InputError(source, "the body is " + size + " units across: centimetres (a whole body of " +
                               format("%.3g", extent / 100) + " m) or millimetres (a body part of " +
                               format("%.3g", extent / 1000) + " m)?" + ask);
}

}  // namespace tightfit
