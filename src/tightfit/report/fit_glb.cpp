#include "tightfit/report/fit_glb.hpp"

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

/// Unit area-weighted vertex normals of `vertices` (already in the file's frame);
/// vertices without a usable normal get +y.
Points3 smooth_normals(const Points3& vertices, const Triangles& faces) {
  Points3 sum = Points3::Zero(vertices.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Vec3 a = vertices.row(faces(f, 0));
    const Vec3 b = vertices.row(faces(f, 1));
    const Vec3 c = vertices.row(faces(f, 2));
    const Vec3 n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) sum.row(faces(f, k)) += n.transpose();
  }
  for (Eigen::Index v = 0; v < sum.rows(); ++v) {
    const double length = sum.row(v).norm();
    if (length > 0.0 && std::isfinite(length))
      sum.row(v) /= length;
    else
      sum.row(v) = Vec3::UnitY().transpose();
  }
  return sum;
}

std::vector<float> flat(const Points3& rows) {
  std::vector<float> out;
  out.reserve(static_cast<std::size_t>(3 * rows.rows()));
  for (Eigen::Index v = 0; v < rows.rows(); ++v)
    for (int k = 0; k < 3; ++k) out.push_back(static_cast<float>(rows(v, k)));
  return out;
}

/// `vertices` turned by `r` (rows are points).
Points3 rotated(const Points3& vertices, const Mat3& r) { return vertices * r.transpose(); }

nlohmann::json body_mesh(const TriMesh& body, const Mat3& r, GltfBuffers& buffers) {
  const Points3 vertices = rotated(body.vertices, r);
  std::vector<std::uint32_t> indices;
  for (int f = 0; f < body.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) indices.push_back(static_cast<std::uint32_t>(body.faces(f, k)));
  }
  const int position = buffers.add_vec3(flat(vertices), true);
  const int normal = buffers.add_vec3(flat(smooth_normals(vertices, body.faces)), false);
  const int index = buffers.add_indices(indices);
  return {{"name", "body"},
          {"primitives",
           {{{"attributes", {{"POSITION", position}, {"NORMAL", normal}}},
             {"indices", index},
             {"material", 0},
             {"mode", 4}}}}};
}

nlohmann::json glb_coloring_json(const ResolvedColoring& c) {
  return {{"field", c.coloring.field},
          {"label", c.coloring.label},
          {"unit", c.coloring.unit},
          {"scale", c.coloring.scale},
          {"colormap", colormap_name(c.coloring.colormap)},
          {"lo", c.lo},
          {"hi", c.hi},
          {"rule", "linear(colormap(clamp((value * scale - lo) / (hi - lo), 0, 1)))"}};
}

/// The garment's vertices split per face (3 per triangle, so that each face shows its
/// own colour): positions and smooth normals as accessors shared by every mesh that
/// draws this garment. The normals face away from the body where its outward normals
/// at the garment vertices are known (`outward`, n_g×3, or empty).
struct SplitGarment {
  int position = -1;
  int normal = -1;
  int faces = 0;
};

SplitGarment split_garment(const TriMesh& garment, const Points3& outward, const Mat3& r,
                           GltfBuffers& buffers) {
  const Points3 vertices = rotated(garment.vertices, r);
  Points3 normals = smooth_normals(vertices, garment.faces);
  if (outward.rows() == normals.rows())
    for (Eigen::Index v = 0; v < normals.rows(); ++v)
      if (normals.row(v).dot(outward.row(v) * r.transpose()) < 0.0) normals.row(v) *= -1.0;
  std::vector<float> positions, corner_normals;
  for (int f = 0; f < garment.num_faces(); ++f)
    for (int corner = 0; corner < 3; ++corner)
      for (int k = 0; k < 3; ++k) {
        positions.push_back(static_cast<float>(vertices(garment.faces(f, corner), k)));
        corner_normals.push_back(static_cast<float>(normals(garment.faces(f, corner), k)));
      }
  return {buffers.add_vec3(positions, true), buffers.add_vec3(corner_normals, false),
          garment.num_faces()};
}

/// COLOR_n accessor of one colouring: colormap(t) per face corner in linear light.
int color_accessor(const SplitGarment& g, const ResolvedColoring& coloring, GltfBuffers& buffers) {
  std::vector<float> colors;
  colors.reserve(static_cast<std::size_t>(9 * g.faces));
  for (int f = 0; f < g.faces; ++f) {
    const Rgb rgb = coloring.color(coloring.values[static_cast<std::size_t>(f)]);
    for (int corner = 0; corner < 3; ++corner)
      for (int k = 0; k < 3; ++k)
        colors.push_back(static_cast<float>(srgb_to_linear(rgb[static_cast<std::size_t>(k)])));
  }
  return buffers.add_vec3(colors, false);
}

/// A garment mesh: POSITION, NORMAL and COLOR_0..COLOR_n (one per colouring, in order).
nlohmann::json garment_mesh(const std::string& name, const SplitGarment& g,
                            const std::vector<int>& colors,
                            const std::vector<ResolvedColoring>& colorings) {
  nlohmann::json attributes = {{"POSITION", g.position}, {"NORMAL", g.normal}};
  nlohmann::json sets = nlohmann::json::array();
  for (std::size_t k = 0; k < colors.size(); ++k) {
    attributes["COLOR_" + std::to_string(k)] = colors[k];
    nlohmann::json set = glb_coloring_json(colorings[k]);
    set["attribute"] = "COLOR_" + std::to_string(k);
    sets.push_back(set);
  }
  return {{"name", name},
          {"primitives", {{{"attributes", attributes}, {"material", 1}, {"mode", 4}}}},
          {"extras", {{"coloring", glb_coloring_json(colorings.front())}, {"color_sets", sets}}}};
}

void append_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xFFu));
}

}  // namespace

Mat3 glb_rotation(const Vec3& up) {
  const double length = up.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return Mat3::Identity();
  return Eigen::Quaterniond::FromTwoVectors(up / length, Vec3::UnitY()).toRotationMatrix();
}

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
  // The colour sets: the chosen colouring first (COLOR_0, what every viewer shows), then
  // the other standard maps the view has a scalar field for.
  std::vector<ResolvedColoring> colorings = {resolve_coloring(options.coloring, *field, source)};
  if (options.all_maps)
    for (const FieldColoring& c : standard_colorings()) {
      const FaceField* f = find_field(view.garment_fields, c.field);
      if (c.field == options.coloring.field || f == nullptr || f->components() != 1) continue;
      colorings.push_back(resolve_coloring(c, *f, source));
    }
  const Mat3 r = glb_rotation(view.up);
  const bool with_body = options.include_body && view.body.num_faces() > 0;

  GltfBuffers buffers;
  nlohmann::json meshes = nlohmann::json::array();
  nlohmann::json nodes = nlohmann::json::array();
  nlohmann::json scenes = nlohmann::json::array();
  auto add_node = [&](const std::string& name, std::size_t mesh) {
    nodes.push_back({{"name", name}, {"mesh", mesh}});
    return nodes.size() - 1;
  };
  std::size_t body = 0;
  if (with_body) {
    meshes.push_back(body_mesh(view.body, r, buffers));
    body = meshes.size() - 1;
  }
  const SplitGarment garment = split_garment(view.garment, view.garment_normals, r, buffers);
  std::vector<int> colors;
  for (const ResolvedColoring& c : colorings) colors.push_back(color_accessor(garment, c, buffers));
  meshes.push_back(garment_mesh("garment", garment, colors, colorings));
  nlohmann::json fit_nodes = nlohmann::json::array();
  if (with_body) fit_nodes.push_back(add_node("body", body));
  fit_nodes.push_back(add_node("garment", meshes.size() - 1));
  scenes.push_back({{"name", "fit"}, {"nodes", fit_nodes}});
  // One scene per further map: the same body and garment geometry (shared accessors),
  // the garment's COLOR_0 that map, so that a viewer's scene list switches maps.
  for (std::size_t k = 1; k < colorings.size(); ++k) {
    const std::string label = colorings[k].coloring.label;
    meshes.push_back(garment_mesh("garment (" + label + ")", garment, {colors[k]}, {colorings[k]}));
    nlohmann::json map_nodes = nlohmann::json::array();
    if (with_body) map_nodes.push_back(add_node("body (" + label + ")", body));
    map_nodes.push_back(add_node("garment (" + label + ")", meshes.size() - 1));
    scenes.push_back({{"name", "map: " + label}, {"nodes", map_nodes}});
  }
  // One node per pose (its posed body and garment as children, the garment coloured by
  // the tangential force above the friction limit on one range for every pose), each in
  // a scene of its own so that viewers show one pose at a time.
  if (!view.poses.empty()) {
    VecX worst = VecX::Zero(view.garment.num_faces());
    for (const FitPose& pose : view.poses) worst = worst.cwiseMax(pose.sliding_excess);
    const FieldColoring sliding{std::string(fit_fields::kSlidingExcess),
                                "Sliding",
                                "N",
                                1.0,
                                ColorMap::kViridis,
                                0.0,
                                std::nullopt,
                                true,
                                std::nullopt};
    const ResolvedColoring range =
        resolve_coloring(sliding, FaceField{sliding.field, "N", worst}, source);
    for (const FitPose& pose : view.poses) {
      nlohmann::json children = nlohmann::json::array();
      if (with_body) {
        meshes.push_back(body_mesh(TriMesh{pose.body, view.body.faces}, r, buffers));
        meshes.back()["name"] = "body (" + pose.name + ")";
        children.push_back(add_node("body (" + pose.name + ")", meshes.size() - 1));
      }
      ResolvedColoring posed = range;
      posed.values.assign(pose.sliding_excess.begin(), pose.sliding_excess.end());
      const SplitGarment g = split_garment(TriMesh{pose.garment, view.garment.faces},
                                           pose.garment_normals, r, buffers);
      meshes.push_back(garment_mesh("garment (" + pose.name + ")", g,
                                    {color_accessor(g, posed, buffers)}, {posed}));
      children.push_back(add_node("garment (" + pose.name + ")", meshes.size() - 1));
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
  nlohmann::json sets = nlohmann::json::array();
  for (std::size_t k = 0; k < colorings.size(); ++k) {
    nlohmann::json set = glb_coloring_json(colorings[k]);
    set["attribute"] = "COLOR_" + std::to_string(k);
    set["scene"] = static_cast<int>(k);  // scene 0 is the fit, scene k map k
    sets.push_back(set);
  }
  const double up_length = view.up.norm();
  const Vec3 up =
      up_length > 0.0 && std::isfinite(up_length) ? Vec3(view.up / up_length) : Vec3::UnitY();
  const auto& bin = buffers.bytes();
  nlohmann::json gltf = {
      {"asset",
       {{"version", "2.0"},
        {"generator", "tightfit"},
        {"extras",
         {{"units", "metres, y up"},
          {"scene_up", {up.x(), up.y(), up.z()}},
          {"rotation",
           "every position and normal is the scene's turned by the rotation that "
           "takes scene_up (the body's up direction) onto +y"},
          {"coloring", glb_coloring_json(colorings.front())},
          {"color_sets", sets}}}}},
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
  return colorings.front();
}

}  // namespace tightfit
