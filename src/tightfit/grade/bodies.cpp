#include "tightfit/grade/bodies.hpp"

#include <cctype>
#include <map>

#include "tightfit/common/error.hpp"
#include "tightfit/common/json_fields.hpp"

namespace tightfit {

bool valid_body_name(const std::string& name) {
  if (name.empty() || name.size() > 64 || name == "." || name == "..") return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      return false;
  return true;
}

std::vector<GradeBody> read_grade_bodies(const std::filesystem::path& file) {
  const std::string source = file.string();
  const nlohmann::json document = read_json_file(source);
  if (!document.is_object()) throw InputError(source, "expected a JSON object {\"bodies\": [...]}");
  JsonFields root(document, source, "");
  root.string("description", std::string());
  const nlohmann::json& list = root.raw("bodies");
  if (!list.is_array() || list.empty())
    root.fail("expected a non-empty array of bodies {\"name\", \"mesh\", \"joints\"}", "bodies");
  root.finish();
  const std::filesystem::path base = file.parent_path();
  auto resolve = [&](JsonFields& f, const std::string& key) {
    const std::string name = f.string(key);
    if (name.empty()) f.fail("must name a file", key);
    const std::filesystem::path p(name);
    return p.is_relative() ? base / p : p;
  };
  std::vector<GradeBody> bodies;
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = "/bodies/" + std::to_string(i);
    if (!list[i].is_object()) throw InputError(source, path + ": expected an object");
    JsonFields f(list[i], source, path);
    GradeBody body;
    body.name = f.string("name");
    if (!valid_body_name(body.name))
      f.fail("\"" + body.name +
                 "\" is not a body name (1 to 64 letters, digits, '_', '-', '.'; "
                 "it names the body's output folder)",
             "name");
    if (const auto it = seen.find(body.name); it != seen.end())
      f.fail("two bodies are named \"" + body.name + "\" (/bodies/" + std::to_string(it->second) +
                 " too): every body needs its own name",
             "name");
    seen.emplace(body.name, i);
    body.mesh = resolve(f, "mesh");
    body.joints = resolve(f, "joints");
    body.rig_mesh = f.has("rig_mesh") ? resolve(f, "rig_mesh") : body.mesh;
    f.string("description", std::string());
    f.finish();
    bodies.push_back(std::move(body));
  }
  return bodies;
}

}  // namespace tightfit
