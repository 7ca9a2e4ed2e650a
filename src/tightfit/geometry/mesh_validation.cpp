#include "tightfit/geometry/mesh_validation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/mesh_measures.hpp"
#include "tightfit/geometry/self_intersection.hpp"
#include "tightfit/geometry/surface_topology.hpp"
#include "tightfit/geometry/text_parsing.hpp"

namespace tightfit {

namespace {

constexpr std::size_t kExamples = 3;

/// "N <plural>: <e1>; <e2>; <e3>; ..." or "<singular>: <e1>" for one item, where
/// describe(i) tells about item i.
std::string summarize(const std::vector<int>& items, const std::string& singular,
                      const std::string& plural, const std::function<std::string(int)>& describe) {
  std::string s = items.size() == 1 ? singular : std::to_string(items.size()) + " " + plural;
  s += ": ";
  for (std::size_t k = 0; k < std::min(items.size(), kExamples); ++k) {
    if (k) s += "; ";
    s += describe(items[k]);
  }
  if (items.size() > kExamples) s += "; ...";
  return s;
}

std::string point_text(const Points3& v, int i) {
  // Appended piece by piece: GCC 12 gives a false -Wrestrict on "literal" + string.
  std::string s = "(";
  s += text::format_double(v(i, 0));
  s += ", ";
  s += text::format_double(v(i, 1));
  s += ", ";
  s += text::format_double(v(i, 2));
  s += ")";
  return s;
}

std::vector<int> non_finite_vertices(const Points3& v) {
  std::vector<int> bad;
  for (int i = 0; i < v.rows(); ++i)
    if (!v.row(i).allFinite()) bad.push_back(i);
  return bad;
}

std::string join(const std::vector<std::string>& problems) {
  std::string s;
  for (const auto& p : problems) {
    if (!s.empty()) s += "; ";
    s += p;
  }
  return s;
}

}  // namespace

std::vector<std::string> surface_problems(const TriMesh& mesh, const SurfaceRequirements& req) {
  std::vector<std::string> problems;
  const int nv = mesh.num_vertices();
  const int nf = mesh.num_faces();
  if (nf == 0) {
    problems.push_back("the mesh has no faces");
    return problems;
  }

  const std::vector<int> non_finite = non_finite_vertices(mesh.vertices);
  if (!non_finite.empty())
    problems.push_back(summarize(
        non_finite, "non-finite vertex coordinates", "vertices with non-finite coordinates",
        [&](int i) { return "vertex " + std::to_string(i) + " " + point_text(mesh.vertices, i); }));

  std::vector<int> bad_index;
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.faces(f, k) < 0 || mesh.faces(f, k) >= nv) {
        bad_index.push_back(f);
        break;
      }
  if (!bad_index.empty()) {
    problems.push_back(
        summarize(bad_index, "bad vertex index", "faces with bad vertex indices", [&](int f) {
          return "face " + std::to_string(f) + " (" + std::to_string(mesh.faces(f, 0)) + ", " +
                 std::to_string(mesh.faces(f, 1)) + ", " + std::to_string(mesh.faces(f, 2)) +
                 ") has an index outside [0, " + std::to_string(nv) + ")";
        }));
    return problems;
  }

  // Degenerate faces.
  std::vector<int> repeated, zero_area;
  for (int f = 0; f < nf; ++f) {
    const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    if (a == b || b == c || a == c) {
      repeated.push_back(f);
      continue;
    }
    if (!non_finite.empty()) continue;
    const Vec3 pa = mesh.vertices.row(a), pb = mesh.vertices.row(b), pc = mesh.vertices.row(c);
    const double longest = std::max({(pb - pa).norm(), (pc - pb).norm(), (pa - pc).norm()});
    const double twice_area = (pb - pa).cross(pc - pa).norm();
    if (twice_area <= req.degenerate_tolerance * longest * longest) zero_area.push_back(f);
  }
  auto face_text = [&](int f) {
    return "face " + std::to_string(f) + " (" + std::to_string(mesh.faces(f, 0)) + ", " +
           std::to_string(mesh.faces(f, 1)) + ", " + std::to_string(mesh.faces(f, 2)) + ")";
  };
  if (!repeated.empty())
    problems.push_back(summarize(repeated, "degenerate face repeating a vertex",
                                 "degenerate faces repeating a vertex", face_text));
  if (!zero_area.empty())
    problems.push_back(summarize(zero_area, "degenerate face with zero area",
                                 "degenerate faces with zero area", face_text));

  // Topology of the faces that do not repeat a vertex (those are reported above and
  // would otherwise add self-loop "holes" and spurious non-manifold edges).
  std::vector<int> kept;  // original face id of each face in `topo`
  for (int f = 0, r = 0; f < nf; ++f) {
    if (r < static_cast<int>(repeated.size()) && repeated[r] == f) {
      ++r;
      continue;
    }
    kept.push_back(f);
  }
  Triangles kept_faces(static_cast<int>(kept.size()), 3);
  for (int k = 0; k < static_cast<int>(kept.size()); ++k)
    kept_faces.row(k) = mesh.faces.row(kept[k]);
  const SurfaceTopology topo(kept_faces, nv);
  auto edge_text = [&](int e) {
    const auto ev = topo.edge_vertices(e);
    return std::to_string(ev[0]) + "-" + std::to_string(ev[1]);
  };
  const auto nm_edges = topo.non_manifold_edges();
  if (!nm_edges.empty())
    problems.push_back(summarize(nm_edges, "non-manifold edge", "non-manifold edges", [&](int e) {
      return "edge " + edge_text(e) + " has " + std::to_string(topo.edge_valence(e)) + " faces";
    }));
  const auto nm_vertices = topo.non_manifold_vertices();
  if (!nm_vertices.empty())
    problems.push_back(
        summarize(nm_vertices, "non-manifold vertex", "non-manifold vertices", [&](int v) {
          return "the faces around vertex " + std::to_string(v) + " form more than one fan";
        }));
  if (!req.allow_isolated_vertices) {
    const auto isolated = topo.isolated_vertices();
    if (!isolated.empty())
      problems.push_back(summarize(isolated, "unused vertex", "unused vertices", [](int v) {
        return "vertex " + std::to_string(v) + " is in no face";
      }));
  }
  bool holes = false;
  if (req.closed && !nm_edges.empty()) {
    // Boundary loops are not well defined next to non-manifold edges: count edges.
    const auto boundary = topo.boundary_edges();
    holes = !boundary.empty();
    if (holes)
      problems.push_back(summarize(boundary, "the surface is not closed: it has a boundary edge",
                                   "boundary edges (the surface must be closed)",
                                   [&](int e) { return "edge " + edge_text(e); }));
  } else if (req.closed) {
    const auto loops = topo.boundary_loops();
    holes = !loops.empty();
    if (holes) {
      std::vector<int> ids(loops.size());
      for (std::size_t k = 0; k < loops.size(); ++k) ids[k] = static_cast<int>(k);
      problems.push_back(
          summarize(ids, "the surface is not closed: it has a hole",
                    "holes (the surface must be closed)", [&](int k) {
                      const auto& loop = loops[k];
                      std::string s = "boundary loop of ";
                      s += std::to_string(loop.size());
                      s += loop.size() == 1 ? " edge through vertices" : " edges through vertices";
                      for (std::size_t i = 0; i < std::min<std::size_t>(loop.size(), 4); ++i) {
                        s += ' ';
                        s += std::to_string(loop[i]);
                      }
                      if (loop.size() > 4) s += " ...";
                      return s;
                    }));
    }
  }
  const auto inconsistent = topo.inconsistently_oriented_edges();
  if (!inconsistent.empty())
    problems.push_back(summarize(inconsistent, "inconsistent orientation",
                                 "edges with inconsistent orientation", [&](int e) {
                                   const auto ef = topo.edge_faces(e);
                                   return "faces " + std::to_string(kept[ef[0]]) + " and " +
                                          std::to_string(kept[ef[1]]) + " traverse edge " +
                                          edge_text(e) + " in the same direction";
                                 }));

  const bool topology_ok = nm_edges.empty() && nm_vertices.empty() && inconsistent.empty();
  const bool geometry_ok = non_finite.empty() && repeated.empty() && zero_area.empty();
  if (req.closed && !holes && topology_ok && non_finite.empty()) {
    const double volume = signed_volume(mesh);
    if (volume < 0)
      problems.push_back("inward orientation: the enclosed signed volume is " +
                         text::format_double(volume) +
                         " < 0 (faces must be counter-clockwise seen from outside)");
    else if (volume == 0)
      problems.push_back("the closed surface encloses zero volume");
  }
  if (req.check_self_intersections && problems.empty() && topology_ok && geometry_ok) {
    const auto pairs = self_intersecting_face_pairs(mesh);
    if (!pairs.empty()) {
      std::vector<int> ids(pairs.size());
      for (std::size_t k = 0; k < pairs.size(); ++k) ids[k] = static_cast<int>(k);
      problems.push_back(
          summarize(ids, "self-intersection", "self-intersecting face pairs", [&](int k) {
            // Where: between the two faces' centroids, in the file's coordinates.
            Vec3 at = Vec3::Zero();
            for (const int f : pairs[k])
              for (int c = 0; c < 3; ++c)
                at += mesh.vertices.row(mesh.faces(f, c)).transpose() / 6.0;
            char near[96];
            std::snprintf(near, sizeof near, " intersect near (%.4g, %.4g, %.4g)", at.x(), at.y(),
                          at.z());
            return "faces " + std::to_string(pairs[k][0]) + " and " + std::to_string(pairs[k][1]) +
                   near;
          }));
    }
  }
  return problems;
}

void validate_surface(const TriMesh& mesh, const std::string& source,
                      const SurfaceRequirements& req) {
  const auto problems = surface_problems(mesh, req);
  if (!problems.empty()) throw InputError(source, join(problems));
}

std::vector<std::string> tet_mesh_problems(const TetMesh& mesh, const TetRequirements& req) {
  std::vector<std::string> problems;
  const int nv = mesh.num_vertices();
  const int nt = mesh.num_tets();
  if (nt == 0) {
    problems.push_back("the tet mesh has no tetrahedra");
    return problems;
  }
  const std::vector<int> non_finite = non_finite_vertices(mesh.vertices);
  if (!non_finite.empty())
    problems.push_back(summarize(
        non_finite, "non-finite vertex coordinates", "vertices with non-finite coordinates",
        [&](int i) { return "vertex " + std::to_string(i) + " " + point_text(mesh.vertices, i); }));
  auto tet_text = [&](int t) {
    return "tet " + std::to_string(t) + " (" + std::to_string(mesh.tets(t, 0)) + ", " +
           std::to_string(mesh.tets(t, 1)) + ", " + std::to_string(mesh.tets(t, 2)) + ", " +
           std::to_string(mesh.tets(t, 3)) + ")";
  };
  std::vector<int> bad_index, repeated;
  for (int t = 0; t < nt; ++t) {
    bool bad = false;
    for (int k = 0; k < 4; ++k) bad = bad || mesh.tets(t, k) < 0 || mesh.tets(t, k) >= nv;
    if (bad) {
      bad_index.push_back(t);
      continue;
    }
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (mesh.tets(t, i) == mesh.tets(t, j) && (repeated.empty() || repeated.back() != t))
          repeated.push_back(t);
  }
  if (!bad_index.empty()) {
    problems.push_back(
        summarize(bad_index, "bad vertex index", "tets with bad vertex indices", [&](int t) {
          return tet_text(t) + " has an index outside [0, " + std::to_string(nv) + ")";
        }));
    return problems;
  }
  if (!repeated.empty())
    problems.push_back(summarize(repeated, "degenerate tet repeating a vertex",
                                 "degenerate tets repeating a vertex", tet_text));
  if (!non_finite.empty()) return problems;

  std::vector<int> inverted, flat;
  const VecX volumes = tet_volumes(mesh);
  for (int t = 0; t < nt; ++t) {
    if (std::find(repeated.begin(), repeated.end(), t) != repeated.end()) continue;
    double longest = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        longest = std::max(
            longest,
            (mesh.vertices.row(mesh.tets(t, i)) - mesh.vertices.row(mesh.tets(t, j))).norm());
    if (6.0 * std::abs(volumes[t]) <= req.degenerate_tolerance * longest * longest * longest)
      flat.push_back(t);
    else if (volumes[t] < 0)
      inverted.push_back(t);
  }
  if (!inverted.empty())
    problems.push_back(summarize(inverted, "inverted tet", "inverted tets", [&](int t) {
      return tet_text(t) + " has volume " + text::format_double(volumes[t]);
    }));
  if (!flat.empty())
    problems.push_back(summarize(flat, "zero-volume tet", "zero-volume tets", [&](int t) {
      return tet_text(t) + " has volume " + text::format_double(volumes[t]);
    }));
  return problems;
}

void validate_tet_mesh(const TetMesh& mesh, const std::string& source, const TetRequirements& req) {
  const auto problems = tet_mesh_problems(mesh, req);
  if (!problems.empty()) throw InputError(source, join(problems));
}

}  // namespace tightfit
