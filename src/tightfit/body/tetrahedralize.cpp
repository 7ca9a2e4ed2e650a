#include "tightfit/body/tetrahedralize.hpp"

#include "tightfit/common/mesh_budget.hpp"

#include <tetgen.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

#include "tightfit/body/surface_distance.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/geometry/mesh_validation.hpp"

namespace tightfit {

double regular_tet_volume(double edge) { return edge * edge * edge / (6.0 * std::sqrt(2.0)); }

std::string tetgen_switches(const TetQuality& q) {
  if (!(q.max_radius_edge >= 1.0) || !std::isfinite(q.max_radius_edge))
    throw std::invalid_argument("max radius-edge ratio must be ≥ 1.0");
  if (!(q.min_dihedral_deg >= 0.0 && q.min_dihedral_deg <= 18.0))
    throw std::invalid_argument("min dihedral angle must be in [0, 18] degrees");
  if (!(q.max_volume >= 0.0) || !std::isfinite(q.max_volume))
    throw std::invalid_argument("max tet volume must be non-negative");
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "pYMq%.6g/%.6g", q.max_radius_edge, q.min_dihedral_deg);
  std::string s = buffer;
  if (q.max_volume > 0.0) {
    std::snprintf(buffer, sizeof buffer, "a%.6e", q.max_volume);
    s += buffer;
  }
  return s + "zQ";
}

namespace {

std::string tetgen_error_text(int code) {
  switch (code) {
    case 1:
      return "TetGen ran out of memory";
    case 3:
      return "the surface intersects itself";
    case 4:
      return "the surface has a very small feature (nearly touching parts)";
    case 5:
      return "the surface has two very close facets";
    case 10:
      return "TetGen rejected the input";
    default:
      return "TetGen failed with internal error " + std::to_string(code);
  }
}

using Face = std::array<int, 3>;
Face sorted_face(int a, int b, int c) {
  Face f{a, b, c};
  std::sort(f.begin(), f.end());
  return f;
}

/// Throws SolverError unless the boundary faces of `tets` are exactly the faces of
/// `surface` (as vertex sets, each once).
void check_boundary(const Tetrahedra& tets, const Triangles& faces) {
  std::map<Face, int> count;
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (Eigen::Index t = 0; t < tets.rows(); ++t)
    for (const auto& f : kFaces) ++count[sorted_face(tets(t, f[0]), tets(t, f[1]), tets(t, f[2]))];
  std::set<Face> boundary;
  for (const auto& [face, n] : count) {
    if (n > 2) throw SolverError("tetrahedralization: a face is shared by more than two tets");
    if (n == 1) boundary.insert(face);
  }
  std::set<Face> input;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    input.insert(sorted_face(faces(f, 0), faces(f, 1), faces(f, 2)));
  if (boundary != input)
    throw SolverError("tetrahedralization: the boundary of the tet mesh (" +
                      std::to_string(boundary.size()) + " faces) differs from the surface (" +
                      std::to_string(input.size()) + " faces)");
}

/// TetGen 1.5.0 frees its memory twice when it stops on bad input (terminatetetgen
/// frees, then the unwinding destructor frees again) and crashes, so everything it would
/// reject is checked here first.
void check_input(const TriMesh& surface, const TriMesh& internal, const Points3& interior,
                 const Triangles& facets, const Points3& fixed) {
  std::vector<std::string> problems = surface_problems(surface);
  if (!problems.empty()) throw InputError("surface", problems.front());
  if (internal.num_faces() == 0 && interior.rows() == 0) return;
  const SurfaceDistance outer(surface);
  if (internal.num_faces() > 0) {
    problems = surface_problems(internal);
    if (!problems.empty()) throw InputError("internal surface", problems.front());
    problems = surface_problems(
        TriMesh{fixed.topRows(surface.num_vertices() + internal.num_vertices()), facets});
    if (!problems.empty())
      throw InputError("internal surface", "it touches the surface: " + problems.front());
    for (int v = 0; v < internal.num_vertices(); ++v)
      if (!outer.contains(internal.vertices.row(v)))
        throw InputError("internal surface",
                         "vertex " + std::to_string(v) + " is outside the surface");
  }
  if (interior.rows() > 0) {
    const SurfaceDistance inner(internal);
    for (Eigen::Index i = 0; i < interior.rows(); ++i) {
      const Vec3 p = interior.row(i);
      if (!outer.contains(p) || outer.distance(p) == 0.0)
        throw InputError("interior points",
                         "point " + std::to_string(i) + " is not strictly inside the surface");
      if (internal.num_faces() > 0 && inner.distance(p) == 0.0)
        throw InputError("interior points",
                         "point " + std::to_string(i) + " lies on the internal surface");
    }
  }
}

/// The volume (m³) a closed, outward-oriented surface encloses (divergence theorem).
double enclosed_volume(const TriMesh& surface) {
  double six_volume = 0.0;
  for (int f = 0; f < surface.num_faces(); ++f) {
    const Vec3 a = surface.vertices.row(surface.faces(f, 0));
    const Vec3 b = surface.vertices.row(surface.faces(f, 1));
    const Vec3 c = surface.vertices.row(surface.faces(f, 2));
    six_volume += a.dot(b.cross(c));
  }
  return std::abs(six_volume) / 6.0;
}

}  // namespace

TetMesh tetrahedralize_surface(const TriMesh& surface, const TetQuality& quality,
                               const Points3& interior_points, const TriMesh& internal_surface) {
  const std::string switches = tetgen_switches(quality);
  const int n_surface = surface.num_vertices();
  const int n_internal = internal_surface.num_vertices();
  // Input vertices in their final order: surface, internal surface, interior points.
  Points3 fixed(n_surface + n_internal + interior_points.rows(), 3);
  fixed << surface.vertices, internal_surface.vertices, interior_points;
  Triangles facets(surface.num_faces() + internal_surface.num_faces(), 3);
  facets << surface.faces, (internal_surface.faces.array() + n_surface).matrix();
  const int n_fixed = static_cast<int>(fixed.rows());
  check_input(surface, internal_surface, interior_points, facets, fixed);
  check_tet_budget(enclosed_volume(surface), quality.max_volume, "surface");

  tetgenio in;
  in.firstnumber = 0;
  in.numberofpoints = n_fixed;
  in.pointlist = new REAL[3 * static_cast<size_t>(n_fixed)];
  for (int i = 0; i < n_fixed; ++i)
    for (int c = 0; c < 3; ++c) in.pointlist[3 * i + c] = fixed(i, c);
  const int n_facets = static_cast<int>(facets.rows());
  in.numberoffacets = n_facets;
  in.facetlist = new tetgenio::facet[static_cast<size_t>(n_facets)];
  for (int f = 0; f < n_facets; ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3];
    for (int c = 0; c < 3; ++c) facet.polygonlist[0].vertexlist[c] = facets(f, c);
  }

  tetgenio out;
  tetgenbehavior behavior;
  std::vector<char> switch_buffer(switches.begin(), switches.end());
  switch_buffer.push_back('\0');
  if (!behavior.parse_commandline(switch_buffer.data()))
    throw std::logic_error("TetGen rejected the switches " + switches);
  try {
    tetrahedralize(&behavior, &in, &out);
  } catch (int code) {
    if (code == 3 || code == 4 || code == 5 || code == 10)
      throw InputError("surface", tetgen_error_text(code));
    throw SolverError(tetgen_error_text(code));
  }
  if (out.numberofcorners != 4 || out.numberoftetrahedra <= 0)
    throw SolverError("tetrahedralization produced no tetrahedra");

  // Map TetGen's vertices so that the input points come first, in input order. TetGen
  // keeps them first already; the reordering only guards against a library change.
  const int n_out = out.numberofpoints;
  std::vector<int> new_index(static_cast<size_t>(n_out), -1);
  bool identity = n_out >= n_fixed;
  for (int i = 0; identity && i < n_fixed; ++i)
    for (int c = 0; c < 3; ++c)
      if (out.pointlist[3 * i + c] != in.pointlist[3 * i + c]) identity = false;
  if (identity) {
    for (int i = 0; i < n_out; ++i) new_index[i] = i;
  } else {
    std::map<std::array<double, 3>, int> input_index;
    for (int i = 0; i < n_fixed; ++i)
      input_index.emplace(std::array<double, 3>{in.pointlist[3 * i], in.pointlist[3 * i + 1],
                                                in.pointlist[3 * i + 2]},
                          i);
    int next = n_fixed;
    for (int i = 0; i < n_out; ++i) {
      auto it = input_index.find(
          {out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]});
      if (it != input_index.end() && new_index[i] < 0) {
        new_index[i] = it->second;
        input_index.erase(it);
      } else {
        new_index[i] = next++;
      }
    }
    if (!input_index.empty())
      throw SolverError("tetrahedralization dropped " + std::to_string(input_index.size()) +
                        " input vertices (interior points outside the surface?)");
  }

  TetMesh mesh;
  mesh.vertices.resize(n_out, 3);
  for (int i = 0; i < n_out; ++i)
    for (int c = 0; c < 3; ++c) mesh.vertices(new_index[i], c) = out.pointlist[3 * i + c];
  mesh.tets.resize(out.numberoftetrahedra, 4);
  for (int t = 0; t < out.numberoftetrahedra; ++t) {
    for (int c = 0; c < 4; ++c) mesh.tets(t, c) = new_index[out.tetrahedronlist[4 * t + c]];
    const Vec3 p0 = mesh.vertices.row(mesh.tets(t, 0));
    const double orientation = (Vec3(mesh.vertices.row(mesh.tets(t, 1))) - p0)
                                   .dot((Vec3(mesh.vertices.row(mesh.tets(t, 2))) - p0)
                                            .cross(Vec3(mesh.vertices.row(mesh.tets(t, 3))) - p0));
    if (orientation == 0.0) throw SolverError("tetrahedralization produced a flat tet");
    if (orientation < 0.0) std::swap(mesh.tets(t, 2), mesh.tets(t, 3));
  }

  // The Body invariant: surface vertex i == volume vertex i, and the boundary is the surface.
  for (int i = 0; i < n_fixed; ++i) {
    if (mesh.vertices.row(i) != fixed.row(i))
      throw SolverError("tetrahedralization: volume vertex " + std::to_string(i) +
                        " is not input vertex " + std::to_string(i));
  }
  check_boundary(mesh.tets, surface.faces);
  return mesh;
}

}  // namespace tightfit
