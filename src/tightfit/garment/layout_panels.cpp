#include "tightfit/garment/layout_build.hpp"

#include <algorithm>
#include <map>
#include <queue>
#include <sstream>

#include "tightfit/common/error.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit::layout_build {

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

namespace {

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

/// A layout with the spec's settings and pin names, its surface compacted to the faces
/// of `in` with a panel (InputError when an edge of it has more than two faces).
Layout start_layout(BuildInput& in, const LayoutSpec& spec) {
  Layout layout;
  layout.source = spec.source;
  layout.seam_tolerance = spec.seam_tolerance;
  layout.area_tolerance = spec.area_tolerance;
  layout.pin_names.clear();
  for (const auto& p : spec.pins) layout.pin_names.push_back(p.name);
  compact(in, layout);
  return layout;
}

/// Panel p's faces of the layout surface as a mesh of its own (InputError when it has
/// none or is not a disc, possibly with holes).
LayoutPanel make_panel(const Layout& layout, int p, const BuildInput& in, const LayoutSpec& spec) {
  const TriMesh& surf = layout.surface;
  LayoutPanel panel;
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
  return panel;
}

/// Per edge of a boundary loop of panel p (panel vertex indices): (the neighbour panel
/// across it or −1, the pin claiming it or −1).
using EdgeLabels = std::vector<std::pair<int, int>>;

EdgeLabels label_loop(const Layout& layout, const SurfaceTopology& topo, const OpenEdges& open,
                      int p, const std::vector<int>& loop) {
  const LayoutPanel& panel = layout.panels[p];
  const int n = static_cast<int>(loop.size());
  EdgeLabels label(n);
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
}

/// Panel p's holes: its boundary loops but the outer one, each made by an opening, along
/// no other panel, pinned along its whole rim or not at all (InputError otherwise).
void add_holes(Layout& layout, const SurfaceTopology& topo, const OpenEdges& open, int p,
               const std::vector<std::vector<int>>& loops, int outer, const BuildInput& in,
               const LayoutSpec& spec) {
  LayoutPanel& panel = layout.panels[p];
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
    const EdgeLabels label = label_loop(layout, topo, open, p, loops[l]);
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
                         in.panel_paths[p] + ": the opening of panel \"" + panel.name + "\" near " +
                             format_position(at) +
                             " is pinned along part of its rim only; pin the whole rim or none");
    panel.holes.push_back({loops[l], label[0].second});
  }
}

/// Panel p's outer boundary `loop`, started at a segment corner, and its segments (a seam
/// segment holds −2 − its neighbour panel until match_seams resolves it).
void add_segments(Layout& layout, const SurfaceTopology& topo, const OpenEdges& open, int p,
                  std::vector<int> loop, const BuildInput& in, const LayoutSpec& spec) {
  LayoutPanel& panel = layout.panels[p];
  const int n = static_cast<int>(loop.size());
  EdgeLabels label = label_loop(layout, topo, open, p, loop);
  int start = -1;
  for (int i = 0; i < n && start < 0; ++i)
    if (label[i] != label[(i + n - 1) % n]) start = i;
  if (start < 0) {
    if (label[0].first >= 0)
      throw InputError(spec.source,
                       in.panel_paths[p] + ": the seam between panels \"" + panel.name +
                           "\" and \"" + in.panel_names[label[0].first] +
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
      s.seam = label[i].first >= 0 ? -2 - label[i].first : -1;  // neighbour, resolved later
      panel.segments.push_back(s);
    }
    ++panel.segments.back().count;
  }
}

/// The surface vertices of panel p's segment s, in the boundary's direction.
std::vector<int> segment_vertices(const Layout& layout, int p, const BoundarySegment& s) {
  const LayoutPanel& panel = layout.panels[p];
  const int n = static_cast<int>(panel.boundary.size());
  std::vector<int> v;
  for (int i = 0; i <= s.count; ++i)
    v.push_back(panel.surface_vertex[panel.boundary[(s.first + i) % n]]);
  return v;
}

/// The seams: each segment of panel p along neighbour q (p < q) matched to q's segment
/// along the same vertices in the opposite direction (InputError when there is none).
void match_seams(Layout& layout, const LayoutSpec& spec) {
  const int np = static_cast<int>(layout.panels.size());
  for (int p = 0; p < np; ++p) {
    for (size_t si = 0; si < layout.panels[p].segments.size(); ++si) {
      BoundarySegment& s = layout.panels[p].segments[si];
      if (s.seam > -2) continue;
      const int q = -2 - s.seam;
      if (q < p) continue;
      const std::vector<int> va = segment_vertices(layout, p, s);
      int match = -1;
      for (size_t sj = 0; sj < layout.panels[q].segments.size(); ++sj) {
        const BoundarySegment& t = layout.panels[q].segments[sj];
        if (t.seam != -2 - p) continue;
        std::vector<int> vb = segment_vertices(layout, q, t);
        std::reverse(vb.begin(), vb.end());
        if (vb == va) match = static_cast<int>(sj);
      }
      if (match < 0)
        throw InputError(spec.source,
                         "panels \"" + layout.panels[p].name + "\" and \"" + layout.panels[q].name +
                             "\" meet along an edge chain that is not one seam on both sides "
                             "(panels touching at a single vertex near " +
                             format_position(layout.surface.vertices.row(va[0]).transpose()) +
                             "?)");
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
}

}  // namespace

Layout build_layout(BuildInput in, const LayoutSpec& spec) {
  Layout layout = start_layout(in, spec);
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
  const int np = static_cast<int>(in.panel_names.size());
  layout.panels.resize(np);
  for (int p = 0; p < np; ++p) {
    layout.panels[p] = make_panel(layout, p, in, spec);
    const LayoutPanel& panel = layout.panels[p];
    const SurfaceTopology ptopo(panel.mesh.faces, panel.mesh.num_vertices());
    const std::vector<std::vector<int>> loops = ptopo.boundary_loops();
    const int outer = outer_loop(panel, loops, in.on_opening);
    add_holes(layout, topo, open, p, loops, outer, in, spec);
    add_segments(layout, topo, open, p, loops[outer], in, spec);
  }
  match_seams(layout, spec);
  name_seams_top_down(layout);
  return layout;
}

}  // namespace tightfit::layout_build
