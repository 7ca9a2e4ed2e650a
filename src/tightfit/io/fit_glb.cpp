#include "tightfit/io/fit_glb.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"

namespace tightfit {

namespace {

constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

/// Collects the binary buffer, buffer views and accessors of the glTF file.
class GltfBuffers {
 public:
  /// Adds tightly packed VEC3 float rows; `with_bounds` stores min/max (POSITION).
  int add_vec3(const std::vector<float>& data, bool with_bounds) {
    const auto count = data.size() / 3;
    const int view = add_view(data.data(), data.size() * sizeof(float), kArrayBuffer);
    float_views_.push_back(view);
    nlohmann::json accessor = {
        {"bufferView", view}, {"componentType", kFloat}, {"count", count}, {"type", "VEC3"}};
    if (with_bounds) {
      std::vector<float> lo(3, std::numeric_limits<float>::max());
      std::vector<float> hi(3, std::numeric_limits<float>::lowest());
      for (std::size_t i = 0; i < data.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], data[i]);
        hi[i % 3] = std::max(hi[i % 3], data[i]);
      }
      accessor["min"] = lo;
      accessor["max"] = hi;
    }
    accessors_.push_back(accessor);
    return static_cast<int>(accessors_.size()) - 1;
  }

  int add_indices(const std::vector<std::uint32_t>& data) {
    const int view =
        add_view(data.data(), data.size() * sizeof(std::uint32_t), kElementArrayBuffer);
    accessors_.push_back({{"bufferView", view},
                          {"componentType", kUnsignedInt},
                          {"count", data.size()},
                          {"type", "SCALAR"}});
    return static_cast<int>(accessors_.size()) - 1;
  }

  /// Throws NonFiniteOutput naming the accessor of the first NaN or infinity in a
  /// float view (positions, normals, colours).
  void require_finite() const {
    for (const int view : float_views_) {
      const nlohmann::json& v = views_[static_cast<std::size_t>(view)];
      const std::size_t count = v["byteLength"].get<std::size_t>() / sizeof(float);
      std::vector<float> values(count);
      std::memcpy(values.data(), bytes_.data() + v["byteOffset"].get<std::size_t>(),
                  count * sizeof(float));
      require_finite_values(values.data(), count, "buffer view " + std::to_string(view));
    }
  }

  const std::vector<char>& bytes() const { return bytes_; }
  const nlohmann::json& views() const { return views_; }
  const nlohmann::json& accessors() const { return accessors_; }

 private:
  int add_view(const void* data, std::size_t size, int target) {
    while (bytes_.size() % 4 != 0) bytes_.push_back(0);
    const std::size_t offset = bytes_.size();
    bytes_.resize(offset + size);
    std::memcpy(bytes_.data() + offset, data, size);
    views_.push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}, {"target", target}});
    return static_cast<int>(views_.size()) - 1;
  }

  std::vector<char> bytes_;
  std::vector<int> float_views_;
  nlohmann::json views_ = nlohmann::json::array();
  nlohmann::json accessors_ = nlohmann::json::array();
};

/// Unit area-weighted vertex normals; vertices without a usable normal get +y.
std::vector<float> smooth_normals(const TriMesh& mesh) {
  Points3 sum = Points3::Zero(mesh.num_vertices(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 a = mesh.vertices.row(mesh.faces(f, 0));
    const Vec3 b = mesh.vertices.row(mesh.faces(f, 1));
    const Vec3 c = mesh.vertices.row(mesh.faces(f, 2));
    const Vec3 n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) sum.row(mesh.faces(f, k)) += n.transpose();
  }
  std::vector<float> out;
  out.reserve(static_cast<std::size_t>(3 * mesh.num_vertices()));
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    Vec3 n = sum.row(v).transpose();
    const double length = n.norm();
    n = (length > 0.0 && std::isfinite(length)) ? Vec3(n / length) : Vec3::UnitY();
    for (int k = 0; k < 3; ++k) out.push_back(static_cast<float>(n[k]));
  }
  return out;
}

nlohmann::json body_mesh(const TriMesh& body, GltfBuffers& buffers) {
  std::vector<float> positions;
  for (int v = 0; v < body.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(body.vertices(v, k)));
  }
  std::vector<std::uint32_t> indices;
  for (int f = 0; f < body.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) indices.push_back(static_cast<std::uint32_t>(body.faces(f, k)));
  }
  const int position = buffers.add_vec3(positions, true);
  const int normal = buffers.add_vec3(smooth_normals(body), false);
  const int index = buffers.add_indices(indices);
  return {{"name", "body"},
          {"primitives",
           {{{"attributes", {{"POSITION", position}, {"NORMAL", normal}}},
             {"indices", index},
             {"material", 0},
             {"mode", 4}}}}};
}

nlohmann::json coloring_json(const ResolvedColoring& c) {
  return {{"field", c.coloring.field},
          {"label", c.coloring.label},
          {"unit", c.coloring.unit},
          {"scale", c.coloring.scale},
          {"colormap", colormap_name(c.coloring.colormap)},
          {"lo", c.lo},
          {"hi", c.hi},
          {"rule", "COLOR_0 = linear(colormap(clamp((value * scale - lo) / (hi - lo), 0, 1)))"}};
}

nlohmann::json garment_mesh(const TriMesh& garment, const ResolvedColoring& coloring,
                            GltfBuffers& buffers) {
  std::vector<float> positions;
  std::vector<float> colors;
  for (int f = 0; f < garment.num_faces(); ++f) {
    const Rgb rgb = coloring.color(coloring.values[static_cast<std::size_t>(f)]);
    for (int corner = 0; corner < 3; ++corner) {
      for (int k = 0; k < 3; ++k) {
        positions.push_back(static_cast<float>(garment.vertices(garment.faces(f, corner), k)));
        colors.push_back(static_cast<float>(srgb_to_linear(rgb[static_cast<std::size_t>(k)])));
      }
    }
  }
  const int position = buffers.add_vec3(positions, true);
  const int color = buffers.add_vec3(colors, false);
  return {{"name", "garment"},
          {"primitives",
           {{{"attributes", {{"POSITION", position}, {"COLOR_0", color}}},
             {"material", 1},
             {"mode", 4}}}},
          {"extras", {{"coloring", coloring_json(coloring)}}}};
}

void append_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xFFu));
}

}  // namespace

ResolvedColoring write_fit_glb(const std::filesystem::path& path, const FitView& view,
                               const GlbOptions& options) {
  const std::string source = path.string();
  validate_fit_view(view, source);
  if (view.garment.num_faces() == 0) throw InputError(source, "the garment has no faces");
  const FaceField* field = find_field(view.garment_fields, options.coloring.field);
  if (field == nullptr) {
    throw InputError(source,
                     "the garment has no field '" + options.coloring.field + "' to colour by");
  }
  const ResolvedColoring coloring = resolve_coloring(options.coloring, *field, source);

  GltfBuffers buffers;
  nlohmann::json meshes = nlohmann::json::array();
  nlohmann::json nodes = nlohmann::json::array();
  if (options.include_body && view.body.num_faces() > 0) {
    meshes.push_back(body_mesh(view.body, buffers));
    nodes.push_back({{"name", "body"}, {"mesh", meshes.size() - 1}});
  }
  meshes.push_back(garment_mesh(view.garment, coloring, buffers));
  nodes.push_back({{"name", "garment"}, {"mesh", meshes.size() - 1}});
  nlohmann::json scene_nodes = nlohmann::json::array();
  for (std::size_t i = 0; i < nodes.size(); ++i) scene_nodes.push_back(i);
  nlohmann::json scenes = nlohmann::json::array({{{"name", "fit"}, {"nodes", scene_nodes}}});
  // One node per pose (its posed body and garment as children, the garment coloured by
  // the tangential force above the friction limit on one range for every pose), each in
  // a scene of its own so that viewers show one pose at a time.
  if (!view.poses.empty()) {
    VecX worst = VecX::Zero(view.garment.num_faces());
    for (const FitPose& pose : view.poses) worst = worst.cwiseMax(pose.sliding_excess);
    const FieldColoring sliding{std::string(fit_fields::kSlidingExcess), "Sliding", "N", 1.0,
                                ColorMap::kViridis, 0.0, std::nullopt, true, std::nullopt};
    const ResolvedColoring range = resolve_coloring(sliding, FaceField{sliding.field, "N", worst}, source);
    for (const FitPose& pose : view.poses) {
      nlohmann::json children = nlohmann::json::array();
      if (options.include_body && view.body.num_faces() > 0) {
        meshes.push_back(body_mesh(TriMesh{pose.body, view.body.faces}, buffers));
        meshes.back()["name"] = "body (" + pose.name + ")";
        nodes.push_back({{"name", "body (" + pose.name + ")"}, {"mesh", meshes.size() - 1}});
        children.push_back(nodes.size() - 1);
      }
      ResolvedColoring posed = range;
      posed.values.assign(pose.sliding_excess.begin(), pose.sliding_excess.end());
      meshes.push_back(garment_mesh(TriMesh{pose.garment, view.garment.faces}, posed, buffers));
      meshes.back()["name"] = "garment (" + pose.name + ")";
      nodes.push_back({{"name", "garment (" + pose.name + ")"}, {"mesh", meshes.size() - 1}});
      children.push_back(nodes.size() - 1);
      nodes.push_back({{"name", "pose " + pose.name}, {"children", children}});
      scenes.push_back({{"name", "pose " + pose.name}, {"nodes", {nodes.size() - 1}}});
    }
  }

  const nlohmann::json materials =
      nlohmann::json::array({{{"name", "body"},
                              {"pbrMetallicRoughness",
                               {{"baseColorFactor", {0.55, 0.55, 0.55, 1.0}},
                                {"metallicFactor", 0.0},
                                {"roughnessFactor", 0.8}}}},
                             {{"name", "garment"},
                              {"doubleSided", true},
                              {"pbrMetallicRoughness",
                               {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}},
                                {"metallicFactor", 0.0},
                                {"roughnessFactor", 0.9}}}}});
  const auto& bin = buffers.bytes();
  nlohmann::json gltf = {
      {"asset",
       {{"version", "2.0"},
        {"generator", "tightfit"},
        {"extras", {{"units", "metres, y up"}, {"coloring", coloring_json(coloring)}}}}},
      {"scene", 0},
      {"scenes", scenes},
      {"nodes", nodes},
      {"meshes", meshes},
      {"materials", materials},
      {"buffers", {{{"byteLength", bin.size()}}}},
      {"bufferViews", buffers.views()},
      {"accessors", buffers.accessors()},
  };
  std::string json = gltf.dump();
  while (json.size() % 4 != 0) json.push_back(' ');
  std::string binary(bin.begin(), bin.end());
  while (binary.size() % 4 != 0) binary.push_back('\0');

  std::string file;
  file.reserve(28 + json.size() + binary.size());
  file += "glTF";
  append_u32(file, 2);
  append_u32(file, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + binary.size()));
  append_u32(file, static_cast<std::uint32_t>(json.size()));
  file += "JSON";
  file += json;
  append_u32(file, static_cast<std::uint32_t>(binary.size()));
  file.append("BIN\0", 4);
  file += binary;
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        require_finite_json(gltf);
        buffers.require_finite();
        out.write(file.data(), static_cast<std::streamsize>(file.size()));
      },
      true);
  return coloring;
}

}  // namespace tightfit
