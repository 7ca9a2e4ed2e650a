#include "tightfit/garment/layout.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <sstream>
#include <unordered_map>

#include "tightfit/common/error.hpp"
#include "tightfit/garment/plane_cut.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit {
namespace {

std::string format_position(const Vec3& p) {
  std::ostringstream s;
  s.precision(4);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ") m";
  return s.str();
}

Vec3 face_centroid(const TriMesh& m, int f) {
  return (m.vertices.row(m.faces(f, 0)) + m.vertices.row(m.faces(f, 1)) +
          m.vertices.row(m.faces(f, 2)))
             .transpose() /
         3.0;
}

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

/// Everything the shared builder needs besides the surface.
struct BuildInput {
  TriMesh surface;  // may contain faces outside the garment (panel −1)
  std::vector<int> face_panel;
  std::vector<int> body_face;  // or empty
  std::vector<std::string> panel_names;
  std::vector<std::string> panel_paths;  // JSON path per panel (or the mesh source)
  /// Region-plane flags per vertex (rules layouts); empty for mesh layouts.
  std::vector<std::vector<char>> on_region_plane;
  /// Per vertex: on the rim of one of the spec's openings (rules layouts, all 0 without
  /// openings); empty for mesh layouts, whose inner boundary loops are all openings.
  std::vector<char> on_opening;
};

/// Compacts the surface to the faces with a panel.
void compact(BuildInput& in, Layout& out) {
  const int nf = in.surface.num_faces();
  std::vector<int> keep;
  for (int f = 0; f < nf; ++f)
    if (in.face_panel[f] >= 0) keep.push_back(f);
  std::vector<int> new_id(in.surface.num_vertices(), -1);
  int nv = 0;
  for (int f : keep)
    for (int c = 0; c < 3; ++c)
      if (new_id[in.surface.faces(f, c)] < 0) new_id[in.surface.faces(f, c)] = nv++;
  out.surface.vertices.resize(nv, 3);
  for (int v = 0; v < in.surface.num_vertices(); ++v)
    if (new_id[v] >= 0) out.surface.vertices.row(new_id[v]) = in.surface.vertices.row(v);
  out.surface.faces.resize(static_cast<Eigen::Index>(keep.size()), 3);
  out.face_panel.clear();
  out.body_face.clear();
  for (size_t i = 0; i < keep.size(); ++i) {
    for (int c = 0; c < 3; ++c)
      out.surface.faces(static_cast<Eigen::Index>(i), c) = new_id[in.surface.faces(keep[i], c)];
    out.face_panel.push_back(in.face_panel[keep[i]]);
    out.body_face.push_back(in.body_face.empty() ? -1 : in.body_face[keep[i]]);
  }
  auto compact_flags = [&](std::vector<char>& flags) {
    std::vector<char> compacted(nv, 0);
    for (int v = 0; v < in.surface.num_vertices(); ++v)
      if (new_id[v] >= 0) compacted[new_id[v]] = flags[v];
    flags = std::move(compacted);
  };
  for (auto& flags : in.on_region_plane) compact_flags(flags);
  if (!in.on_opening.empty()) compact_flags(in.on_opening);
}

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

/// Directed open boundary edges of the garment (following face orientation) and the
/// pin claiming each (−1: none).
struct OpenEdges {
  std::map<std::pair<int, int>, int> pin;  // (from, to) → pin index or −1
};

OpenEdges assign_pins(const Layout& layout, const SurfaceTopology& topo, const BuildInput& in,
                      const LayoutSpec& spec) {
  OpenEdges open;
  const TriMesh& m = layout.surface;
  for (int f = 0; f < m.num_faces(); ++f)
    for (int i = 0; i < 3; ++i)
      if (topo.is_boundary_edge(topo.face_edge(f, i)))
        open.pin[{m.faces(f, i), m.faces(f, (i + 1) % 3)}] = -1;
  // Chain the open edges into loops (for "nearest").
  std::multimap<int, int> next;
  for (const auto& [e, p] : open.pin) next.emplace(e.first, e.second);
  std::vector<std::vector<std::pair<int, int>>> loops;
  std::map<std::pair<int, int>, bool> used;
  for (const auto& [e, p] : open.pin) {
    if (used[e]) continue;
    std::vector<std::pair<int, int>> loop;
    std::pair<int, int> cur = e;
    while (!used[cur]) {
      used[cur] = true;
      loop.push_back(cur);
      auto range = next.equal_range(cur.second);
      for (auto it = range.first; it != range.second; ++it)
        if (!used[{it->first, it->second}]) {
          cur = {it->first, it->second};
          break;
        }
    }
    loops.push_back(std::move(loop));
  }
  const std::string where = spec.path + "/pinned";
  for (size_t k = 0; k < spec.pins.size(); ++k) {
    const PinRule& pin = spec.pins[k];
    int claimed = 0;
    auto claim = [&](const std::pair<int, int>& e) {
      ++claimed;
      int& slot = open.pin[e];
      if (slot < 0) slot = static_cast<int>(k);
    };
    if (pin.kind == PinRule::Kind::kNearest) {
      if (loops.empty())
        throw InputError(spec.source, pin.source_path + ": pinned boundary \"" + pin.name +
                                          "\" does not exist: the garment has no open boundary");
      double best = std::numeric_limits<double>::infinity();
      size_t best_loop = 0;
      for (size_t l = 0; l < loops.size(); ++l)
        for (const auto& e : loops[l]) {
          const double d = point_segment_distance(pin.point, m.vertices.row(e.first).transpose(),
                                                  m.vertices.row(e.second).transpose());
          if (d < best) {
            best = d;
            best_loop = l;
          }
        }
      if (best > pin.max_distance)
        throw InputError(spec.source, pin.source_path + ": pinned boundary \"" + pin.name +
                                          "\" does not exist: the nearest open boundary is " +
                                          std::to_string(best) + " m from " +
                                          format_position(pin.point) + " (max_distance " +
                                          std::to_string(pin.max_distance) + " m)");
      for (const auto& e : loops[best_loop]) claim(e);
    } else {
      for (const auto& [e, p] : open.pin) {
        bool on = false;
        if (pin.kind == PinRule::Kind::kOnRegionPlane) {
          const auto& flags = in.on_region_plane[pin.region_plane];
          on = flags[e.first] && flags[e.second];
        } else {
          on = std::abs(pin.plane.distance(m.vertices.row(e.first).transpose())) <=
                   spec.plane_tolerance &&
               std::abs(pin.plane.distance(m.vertices.row(e.second).transpose())) <=
                   spec.plane_tolerance;
        }
        if (on) claim(e);
      }
      if (claimed == 0) {
        const std::string plane_name =
            pin.kind == PinRule::Kind::kOnRegionPlane
                ? "region plane \"" + spec.region[pin.region_plane].name + "\""
                : "the given plane";
        throw InputError(spec.source, pin.source_path + ": pinned boundary \"" + pin.name +
                                          "\" does not exist: no open garment boundary lies on " +
                                          plane_name);
      }
    }
  }
  return open;
}

/// Two panels may meet along several seams (the shoulder and the side seam of a front
/// and a back): "A/B", "A/B#2", … numbered from the highest (mean height y of the seam's
/// vertices) down, so that the same seam has the same name on every body a layout is
/// laid out on (grading compares seams by name).
void name_seams_top_down(Layout& layout) {
  std::map<std::pair<int, int>, std::vector<int>> by_pair;
  for (size_t k = 0; k < layout.seams.size(); ++k)
    by_pair[{layout.seams[k].panel_a, layout.seams[k].panel_b}].push_back(static_cast<int>(k));
  auto mean_height = [&](int k) {
    double sum = 0.0;
    for (int v : layout.seams[static_cast<size_t>(k)].vertices)
      sum += layout.surface.vertices(v, 1);
    return sum / static_cast<double>(layout.seams[static_cast<size_t>(k)].vertices.size());
  };
  for (auto& [pair, seams] : by_pair) {
    std::stable_sort(seams.begin(), seams.end(),
                     [&](int a, int b) { return mean_height(a) > mean_height(b); });
    for (size_t i = 0; i < seams.size(); ++i) {
      std::string name = layout.panels[static_cast<size_t>(pair.first)].name;
      name += '/';
      name += layout.panels[static_cast<size_t>(pair.second)].name;
      if (i > 0) {
        name += '#';
        name += std::to_string(i + 1);
      }
      layout.seams[static_cast<size_t>(seams[i])].name = std::move(name);
    }
  }
}

/// Checks that a panel is a disc, possibly with holes: connected, manifold, one or more
/// boundary loops, no handles.
void check_panel_topology(const LayoutPanel& panel, const std::string& source,
                          const std::string& path) {
  const std::string what = "panel \"" + panel.name + "\" is not a disc: ";
  const int nf = panel.mesh.num_faces();
  const SurfaceTopology topo(panel.mesh.faces, panel.mesh.num_vertices());
  const Vec3 at = face_centroid(panel.mesh, 0);
  if (!topo.non_manifold_edges().empty())
    throw InputError(source,
                     path + ": " + what + "it has non-manifold edges near " + format_position(at));
  // Connected?
  std::vector<char> seen(nf, 0);
  std::queue<int> queue;
  queue.push(0);
  seen[0] = 1;
  int reached = 1;
  while (!queue.empty()) {
    const int f = queue.front();
    queue.pop();
    for (int i = 0; i < 3; ++i) {
      const auto a = topo.across(f, i);
      if (a.face >= 0 && !seen[a.face]) {
        seen[a.face] = 1;
        ++reached;
        queue.push(a.face);
      }
    }
  }
  if (reached != nf) {
    int other = 0;
    while (seen[other]) ++other;
    throw InputError(source, path + ": " + what + "it falls apart into separate parts (near " +
                                 format_position(at) + " and " +
                                 format_position(face_centroid(panel.mesh, other)) + ")");
  }
  const auto nm = topo.non_manifold_vertices();
  if (!nm.empty())
    throw InputError(source, path + ": " + what + "it touches itself at " +
                                 format_position(panel.mesh.vertices.row(nm[0]).transpose()));
  const auto loops = topo.boundary_loops();
  if (loops.empty())
    throw InputError(source, path + ": " + what + "it is closed (it has no boundary)");
  const int euler = topo.num_vertices() - topo.num_edges() + nf;
  if (euler != 2 - static_cast<int>(loops.size()))
    throw InputError(source, path + ": " + what + "it has handles (Euler characteristic " +
                                 std::to_string(euler) + ")");
}

/// The panel's outer boundary loop: the longest (3D) loop not entirely on openings'
/// rims (`on_opening` per layout vertex; empty: any loop), else the longest loop.
int outer_loop(const LayoutPanel& panel, const std::vector<std::vector<int>>& loops,
               const std::vector<char>& on_opening) {
  int best = -1, best_any = 0;
  double best_length = -1.0, best_any_length = -1.0;
  for (size_t l = 0; l < loops.size(); ++l) {
    double length = 0.0;
    bool all_on_opening = !on_opening.empty();
    const size_t n = loops[l].size();
    for (size_t i = 0; i < n; ++i) {
      length +=
          (panel.mesh.vertices.row(loops[l][i]) - panel.mesh.vertices.row(loops[l][(i + 1) % n]))
              .norm();
      if (!on_opening.empty() && !on_opening[panel.surface_vertex[loops[l][i]]])
        all_on_opening = false;
    }
    if (length > best_any_length) {
      best_any_length = length;
      best_any = static_cast<int>(l);
    }
    if (!all_on_opening && length > best_length) {
      best_length = length;
      best = static_cast<int>(l);
    }
  }
  return best >= 0 ? best : best_any;
}

Layout build_layout(BuildInput in, const LayoutSpec& spec) {
  Layout layout;
  layout.source = spec.source;
  layout.seam_tolerance = spec.seam_tolerance;
  layout.area_tolerance = spec.area_tolerance;
  layout.pin_names.clear();
  for (const auto& p : spec.pins) layout.pin_names.push_back(p.name);
  compact(in, layout);
  const int np = static_cast<int>(in.panel_names.size());
  const TriMesh& surf = layout.surface;
  const SurfaceTopology topo(surf.faces, surf.num_vertices());
  const auto nm = topo.non_manifold_edges();
  if (!nm.empty()) {
    const auto ev = topo.edge_vertices(nm[0]);
    throw InputError(spec.source,
                     "the layout surface has an edge shared by more than two faces at " +
                         format_position(surf.vertices.row(ev[0]).transpose()));
  }
  const OpenEdges open = assign_pins(layout, topo, in, spec);

  // Panels.
  layout.panels.resize(np);
  for (int p = 0; p < np; ++p) {
    LayoutPanel& panel = layout.panels[p];
    panel.name = in.panel_names[p];
    std::vector<int> local(surf.num_vertices(), -1);
    for (int f = 0; f < surf.num_faces(); ++f) {
      if (layout.face_panel[f] != p) continue;
      panel.surface_face.push_back(f);
      for (int c = 0; c < 3; ++c) {
        const int v = surf.faces(f, c);
        if (local[v] < 0) {
          local[v] = static_cast<int>(panel.surface_vertex.size());
          panel.surface_vertex.push_back(v);
        }
      }
    }
    if (panel.surface_face.empty())
      throw InputError(spec.source, in.panel_paths[p] + ": panel \"" + panel.name +
                                        "\" is empty: no part of the surface lies on its sides");
    panel.mesh.vertices.resize(static_cast<Eigen::Index>(panel.surface_vertex.size()), 3);
    for (size_t i = 0; i < panel.surface_vertex.size(); ++i)
      panel.mesh.vertices.row(static_cast<Eigen::Index>(i)) =
          surf.vertices.row(panel.surface_vertex[i]);
    panel.mesh.faces.resize(static_cast<Eigen::Index>(panel.surface_face.size()), 3);
    for (size_t i = 0; i < panel.surface_face.size(); ++i)
      for (int c = 0; c < 3; ++c)
        panel.mesh.faces(static_cast<Eigen::Index>(i), c) =
            local[surf.faces(panel.surface_face[i], c)];
    check_panel_topology(panel, spec.source, in.panel_paths[p]);

    // Label the boundary edges: (neighbour panel or −1, pin or −1).
    const SurfaceTopology ptopo(panel.mesh.faces, panel.mesh.num_vertices());
    const std::vector<std::vector<int>> loops = ptopo.boundary_loops();
    auto label_loop = [&](const std::vector<int>& loop) {
      const int n = static_cast<int>(loop.size());
      std::vector<std::pair<int, int>> label(n);
      for (int i = 0; i < n; ++i) {
        const int a = panel.surface_vertex[loop[i]], b = panel.surface_vertex[loop[(i + 1) % n]];
        const int e = topo.find_edge(a, b);
        int other = -1;
        for (int g : topo.edge_all_faces(e))
          if (layout.face_panel[g] != p) other = layout.face_panel[g];
        if (other >= 0) {
          label[i] = {other, -1};
        } else {
          auto it = open.pin.find({a, b});
          label[i] = {-1, it == open.pin.end() ? -1 : it->second};
        }
      }
      return label;
    };
    const int outer = outer_loop(panel, loops, in.on_opening);
    for (size_t l = 0; l < loops.size(); ++l) {
      if (static_cast<int>(l) == outer) continue;
      const Vec3 at = panel.mesh.vertices.row(loops[l][0]).transpose();
      if (!in.on_opening.empty())
        for (int v : loops[l])
          if (!in.on_opening[panel.surface_vertex[v]])
            throw InputError(spec.source,
                             in.panel_paths[p] + ": panel \"" + panel.name +
                                 "\" is not a disc: it has " + std::to_string(loops.size()) +
                                 " boundary loops, one of them near " + format_position(at) +
                                 " not made by an opening (a band around the body? add a divider)");
      const auto label = label_loop(loops[l]);
      for (const auto& [other, pin] : label)
        if (other >= 0)
          throw InputError(spec.source,
                           in.panel_paths[p] + ": panel \"" + panel.name + "\" surrounds panel \"" +
                               in.panel_names[other] + "\" (near " + format_position(at) +
                               "); a seam along a piece's inner boundary is not supported: "
                               "cut the surrounding panel with a divider through the inner one");
      for (const auto& entry : label)
        if (entry.second != label[0].second)
          throw InputError(spec.source,
                           in.panel_paths[p] + ": the opening of panel \"" + panel.name +
                               "\" near " + format_position(at) +
                               " is pinned along part of its rim only; pin the whole rim or none");
      panel.holes.push_back({loops[l], label[0].second});
    }
    std::vector<int> loop = loops[outer];
    const int n = static_cast<int>(loop.size());
    std::vector<std::pair<int, int>> label = label_loop(loop);
    int start = -1;
    for (int i = 0; i < n && start < 0; ++i)
      if (label[i] != label[(i + n - 1) % n]) start = i;
    if (start < 0) {
      if (label[0].first >= 0)
        throw InputError(
            spec.source,
            in.panel_paths[p] + ": the seam between panels \"" + panel.name + "\" and \"" +
                in.panel_names[label[0].first] +
                "\" is a closed loop; split one of them so that the seam has two ends");
      start = 0;
    }
    std::rotate(loop.begin(), loop.begin() + start, loop.end());
    std::rotate(label.begin(), label.begin() + start, label.end());
    panel.boundary = loop;
    for (int i = 0; i < n; ++i) {
      if (i == 0 || label[i] != label[i - 1]) {
        BoundarySegment s;
        s.first = i;
        s.pin = label[i].second;
        s.seam = label[i].first >= 0 ? -2 - label[i].first : -1;  // neighbour, resolved below
        panel.segments.push_back(s);
      }
      ++panel.segments.back().count;
    }
  }

  // Seams: match each segment of panel p with neighbour q (p < q) to q's segment.
  auto seg_vertices = [&](int p, const BoundarySegment& s) {
    const LayoutPanel& panel = layout.panels[p];
    const int n = static_cast<int>(panel.boundary.size());
    std::vector<int> v;
    for (int i = 0; i <= s.count; ++i)
      v.push_back(panel.surface_vertex[panel.boundary[(s.first + i) % n]]);
    return v;
  };
  for (int p = 0; p < np; ++p) {
    for (size_t si = 0; si < layout.panels[p].segments.size(); ++si) {
      BoundarySegment& s = layout.panels[p].segments[si];
      if (s.seam > -2) continue;
      const int q = -2 - s.seam;
      if (q < p) continue;
      const std::vector<int> va = seg_vertices(p, s);
      int match = -1;
      for (size_t sj = 0; sj < layout.panels[q].segments.size(); ++sj) {
        const BoundarySegment& t = layout.panels[q].segments[sj];
        if (t.seam != -2 - p) continue;
        std::vector<int> vb = seg_vertices(q, t);
        std::reverse(vb.begin(), vb.end());
        if (vb == va) match = static_cast<int>(sj);
      }
      if (match < 0)
        throw InputError(spec.source,
                         "panels \"" + layout.panels[p].name + "\" and \"" + layout.panels[q].name +
                             "\" meet along an edge chain that is not one seam on both sides "
                             "(panels touching at a single vertex near " +
                             format_position(surf.vertices.row(va[0]).transpose()) + "?)");
      LayoutSeam seam;  // named by name_seams_top_down
      seam.panel_a = p;
      seam.segment_a = static_cast<int>(si);
      seam.panel_b = q;
      seam.segment_b = match;
      seam.vertices = va;
      const int id = static_cast<int>(layout.seams.size());
      s.seam = id;
      s.side_a = true;
      BoundarySegment& t = layout.panels[q].segments[match];
      t.seam = id;
      t.side_a = false;
      layout.seams.push_back(std::move(seam));
    }
  }
  for (const auto& panel : layout.panels)
    for (const auto& s : panel.segments)
      if (s.seam < -1)
        throw InputError(spec.source, "panel \"" + panel.name + "\": a seam has no matching side");
  name_seams_top_down(layout);
  return layout;
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
  // Panels whose boundaries run side by side without sharing vertices: a gap.
  {
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
        const double d = (in.surface.vertices.row(boundary[i].first) -
                          in.surface.vertices.row(boundary[j].first))
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
