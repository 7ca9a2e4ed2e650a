#pragma once
/// What the layout builders of layout.hpp share (internal to the garment layer): the
/// input of the common builder, which makes the panels, their boundary segments and the
/// seams (layout_panels.cpp), from a cut body surface (layout_from_rules) or a mesh with
/// a group per panel (layout_from_groups; both layout_inputs.cpp), and the assignment
/// of the pinned boundaries (layout_pins.cpp).
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tightfit/garment/layout.hpp"
#include "tightfit/geometry/surface_topology.hpp"

namespace tightfit::layout_build {

/// "(x, y, z) m" with four significant digits, for error messages.
std::string format_position(const Vec3& p);
/// The centroid of face f of m.
Vec3 face_centroid(const TriMesh& m, int f);

/// Everything the shared builder needs besides the surface.
struct BuildInput {
  TriMesh surface;  ///< may contain faces outside the garment (panel −1)
  std::vector<int> face_panel;
  std::vector<int> body_face;  ///< or empty
  std::vector<std::string> panel_names;
  std::vector<std::string> panel_paths;  ///< JSON path per panel (or the mesh source)
  /// Region-plane flags per vertex (rules layouts); empty for mesh layouts.
  std::vector<std::vector<char>> on_region_plane;
  /// Per vertex: on the rim of one of the spec's openings (rules layouts, all 0 without
  /// openings); empty for mesh layouts, whose inner boundary loops are all openings.
  std::vector<char> on_opening;
};

/// Directed open boundary edges of the garment (following face orientation) and the
/// pin claiming each (−1: none).
struct OpenEdges {
  std::map<std::pair<int, int>, int> pin;  ///< (from, to) → pin index or −1
};

/// The open boundary edges of the layout's (compacted) surface, each claimed by the first
/// of the spec's pin rules that covers it. InputError (the rule's JSON path) for a rule
/// that claims no edge or whose nearest open boundary is too far.
OpenEdges assign_pins(const Layout& layout, const SurfaceTopology& topo, const BuildInput& in,
                      const LayoutSpec& spec);

/// The layout of `in`'s panels: the surface compacted to the faces with a panel, each
/// panel checked (a disc, possibly with holes made by openings), its boundary split into
/// segments, the seams matched and named (layout.hpp's rules; InputError otherwise).
Layout build_layout(BuildInput in, const LayoutSpec& spec);

}  // namespace tightfit::layout_build
