#include "tightfit/garment/layout.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <numeric>
#include <unordered_map>

#include "tightfit/common/error.hpp"
#include "tightfit/garment/layout_build.hpp"
#include "tightfit/garment/plane_cut.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit {
namespace {

using layout_build::build_layout;
using layout_build::BuildInput;
using layout_build::face_centroid;
using layout_build::format_position;

/// The connected parts of every panel (faces joined across edges to faces of the same
/// panel).
struct PanelParts {
  std::vector<int> part;     ///< per face: its part, −1 for faces in no panel
  std::vector<double> area;  ///< per part (m²)
  std::vector<int> panel;    ///< per part
  std::vector<int> face;     ///< per part: one of its faces
  std::vector<int> largest;  ///< per panel: its largest part (−1: none)
};

PanelParts panel_parts(const TriMesh& m, const SurfaceTopology& topo,
                       const std::vector<int>& face_panel, size_t num_panels) {
  const int nf = m.num_faces();
  PanelParts out;
  out.part.assign(static_cast<size_t>(nf), -1);
  for (int f = 0; f < nf; ++f) {
    if (face_panel[f] < 0 || out.part[f] >= 0) continue;
    const int id = static_cast<int>(out.area.size());
    out.area.push_back(0.0);
    out.panel.push_back(face_panel[f]);
    out.face.push_back(f);
    std::vector<int> stack{f};
    out.part[f] = id;
    while (!stack.empty()) {
      const int g = stack.back();
      stack.pop_back();
      out.area[id] += face_area(m, g);
      for (int i = 0; i < 3; ++i)
        for (int h : topo.edge_all_faces(topo.face_edge(g, i)))
          if (out.part[h] < 0 && face_panel[h] == face_panel[g]) {
            out.part[h] = id;
            stack.push_back(h);
          }
    }
  }
  out.largest.assign(num_panels, -1);
  for (size_t k = 0; k < out.area.size(); ++k) {
    int& best = out.largest[static_cast<size_t>(out.panel[k])];
    if (best < 0 || out.area[k] > out.area[static_cast<size_t>(best)]) best = static_cast<int>(k);
  }
  return out;
}

/// Openings can cut a part of a panel off the rest (the mouth cavity behind a mouth
/// opening, the inside of a nostril): per panel, every connected part but the largest
/// that touches an opening's rim goes with the openings (its faces get panel −1), with
/// a warning naming the opening, the part's area and where it is.
void drop_parts_cut_off_by_openings(const CutMesh& cut, const LayoutSpec& spec,
                                    size_t first_opening, std::vector<int>& face_panel,
                                    std::vector<std::string>& warnings) {
  const TriMesh& m = cut.mesh;
  const SurfaceTopology topo(m.faces, m.num_vertices());
  const int nf = m.num_faces();
  const PanelParts parts = panel_parts(m, topo, face_panel, spec.panels.size());
  const std::vector<int>& part = parts.part;
  const std::vector<double>& part_area = parts.area;
  const std::vector<int>& part_panel = parts.panel;
  const std::vector<int>& part_face = parts.face;
  const std::vector<int>& largest = parts.largest;
  const int np = static_cast<int>(part_area.size());
  std::vector<char> drop(np, 0);
  for (int k = 0; k < np; ++k) {
    if (largest[static_cast<size_t>(part_panel[k])] == k) continue;
    // The openings whose rims this part touches.
    std::vector<char> touches(spec.openings.size(), 0);
    for (int f = 0; f < nf; ++f)
      if (part[f] == k)
        for (int c = 0; c < 3; ++c)
          for (size_t o = 0; o < spec.openings.size(); ++o)
            if (cut.on_plane[first_opening + o][m.faces(f, c)]) touches[o] = 1;
    std::string names;
    for (size_t o = 0; o < spec.openings.size(); ++o)
      if (touches[o])
        names += std::string(names.empty() ? "" : ", ") + "\"" + spec.openings[o].name + "\"";
    if (names.empty()) continue;  // not made by an opening: the topology check names it
    warnings.push_back(
        spec.source + ": opening " + names + " cuts a part of " + std::to_string(part_area[k]) +
        " m² near " + format_position(face_centroid(m, part_face[k])) + " off panel \"" +
        spec.panels[part_panel[k]].name + "\"; it is left out of the garment with the opening");
    drop[k] = 1;
  }
  for (int f = 0; f < nf; ++f)
    if (part[f] >= 0 && drop[part[f]]) face_panel[f] = -1;
}

/// Dividers that graze the body (a plane nearly tangent to a shoulder or a buttock)
/// leave small islands of one panel inside its neighbour. Per panel, every part but the
/// largest whose area is below spec.stray_part_fraction of the panel's area joins the
/// neighbouring panel it shares the longest edge with, with a warning naming it. Larger
/// parts stay: the topology check reports them as a panel that falls apart.
void join_stray_parts(const TriMesh& m, const LayoutSpec& spec, std::vector<int>& face_panel,
                      std::vector<std::string>& warnings) {
  const SurfaceTopology topo(m.faces, m.num_vertices());
  const PanelParts parts = panel_parts(m, topo, face_panel, spec.panels.size());
  std::vector<double> panel_area(spec.panels.size(), 0.0);
  for (size_t k = 0; k < parts.area.size(); ++k)
    panel_area[static_cast<size_t>(parts.panel[k])] += parts.area[k];
  std::vector<int> joins(parts.area.size(), -1);
  for (size_t k = 0; k < parts.area.size(); ++k) {
    const size_t panel = static_cast<size_t>(parts.panel[k]);
    if (parts.largest[panel] == static_cast<int>(k) ||
        parts.area[k] >= spec.stray_part_fraction * panel_area[panel])
      continue;
    std::map<int, double> shared;  // neighbouring panel → length of the shared edges (m)
    for (int f = 0; f < m.num_faces(); ++f) {
      if (parts.part[f] != static_cast<int>(k)) continue;
      for (int i = 0; i < 3; ++i)
        for (int h : topo.edge_all_faces(topo.face_edge(f, i)))
          if (face_panel[h] >= 0 && face_panel[h] != face_panel[f])
            shared[face_panel[h]] +=
                (m.vertices.row(m.faces(f, i)) - m.vertices.row(m.faces(f, (i + 1) % 3))).norm();
    }
    if (shared.empty()) continue;
    joins[k] = std::max_element(shared.begin(), shared.end(), [](const auto& a, const auto& b) {
                 return a.second < b.second;
               })->first;
    warnings.push_back(spec.source + ": panel \"" + spec.panels[panel].name +
                       "\" has a stray part of " + std::to_string(parts.area[k] * 1e4) +
                       " cm² near " + format_position(face_centroid(m, parts.face[k])) +
                       " apart from the rest (a divider grazes the "
                       "body there); it joins panel \"" +
                       spec.panels[static_cast<size_t>(joins[k])].name + "\"");
  }
  for (int f = 0; f < m.num_faces(); ++f)
    if (parts.part[f] >= 0 && joins[static_cast<size_t>(parts.part[f])] >= 0)
      face_panel[f] = joins[static_cast<size_t>(parts.part[f])];
}

/// Welds vertices closer than `tol` (grid hashing); returns the new index per vertex.
std::vector<int> weld_vertices(const Points3& x, double tol, Points3& welded) {
  const int n = static_cast<int>(x.rows());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  const double cell = std::max(tol, 1e-12);
  auto key = [&](const Eigen::Vector3i& c) {
    return (static_cast<long long>(c.x()) * 73856093LL) ^
           (static_cast<long long>(c.y()) * 19349663LL) ^
           (static_cast<long long>(c.z()) * 83492791LL);
  };
  std::unordered_multimap<long long, int> grid;
  for (int i = 0; i < n; ++i) {
    const Vec3 p = x.row(i).transpose();
    const Eigen::Vector3i c = (p / cell).array().floor().cast<int>();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto range = grid.equal_range(key(c + Eigen::Vector3i(dx, dy, dz)));
          for (auto it = range.first; it != range.second; ++it)
            if ((x.row(it->second) - x.row(i)).norm() <= tol) {
              const int a = root(i), b = root(it->second);
              if (a != b) parent[std::max(a, b)] = std::min(a, b);
            }
        }
    grid.emplace(key(c), i);
  }
  std::vector<int> id(n, -1), out(n);
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const int r = root(i);
    if (id[r] < 0) id[r] = m++;
    out[i] = id[r];
  }
  welded.resize(m, 3);
  for (int i = 0; i < n; ++i) welded.row(out[i]) = x.row(root(i));
  return out;
}

/// Panels whose boundaries run side by side without sharing vertices: a gap
/// (InputError naming `mesh_source`).
void check_no_gaps(const BuildInput& in, const LayoutSpec& spec, const std::string& mesh_source) {
  const SurfaceTopology topo(in.surface.faces, in.surface.num_vertices());
  double mean_edge = 0.0;
  for (int e = 0; e < topo.num_edges(); ++e) {
    const auto ev = topo.edge_vertices(e);
    mean_edge += (in.surface.vertices.row(ev[0]) - in.surface.vertices.row(ev[1])).norm();
  }
  mean_edge /= std::max(1, topo.num_edges());
  std::vector<std::pair<int, int>> boundary;  // (vertex, panel)
  for (int e : topo.boundary_edges()) {
    const int f = topo.edge_faces(e)[0];
    for (int v : topo.edge_vertices(e)) boundary.emplace_back(v, in.face_panel[f]);
  }
  const double gap = 0.25 * mean_edge;
  for (size_t i = 0; i < boundary.size(); ++i)
    for (size_t j = i + 1; j < boundary.size(); ++j) {
      if (boundary[i].second == boundary[j].second || boundary[i].first == boundary[j].first)
        continue;
      const double d =
          (in.surface.vertices.row(boundary[i].first) - in.surface.vertices.row(boundary[j].first))
              .norm();
      if (d < gap)
        throw InputError(
            mesh_source,
            "a gap between panels \"" + in.panel_names[boundary[i].second] + "\" and \"" +
                in.panel_names[boundary[j].second] + "\" near " +
                format_position(in.surface.vertices.row(boundary[i].first).transpose()) +
                ": their boundaries are " + std::to_string(d) +
                " m apart but not shared (weld_tolerance " + std::to_string(spec.weld_tolerance) +
                " m)");
    }
}

}  // namespace

Layout layout_from_rules(const TriMesh& body_surface, const LayoutSpec& spec) {
  if (spec.is_mesh_layout())
    throw std::invalid_argument("layout_from_rules: the spec is a mesh layout");
  std::vector<LayoutPlane> planes = spec.region;
  planes.insert(planes.end(), spec.dividers.begin(), spec.dividers.end());
  CutMesh cut = cut_by_planes_and_openings(body_surface, planes, spec.openings);
  const int nr = static_cast<int>(spec.region.size());
  const int nf = cut.mesh.num_faces();
  const size_t first_opening = planes.size();
  std::vector<int> opening_faces(spec.openings.size(), 0);

  BuildInput in;
  in.face_panel.assign(nf, -1);
  bool any_region = false;
  for (int f = 0; f < nf; ++f) {
    bool inside = true;
    for (int k = 0; k < nr; ++k) inside = inside && cut.side[k][f] > 0;
    if (!inside) continue;
    any_region = true;
    bool in_opening = false;
    for (size_t o = 0; o < spec.openings.size(); ++o)
      if (cut.side[first_opening + o][f] < 0) {
        ++opening_faces[o];
        in_opening = true;
      }
    if (in_opening) continue;
    std::vector<int> matches;
    for (size_t p = 0; p < spec.panels.size(); ++p) {
      bool ok = true;
      for (const auto& [d, sign] : spec.panels[p].sides) ok = ok && cut.side[nr + d][f] == sign;
      if (ok) matches.push_back(static_cast<int>(p));
    }
    const Vec3 at = face_centroid(cut.mesh, f);
    if (matches.empty()) {
      std::string sides;
      for (size_t d = 0; d < spec.dividers.size(); ++d)
        sides += std::string(sides.empty() ? "" : ", ") + (cut.side[nr + d][f] > 0 ? "+" : "-") +
                 spec.dividers[d].name;
      throw InputError(spec.source, spec.path + "/panels: a gap: the surface near " +
                                        format_position(at) + " (sides " + sides +
                                        ") is in no panel");
    }
    if (matches.size() > 1)
      throw InputError(spec.source, spec.path + "/panels: an overlap: the surface near " +
                                        format_position(at) + " is in panels \"" +
                                        spec.panels[matches[0]].name + "\" and \"" +
                                        spec.panels[matches[1]].name + "\"");
    in.face_panel[f] = matches[0];
  }
  if (!any_region)
    throw InputError(
        spec.source,
        spec.path +
            "/region: no part of the body surface is on the kept side of every region plane");
  for (size_t o = 0; o < spec.openings.size(); ++o)
    if (opening_faces[o] == 0)
      throw InputError(
          spec.source,
          spec.openings[o].source_path + ": opening \"" + spec.openings[o].name +
              "\" cuts nothing: no part of the garment's surface lies inside its ellipsoid");
  std::vector<std::string> warnings;
  if (!spec.openings.empty())
    drop_parts_cut_off_by_openings(cut, spec, first_opening, in.face_panel, warnings);
  join_stray_parts(cut.mesh, spec, in.face_panel, warnings);
  in.on_opening.assign(static_cast<size_t>(cut.mesh.num_vertices()), 0);
  for (size_t o = 0; o < spec.openings.size(); ++o)
    for (int v = 0; v < cut.mesh.num_vertices(); ++v)
      if (cut.on_plane[first_opening + o][v]) in.on_opening[v] = 1;
  in.surface = std::move(cut.mesh);
  in.body_face = std::move(cut.parent_face);
  for (const auto& rule : spec.panels) {
    in.panel_names.push_back(rule.name);
    in.panel_paths.push_back(rule.source_path);
  }
  in.on_region_plane.assign(cut.on_plane.begin(), cut.on_plane.begin() + nr);
  Layout layout = build_layout(std::move(in), spec);
  layout.warnings = std::move(warnings);
  return layout;
}

Layout layout_from_groups(const TriMesh& mesh, const std::vector<int>& face_group,
                          const std::vector<std::string>& group_names, const LayoutSpec& spec,
                          const std::string& mesh_source) {
  if (face_group.size() != static_cast<size_t>(mesh.num_faces()))
    throw std::invalid_argument("layout_from_groups: one group per face needed");
  BuildInput in;
  const std::vector<int> id =
      weld_vertices(mesh.vertices, spec.weld_tolerance, in.surface.vertices);
  in.surface.faces.resize(mesh.num_faces(), 3);
  std::map<std::array<int, 3>, int> seen;
  int no_panel = 0;
  Vec3 no_panel_at = Vec3::Zero();
  for (int f = 0; f < mesh.num_faces(); ++f) {
    std::array<int, 3> key;
    for (int c = 0; c < 3; ++c) key[c] = in.surface.faces(f, c) = id[mesh.faces(f, c)];
    const Vec3 at = face_centroid(mesh, f);
    if (key[0] == key[1] || key[1] == key[2] || key[0] == key[2])
      throw InputError(mesh_source, "face " + std::to_string(f + 1) + " near " +
                                        format_position(at) +
                                        " is degenerate (two corners coincide)");
    std::sort(key.begin(), key.end());
    const int g = face_group[f];
    if (g < 0) {
      if (no_panel++ == 0) no_panel_at = at;
      continue;
    }
    auto [it, inserted] = seen.emplace(key, g);
    if (!inserted) {
      if (it->second == g)
        throw InputError(mesh_source, "face " + std::to_string(f + 1) + " near " +
                                          format_position(at) + " appears twice in group \"" +
                                          group_names[g] + "\"");
      throw InputError(mesh_source, "an overlap: the face near " + format_position(at) +
                                        " is in panels \"" + group_names[it->second] + "\" and \"" +
                                        group_names[g] + "\"");
    }
  }
  if (no_panel > 0)
    throw InputError(mesh_source, "a gap: " + std::to_string(no_panel) +
                                      " faces belong to no panel (no group), e.g. near " +
                                      format_position(no_panel_at));
  // Map the used groups to panels, in order of first use.
  std::vector<int> panel_of_group(group_names.size(), -1);
  in.face_panel.resize(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    int& p = panel_of_group[face_group[f]];
    if (p < 0) {
      p = static_cast<int>(in.panel_names.size());
      in.panel_names.push_back(group_names[face_group[f]]);
      in.panel_paths.push_back(mesh_source + ": group \"" + group_names[face_group[f]] + "\"");
    }
    in.face_panel[f] = p;
  }
  check_no_gaps(in, spec, mesh_source);
  return build_layout(std::move(in), spec);
}

Layout layout_from_obj(const LayoutSpec& spec) {
  if (!spec.is_mesh_layout()) throw std::invalid_argument("layout_from_obj: not a mesh layout");
  const ObjGroups obj = read_obj_with_groups(spec.mesh_file);
  std::vector<int> groups = obj.face_group;
  // Faces before any g/o line are in the reader's "default" group: no panel.
  for (int& g : groups)
    if (obj.group_names[g] == "default") g = -1;
  return layout_from_groups(obj.mesh, groups, obj.group_names, spec, spec.mesh_file);
}

}  // namespace tightfit
