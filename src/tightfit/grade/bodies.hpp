#pragma once
/// The bodies file of `tightfit grade` (BODIES.json, schema/bodies.schema.json): the
/// population one design is graded on.
///
///   {"description": "...",                                  // optional
///    "bodies": [{"name": "regular",                         // [A-Za-z0-9_.-], ≤ 64 chars
///                "mesh": "bodies/mh_male_regular.obj",      // the body surface
///                "joints": "rig/mh_male_regular.joints.json",
///                "rig_mesh": "bodies/mh_male_regular.obj"}, // optional (see below)
///               ...]}
///
/// Relative paths resolve against the bodies file's folder. "rig_mesh" is the full body
/// the joints and the skin weights were placed on when "mesh" is a crop of it (the
/// male legs cut from mh_male_regular); it defaults to "mesh".
#include <filesystem>
#include <string>
#include <vector>

namespace tightfit {

/// One body of the population (paths resolved).
struct GradeBody {
  std::string name;
  std::filesystem::path mesh;
  std::filesystem::path joints;
  std::filesystem::path rig_mesh;  ///< = mesh unless the file gives "rig_mesh"
};

/// Whether `name` may name a body (and so its output folder): 1 to 64 characters of
/// letters, digits, '_', '-', '.', not "." or "..".
bool valid_body_name(const std::string& name);

/// Reads and checks the bodies file: structure and types, at least one body, valid and
/// unique names. The files it names are not opened (a missing or bad mesh fails that
/// body only, when it is graded). InputError naming the file and the JSON path.
std::vector<GradeBody> read_grade_bodies(const std::filesystem::path& file);

}  // namespace tightfit
