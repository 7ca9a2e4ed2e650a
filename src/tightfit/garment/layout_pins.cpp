#include "tightfit/garment/layout_build.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "tightfit/common/error.hpp"

namespace tightfit::layout_build {
namespace {

using Edge = std::pair<int, int>;  // (from, to) surface vertices

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

/// The open edges chained into loops (for "nearest").
std::vector<std::vector<Edge>> open_loops(const OpenEdges& open) {
  std::multimap<int, int> next;
  for (const auto& [e, p] : open.pin) next.emplace(e.first, e.second);
  std::vector<std::vector<Edge>> loops;
  std::map<Edge, bool> used;
  for (const auto& [e, p] : open.pin) {
    if (used[e]) continue;
    std::vector<Edge> loop;
    Edge cur = e;
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
  return loops;
}

/// The open loop nearest to the point of the "nearest" pin rule `pin` (InputError when
/// there is none within its max_distance).
const std::vector<Edge>& nearest_loop(const std::vector<std::vector<Edge>>& loops,
                                      const PinRule& pin, const TriMesh& m,
                                      const LayoutSpec& spec) {
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
  return loops[best_loop];
}

/// Whether the open edge e lies on the plane of pin rule `pin` (a region plane or a
/// plane of its own).
bool on_pin_plane(const Edge& e, const PinRule& pin, const TriMesh& m, const BuildInput& in,
                  const LayoutSpec& spec) {
  if (pin.kind == PinRule::Kind::kOnRegionPlane) {
    const auto& flags = in.on_region_plane[pin.region_plane];
    return flags[e.first] && flags[e.second];
  }
  return std::abs(pin.plane.distance(m.vertices.row(e.first).transpose())) <=
             spec.plane_tolerance &&
         std::abs(pin.plane.distance(m.vertices.row(e.second).transpose())) <= spec.plane_tolerance;
}

}  // namespace

OpenEdges assign_pins(const Layout& layout, const SurfaceTopology& topo, const BuildInput& in,
                      const LayoutSpec& spec) {
  OpenEdges open;
  const TriMesh& m = layout.surface;
  for (int f = 0; f < m.num_faces(); ++f)
    for (int i = 0; i < 3; ++i)
      if (topo.is_boundary_edge(topo.face_edge(f, i)))
        open.pin[{m.faces(f, i), m.faces(f, (i + 1) % 3)}] = -1;
  const std::vector<std::vector<Edge>> loops = open_loops(open);
  for (size_t k = 0; k < spec.pins.size(); ++k) {
    const PinRule& pin = spec.pins[k];
    int claimed = 0;
    auto claim = [&](const Edge& e) {
      ++claimed;
      int& slot = open.pin[e];
      if (slot < 0) slot = static_cast<int>(k);
    };
    if (pin.kind == PinRule::Kind::kNearest) {
      for (const auto& e : nearest_loop(loops, pin, m, spec)) claim(e);
      continue;
    }
    for (const auto& [e, p] : open.pin)
      if (on_pin_plane(e, pin, m, in, spec)) claim(e);
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
  return open;
}

}  // namespace tightfit::layout_build
