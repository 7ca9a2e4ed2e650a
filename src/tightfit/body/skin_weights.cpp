#include "tightfit/body/skin_weights.hpp"

#include <cmath>

#include "tightfit/common/error.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/geometry/mesh_io.hpp"

namespace tightfit {

VecX SkinWeights::summed(const std::vector<std::string>& names, const std::string& context) const {
  VecX s = VecX::Zero(vertices.rows());
  for (const std::string& name : names) {
    const auto it = bones.find(name);
    if (it == bones.end())
      throw InputError(source, context + ": the rig has no bone \"" + name + "\"");
    for (const auto& [v, w] : it->second) s[v] += w;
  }
  return s;
}

SkinWeights read_skin_weights(const std::filesystem::path& mesh,
                              const std::filesystem::path& weights) {
  SkinWeights rig;
  TriMesh rig_mesh = read_tri_mesh(mesh);
  rig.vertices = std::move(rig_mesh.vertices);
  rig.faces = std::move(rig_mesh.faces);
  rig.source = weights.string();
  const nlohmann::json root = read_json_file(weights.string());
  if (!root.is_object() || !root.contains("weights") || !root["weights"].is_object())
    throw InputError(rig.source, "/weights: missing (expected an object of bones)");
  const auto n = static_cast<long long>(rig.vertices.rows());
  for (auto it = root["weights"].begin(); it != root["weights"].end(); ++it) {
    const std::string path = "/weights/" + it.key();
    if (!it.value().is_array())
      throw InputError(rig.source, path + ": expected an array of [vertex, weight] pairs");
    std::vector<std::pair<int, double>>& entries = rig.bones[it.key()];
    std::size_t k = 0;
    for (const nlohmann::json& pair : it.value()) {
      const std::string where = path + "/" + std::to_string(k++);
      if (!pair.is_array() || pair.size() != 2 || !pair[0].is_number_integer() ||
          !pair[1].is_number())
        throw InputError(rig.source, where + ": expected [vertex, weight]");
      const long long v = pair[0].get<long long>();
      const double w = pair[1].get<double>();
      if (v < 0) throw InputError(rig.source, where + ": negative vertex index");
      if (!std::isfinite(w) || w < 0.0)
        throw InputError(rig.source, where + ": the weight must be finite and >= 0");
      if (v >= n || w == 0.0) continue;  // helper geometry
      entries.emplace_back(static_cast<int>(v), w);
    }
  }
  // Normalize per vertex: the file's weights are rounded (MakeHuman's sum to 0.95-1.06).
  VecX total = VecX::Zero(rig.vertices.rows());
  for (const auto& [bone, entries] : rig.bones)
    for (const auto& [v, w] : entries) total[v] += w;
  for (auto& [bone, entries] : rig.bones)
    for (auto& [v, w] : entries) w /= total[v];
  return rig;
}

}  // namespace tightfit
