#include "tightfit/report/fit_view.hpp"

#include <set>

#include "tightfit/common/error.hpp"

namespace tightfit {

namespace {

bool valid_field_name(const std::string& name) {
  if (name.empty()) return false;
  for (const char c : name) {
    const bool ok =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) return false;
  }
  return true;
}

void validate_mesh(const TriMesh& mesh, const std::string& what, const std::string& source) {
  if (!mesh.vertices.allFinite())
    throw InputError(source, what + " has non-finite vertex positions");
  if (mesh.faces.size() > 0 &&
      (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= mesh.num_vertices())) {
    throw InputError(
        source, what + " has a face index outside 0.." + std::to_string(mesh.num_vertices() - 1));
  }
}

void validate_fields(const std::vector<FaceField>& fields, int num_faces, const std::string& what,
                     const std::string& source) {
  std::set<std::string> names;
  for (const auto& field : fields) {
    if (!valid_field_name(field.name)) {
      throw InputError(source, what + " field name '" + field.name +
                                   "' must be non-empty letters, digits and '_'");
    }
    if (!names.insert(field.name).second) {
      throw InputError(source, what + " field '" + field.name + "' appears twice");
    }
    if (field.values.rows() != num_faces || field.values.cols() < 1) {
      throw InputError(source, what + " field '" + field.name + "' has " +
                                   std::to_string(field.values.rows()) + "x" +
                                   std::to_string(field.values.cols()) + " values for " +
                                   std::to_string(num_faces) + " faces");
    }
  }
}

void validate_pattern_mapping(const FitView& view, const std::string& source) {
  const auto& pieces = view.pattern.pieces;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const auto& piece = pieces[k];
    const std::string name = "pattern piece " + std::to_string(k) + " ('" + piece.name + "')";
    if (!piece.rest.allFinite()) throw InputError(source, name + " has non-finite rest positions");
    const auto n = static_cast<int>(piece.rest.rows());
    if (piece.triangles.size() > 0 &&
        (piece.triangles.minCoeff() < 0 || piece.triangles.maxCoeff() >= n)) {
      throw InputError(source, name + " has a triangle index outside its vertices");
    }
    for (const int v : piece.boundary_vertices()) {
      if (v < 0 || v >= n)
        throw InputError(source, name + " has a boundary index outside its vertices");
    }
  }
  if (!view.piece_faces.empty() && view.piece_faces.size() != pieces.size()) {
    throw InputError(source, "piece_faces has " + std::to_string(view.piece_faces.size()) +
                                 " entries for " + std::to_string(pieces.size()) + " pieces");
  }
  std::size_t triangles = 0;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const auto count = static_cast<std::size_t>(pieces[k].triangles.rows());
    if (!view.piece_faces.empty() && view.piece_faces[k].size() != count) {
      throw InputError(source, "piece_faces[" + std::to_string(k) + "] has " +
                                   std::to_string(view.piece_faces[k].size()) + " entries for " +
                                   std::to_string(count) + " triangles");
    }
    triangles += count;
  }
  const auto faces = static_cast<std::size_t>(view.garment.num_faces());
  if (triangles != faces) {
    throw InputError(source, "the pattern has " + std::to_string(triangles) +
                                 " triangles but the garment has " + std::to_string(faces) +
                                 " faces");
  }
  std::vector<char> used(faces, 0);
  for (const auto& map : resolved_piece_faces(view)) {
    for (const int f : map) {
      if (f < 0 || static_cast<std::size_t>(f) >= faces) {
        throw InputError(source, "piece_faces names garment face " + std::to_string(f) +
                                     " outside 0.." + std::to_string(faces - 1));
      }
      if (used[static_cast<std::size_t>(f)]++) {
        throw InputError(source, "piece_faces names garment face " + std::to_string(f) + " twice");
      }
    }
  }
}

}  // namespace

void validate_fit_view(const FitView& view, const std::string& source) {
  validate_mesh(view.body, "body", source);
  validate_mesh(view.garment, "garment", source);
  validate_mesh(view.shape_target, "shape target", source);
  validate_mesh(view.initial_garment, "initial garment", source);
  validate_fields(view.body_fields, view.body.num_faces(), "body", source);
  validate_fields(view.garment_fields, view.garment.num_faces(), "garment", source);
  validate_pattern_mapping(view, source);
  if (!view.parameters.is_object()) throw InputError(source, "parameters must be a JSON object");
  if (!view.history.is_array()) throw InputError(source, "history must be a JSON array");
  if (!view.summary.is_object()) throw InputError(source, "summary must be a JSON object");
  if (view.garment_normals.rows() > 0 &&
      (view.garment_normals.rows() != view.garment.vertices.rows() ||
       !view.garment_normals.allFinite()))
    throw InputError(source, "garment normals must be finite, one per garment vertex");
  for (const int v : view.pinned_vertices)
    if (v < 0 || v >= view.garment.vertices.rows())
      throw InputError(source, "pinned vertex " + std::to_string(v) + " is not a garment vertex");
  if (!view.initial_outlines.empty()) {
    if (view.initial_outlines.size() != view.pattern.pieces.size())
      throw InputError(source, std::to_string(view.initial_outlines.size()) +
                                   " initial outlines for " +
                                   std::to_string(view.pattern.pieces.size()) + " pieces");
    for (size_t k = 0; k < view.initial_outlines.size(); ++k) {
      const Points2& o = view.initial_outlines[k];
      if (o.rows() == 1 || o.rows() == 2 || !o.allFinite())
        throw InputError(source, "the initial outline of piece \"" + view.pattern.pieces[k].name +
                                     "\" is not a polygon of finite points");
    }
  }
  for (const FitPose& pose : view.poses)
    if (pose.garment.rows() != view.garment.vertices.rows() ||
        pose.garment_normals.rows() != view.garment.vertices.rows() ||
        pose.body.rows() != view.body.vertices.rows() ||
        pose.sliding_excess.size() != view.garment.num_faces() || !pose.garment.allFinite() ||
        !pose.garment_normals.allFinite() || !pose.body.allFinite() ||
        !pose.sliding_excess.allFinite())
      throw InputError(source, "pose \"" + pose.name +
                                   "\" does not match the garment and body, or is not finite");
  for (const FitRegion& region : view.pressure_regions) {
    if (!(region.min_pa <= region.max_pa))
      throw InputError(source, "pressure region \"" + region.name + "\" has min > max");
    for (const int f : region.faces)
      if (f < 0 || f >= view.garment.num_faces())
        throw InputError(source, "pressure region \"" + region.name + "\" has a face out of range");
  }
}

const FaceField* find_field(const std::vector<FaceField>& fields, std::string_view name) {
  for (const auto& field : fields) {
    if (field.name == name) return &field;
  }
  return nullptr;
}

std::vector<std::vector<int>> resolved_piece_faces(const FitView& view) {
  if (!view.piece_faces.empty()) return view.piece_faces;
  std::vector<std::vector<int>> map;
  int next = 0;
  for (const auto& piece : view.pattern.pieces) {
    std::vector<int> faces(static_cast<std::size_t>(piece.triangles.rows()));
    for (auto& f : faces) f = next++;
    map.push_back(std::move(faces));
  }
  return map;
}

FaceField pressure_mmhg_field(const FaceField& pressure_pa) {
  return FaceField{std::string(fit_fields::kPressureMmHg), "mmHg",
                   pressure_pa.values / kPascalPerMmHg};
}

}  // namespace tightfit
