/// `tightfit body [SPEC] --out DIR [flags]`: builds a simulation body (surface control
/// mesh, tet mesh, pinned core) from a JSON body spec (body/body_spec.hpp) and/or flags,
/// and writes DIR/surface.obj, DIR/volume.vtu and DIR/body.json.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "command_registry.hpp"
#include "tightfit/body/body_spec.hpp"
#include "tightfit/body/body_stats.hpp"
#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/common/finite_output.hpp"
#include "tightfit/common/json_fields.hpp"
#include "tightfit/common/output_directory.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/tet_mesh_io.hpp"

namespace tightfit::app {
namespace {

namespace fs = std::filesystem;

struct BodyOptions {
  std::string spec;
  std::string out;
  bool force = false;
  std::string generator;
  std::string mesh;
  std::string caps;
  std::string units;
  double radius = 0.0;
  double length = 0.0;
  double edge_length = 0.0;
  double soft_tissue = 0.0;
  double max_radius_edge = 0.0;
  double min_dihedral = 0.0;
};

/// The spec: the JSON file if given, with the flags that were passed written over it.
nlohmann::json spec_json(const BodyOptions& o, const CLI::App& cmd) {
  nlohmann::json j = o.spec.empty() ? nlohmann::json::object() : read_json_file(o.spec);
  if (!j.is_object()) throw InputError(o.spec, "/: expected an object");
  auto set = [&](const char* flag, const char* key, const auto& value) {
    if (cmd.count(flag) > 0) j[key] = value;
  };
  set("--generator", "generator", o.generator);
  // A mesh named on the command line is relative to the current folder.
  set("--mesh", "mesh", o.mesh.empty() ? o.mesh : fs::absolute(o.mesh).string());
  set("--caps", "caps", o.caps);
  set("--units", "units", o.units);
  set("--radius", "radius", o.radius);
  set("--length", "length", o.length);
  set("--edge-length", "edge_length", o.edge_length);
  set("--max-radius-edge", "max_radius_edge", o.max_radius_edge);
  set("--min-dihedral", "min_dihedral_deg", o.min_dihedral);
  if (cmd.count("--soft-tissue") > 0) j["core"] = {{"soft_tissue", o.soft_tissue}};
  if (j.empty()) throw InputError("tightfit body", "give a SPEC file or --generator/--mesh flags");
  return j;
}

/// Writes the three outputs through an OutputDirectory (the rule of every command).
void write_outputs(const fs::path& out, bool force, const Body& body,
                   const nlohmann::json& summary) {
  OutputDirectory folder(out, force, "body");
  write_tri_mesh(folder.file("surface.obj"), body.surface);
  write_vtu(folder.file("volume.vtu"), body.volume, body_point_fields(body),
            body_cell_fields(body));
  write_json_atomically(folder.file("body.json"), summary, 2);
  folder.commit();
}

void run(const BodyOptions& o, const CLI::App& cmd) {
  const nlohmann::json j = spec_json(o, cmd);
  const std::string source = o.spec.empty() ? "command line" : o.spec;
  const fs::path base_dir =
      o.spec.empty() ? fs::current_path() : fs::absolute(o.spec).parent_path();
  const BodySpec spec = parse_body_spec(j, "", base_dir, source);
  BuildReport report;
  const Body body = build_body(spec, &report);
  for (const std::string& w : report.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const nlohmann::json summary = body_summary_json(compute_body_stats(body), report);
  const fs::path out(o.out);
  write_outputs(out, o.force, body, summary);
  for (const char* name : {"surface.obj", "volume.vtu", "body.json"})
    std::printf("%s\n", (out / name).string().c_str());
}

const CommandRegistration kBody{
    "body", [](CLI::App& root) {
      auto [cmd, o] = add_command<BodyOptions>(
          root,
          {"body",
           "Build a simulation body (surface, tets, pinned core) from a JSON spec and/or flags;\n"
           "writes OUT/surface.obj, OUT/volume.vtu and OUT/body.json. Units: metres.",
           "Examples:\n  tightfit body --generator cylinder --radius 0.05 --length 0.3 --out "
           "out/cylinder\n  tightfit body --mesh data/bodies/mh_child.obj --units m --edge-length "
           "0.03 --out out/child"},
          [](const BodyOptions& options, const CLI::App& command) { run(options, command); });
      cmd.add_option("spec", o.spec, "JSON body spec (flags below override its keys)");
      add_output_options(cmd, o.out, o.force);
      cmd.add_option("--generator", o.generator, "Built-in body: cylinder or sphere");
      cmd.add_option("--mesh", o.mesh, "Closed surface mesh to import (OBJ, PLY, OFF, STL)");
      cmd.add_option("--units", o.units,
                     "Units of the mesh file: m, cm or mm (default: guessed from the body's size, "
                     "with a warning)");
      cmd.add_option("--caps", o.caps, "Cylinder caps: round or flat");
      cmd.add_option("--radius", o.radius, "Generator radius (m)");
      cmd.add_option("--length", o.length, "Cylinder length without caps (m)");
      cmd.add_option("--edge-length", o.edge_length, "Surface edge length (m)");
      cmd.add_option("--soft-tissue", o.soft_tissue, "Pin vertices deeper than this (m)");
      cmd.add_option("--max-radius-edge", o.max_radius_edge, "TetGen radius-edge bound");
      cmd.add_option("--min-dihedral", o.min_dihedral, "TetGen min dihedral angle (degrees)");
    }};

}  // namespace
}  // namespace tightfit::app
