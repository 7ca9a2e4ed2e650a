#pragma once
/// A garment layout on a body: panels (disc-shaped pieces of a surface lying on the
/// body), the seams where two panels meet, the open boundaries where the garment ends,
/// and which open boundaries are pinned. Built from a LayoutSpec, either by cutting the
/// body surface with the spec's planes or from an OBJ with one group per panel.
///
/// Every panel is validated: connected, manifold, a topological disc (Euler
/// characteristic 1) or a disc with holes made by openings (one outer boundary loop
/// plus one loop per hole, no handles). Seams are maximal runs of panel boundary edges shared
/// with the same other panel; a seam that is a closed loop is rejected (split one of
/// its panels so that the seam has two ends).
#include <string>
#include <vector>

#include "tightfit/garment/layout_spec.hpp"
#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// A maximal run of a panel's boundary loop with one kind: part of a seam or an open
/// boundary (pinned or free). Runs from boundary[first] through `count` edges, wrapping
/// around the loop (first + count may exceed the loop length; count = loop length for a
/// segment that is the whole loop).
struct BoundarySegment {
  int first = 0;
  int count = 0;
  int seam = -1;       ///< index into Layout::seams, or −1 for an open boundary
  bool side_a = true;  ///< seams: whether this segment is side a of the seam
  int pin = -1;        ///< open boundaries: index into Layout::pin_names, or −1
};

/// An opening inside a panel (a hole; e.g. a mask's eye): an open boundary loop, never
/// part of a seam.
struct PanelHole {
  /// The loop in panel vertex indices, interior of the panel on its left.
  std::vector<int> loop;
  int pin = -1;  ///< index into Layout::pin_names when the whole rim is pinned, or −1
};

/// One panel: a disc-shaped part of the layout surface (possibly with holes made by
/// openings) with its own vertex numbering.
struct LayoutPanel {
  std::string name;
  TriMesh mesh;                     ///< the panel (m); faces oriented like the body
  std::vector<int> surface_vertex;  ///< panel vertex → Layout::surface vertex
  std::vector<int> surface_face;    ///< panel face → Layout::surface face
  /// The boundary loop in panel vertex indices, counter-clockwise seen from outside
  /// (interior on the left); starts at a segment corner when there is one.
  std::vector<int> boundary;
  std::vector<BoundarySegment> segments;  ///< in loop order, covering the loop
  std::vector<PanelHole> holes;           ///< openings inside the panel
};

/// A seam: panel a's segment and panel b's segment run along the same surface
/// polyline in opposite directions.
struct LayoutSeam {
  std::string name;
  int panel_a = -1, segment_a = -1;
  int panel_b = -1, segment_b = -1;
  /// Surface vertices along the seam, in panel a's boundary direction.
  std::vector<int> vertices;
};

/// A laid-out garment (before flattening).
struct Layout {
  std::string source;           ///< spec source, for error messages
  TriMesh surface;              ///< all panel faces (m)
  std::vector<int> face_panel;  ///< per surface face: its panel
  /// Per surface face: the body control face it was cut from (rules layouts), or −1.
  std::vector<int> body_face;
  std::vector<LayoutPanel> panels;
  std::vector<LayoutSeam> seams;
  std::vector<std::string> pin_names;  ///< one per PinRule of the spec
  double seam_tolerance = 0.05;        ///< copied from the spec
  double area_tolerance = 0.5;         ///< copied from the spec
  /// What the builder changed that the user should know (e.g. surface an opening cut
  /// off and left out), prefixed with the spec source.
  std::vector<std::string> warnings;
};

/// Cuts `body_surface` (closed, outward-oriented; m) by the spec's region planes and
/// dividers and builds the panels. Throws InputError (naming the spec source and JSON
/// path) for faces in no panel or in two, panels that are empty or not discs, closed
/// seams, and pins that match no open boundary.
Layout layout_from_rules(const TriMesh& body_surface, const LayoutSpec& spec);

/// Builds the panels from a mesh lying on the body with a panel index per face.
/// Vertices closer than `spec.weld_tolerance` are welded first. Faces whose group is
/// −1 are in no panel (an error), the same triangle in two panels is an error.
/// `mesh_source` names the mesh in error messages.
Layout layout_from_groups(const TriMesh& mesh, const std::vector<int>& face_group,
                          const std::vector<std::string>& group_names, const LayoutSpec& spec,
                          const std::string& mesh_source);

/// Reads spec.mesh_file (OBJ with one group per panel) and calls layout_from_groups.
Layout layout_from_obj(const LayoutSpec& spec);

}  // namespace tightfit
