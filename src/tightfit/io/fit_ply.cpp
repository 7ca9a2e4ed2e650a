#include "tightfit/io/fit_ply.hpp"

#include "tightfit/common/error.hpp"

namespace tightfit {

void write_face_field_ply(const std::filesystem::path& path, const TriMesh& mesh,
                          const std::vector<FaceField>& fields, PlyEncoding encoding) {
  std::vector<MeshField> face_fields;
  for (const auto& field : fields) {
    if (field.values.rows() != mesh.num_faces()) {
      throw InputError(path.string(), "field '" + field.name + "' has " +
                                          std::to_string(field.values.rows()) + " rows for " +
                                          std::to_string(mesh.num_faces()) + " faces");
    }
    face_fields.push_back(MeshField{field.name, field.values});
  }
  try {
    write_ply(path, mesh, face_fields, {}, encoding);
  } catch (const std::invalid_argument& e) {
    throw InputError(path.string(), e.what());
  }
}

void write_fit_ply(const FitView& view, const std::filesystem::path& garment_path,
                   const std::filesystem::path& body_path, PlyEncoding encoding) {
  validate_fit_view(view, garment_path.string());
  write_face_field_ply(garment_path, view.garment, view.garment_fields, encoding);
  write_face_field_ply(body_path, view.body, view.body_fields, encoding);
}

}  // namespace tightfit
