#include "tightfit/garment/garment_builder.hpp"

#include <algorithm>

#include "tightfit/common/error.hpp"
#include "tightfit/garment/piece_mesher.hpp"
#include "tightfit/garment/triangle_geometry.hpp"
#include "tightfit/subdiv/limit_projector.hpp"

namespace tightfit {
namespace {

/// Closest point on the limit surface, started from the control face `body_face`
/// (at the point of that control triangle closest to p) when known, else found by the
/// projector's global search.
SurfacePoint project(const LimitSurface& limit, const LimitProjector& projector,
                     const TriMesh& control, const Vec3& p, int body_face) {
  if (body_face < 0) return projector.project(p);
  const Vec3 w = closest_point_weights(p, control.vertices.row(control.faces(body_face, 0)),
                                       control.vertices.row(control.faces(body_face, 1)),
                                       control.vertices.row(control.faces(body_face, 2)));
  // Local Newton from the face the point was cut from: near-touching body parts (the
  // inner thighs) cannot capture the point the way a global nearest search could.
  return refine_closest_point(limit, control.vertices, p, SurfacePoint{body_face, w[1], w[2]});
}

void move_layout_to_limit(Layout& layout, const LimitSurface& limit,
                          const LimitProjector& projector, const TriMesh& control) {
  const int nv = layout.surface.num_vertices();
  std::vector<int> face_of_vertex(nv, -1);
  for (int f = 0; f < layout.surface.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) face_of_vertex[layout.surface.faces(f, c)] = layout.body_face[f];
  for (int v = 0; v < nv; ++v) {
    const Vec3 p = layout.surface.vertices.row(v).transpose();
    const SurfacePoint s = project(limit, projector, control, p, face_of_vertex[v]);
    layout.surface.vertices.row(v) = limit.position(s, control.vertices).transpose();
  }
  for (auto& panel : layout.panels)
    for (size_t i = 0; i < panel.surface_vertex.size(); ++i)
      panel.mesh.vertices.row(static_cast<Eigen::Index>(i)) =
          layout.surface.vertices.row(panel.surface_vertex[i]);
}

}  // namespace

GarmentBuild build_garment(const TriMesh& control, const LimitSurface& limit,
                           const LayoutSpec& spec, const PatternOptions& options,
                           const LayoutRig& rig) {
  GarmentBuild out;
  const LayoutSpec absolute = resolve_layout_anchors(spec, control, rig);
  out.layout =
      absolute.is_mesh_layout() ? layout_from_obj(absolute) : layout_from_rules(control, absolute);
  const LimitProjector projector(limit, control.vertices);
  if (options.flatten_limit_surface) move_layout_to_limit(out.layout, limit, projector, control);

  PatternBuild build;
  try {
    build = build_pattern(out.layout, options);
  } catch (const InputError& e) {
    // The layout's warnings (e.g. parts cut off by openings) often explain the failure:
    // they go with it rather than being lost.
    if (out.layout.warnings.empty()) throw;
    std::string message = e.what();
    if (const std::string prefix = e.source() + ": ";
        !e.source().empty() && message.rfind(prefix, 0) == 0)
      message = message.substr(prefix.size());
    for (const std::string& w : out.layout.warnings) message += "\n  after the warning: " + w;
    throw InputError(e.source(), message);
  }
  out.maps = std::move(build.maps);
  out.seams = std::move(build.seams);
  for (size_t k = 0; k < build.pattern.pieces.size(); ++k) {
    const PatternPiece& piece = build.pattern.pieces[k];
    PieceReport r;
    r.name = piece.name;
    r.distortion = out.maps[k].distortion;
    r.scale = options.scale_of(piece.name);
    r.vertices = static_cast<int>(piece.rest.rows());
    r.triangles = static_cast<int>(piece.triangles.rows());
    r.min_angle_deg = min_angle_deg(piece.rest, piece.triangles);
    out.pieces.push_back(r);
  }
  out.garment = weld_pattern(std::move(build.pattern));

  // Embed: one panel point per garment vertex (the first pattern vertex welded to it).
  Garment& g = out.garment;
  const int ng = g.num_garment_vertices();
  std::vector<int> representative(ng, -1);
  for (int i = 0; i < g.num_pattern_vertices(); ++i)
    if (representative[g.topology->pattern_to_garment[i]] < 0)
      representative[g.topology->pattern_to_garment[i]] = i;
  g.embedding.resize(ng);
  out.positions.resize(ng, 3);
  out.projection_distance.resize(ng);
  for (int v = 0; v < ng; ++v) {
    const int i = representative[v];
    const int piece = static_cast<int>(std::upper_bound(g.topology->piece_offset.begin(),
                                                        g.topology->piece_offset.end(), i) -
                                       g.topology->piece_offset.begin()) -
                      1;
    const PieceMap& map = out.maps[piece];
    const PanelPoint& loc = map.location[i - g.topology->piece_offset[piece]];
    const Vec3 p = panel_position(out.layout, map, loc);
    const int surface_face = out.layout.panels[map.panel].surface_face[loc.face];
    g.embedding[v] = project(limit, projector, control, p, out.layout.body_face[surface_face]);
    const Vec3 x = limit.position(g.embedding[v], control.vertices);
    out.positions.row(v) = x.transpose();
    out.projection_distance[v] = (x - p).norm();
  }
  return out;
}

}  // namespace tightfit
