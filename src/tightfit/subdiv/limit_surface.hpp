#pragma once
/// The Loop limit surface of a closed triangle control mesh (docs/design.md §3, §6; paper
/// Sec. 3.1 and Eq. 18-20), evaluated with OpenSubdiv's Bfr as stencils: weights over
/// control vertices that depend on topology and (face, u, v) only. The same object
/// therefore serves a deforming body: positions are passed to every call.
///
/// Parametrization of a face (SurfacePoint): corner 0, 1, 2 of the control triangle at
/// (u, v) = (0,0), (1,0), (0,1); face edge i runs from corner i to corner (i+1)%3.
/// Across a shared edge the two faces' (u, v) are related by the affine map that makes
/// the two parameter triangles a parallelogram (the regular Loop lattice); see walk().
///
/// Accuracy: within 2^-L (L = approx_level_smooth) of an extraordinary vertex (EV,
/// valence ≠ 6) OpenSubdiv uses a Gregory patch, whose position is off the exact limit
/// by ~3e-4 edge lengths at L = 8 and whose derivatives are not exactly those of its
/// position. Everywhere else the stencils are exact (box-spline patches): positions
/// match uniform Loop subdivision with limit masks, derivatives match finite
/// differences, and the surface is C2 across edges under the affine crossing maps.
/// Inside Gregory regions the surface is tangent-plane continuous across edges (normals
/// agree to ~1e-10) but not C1 under the crossing maps: x_u, x_v on the two sides of an
/// edge can differ by O(1) there, so Eq. 20 only holds approximately within 2^-L of an EV.
///
/// Thread safety: all const member functions may be called concurrently.
#include <memory>
#include <optional>
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/geometry/mesh.hpp"
#include "tightfit/geometry/surface_topology.hpp"
#include "tightfit/subdiv/surface_point.hpp"

namespace tightfit {

struct LimitSurfaceOptions {
  /// Bfr refinement depth L around smooth extraordinary vertices (1..10). The Gregory
  /// region is the corner sub-triangle of size 2^-L at each EV.
  int approx_level_smooth = 8;
  /// Bfr refinement depth for sharp features (≥ approx_level_smooth, ≤ 10). Our meshes
  /// have no creases, so it only has to be at least the smooth level.
  int approx_level_sharp = 8;
  /// Detect OpenSubdiv's second-derivative sign bug (docs/design.md §6 item 2) with a
  /// finite-difference self-test at construction and correct it when present. Turning
  /// it off returns OpenSubdiv's raw second derivatives (for inspection and tests only:
  /// they may have the wrong sign on rotated sub-triangles of irregular faces).
  bool self_test = true;
};

/// Limit stencil at one surface point, accumulated per unique control vertex:
/// x = Σ_k p[k] y[index[k]], x_u = Σ_k du[k] y[index[k]], ... (y: control positions).
/// All arrays have the same length; Σ p = 1 and every derivative stencil sums to 0.
struct LimitWeights {
  std::vector<int> index;  ///< unique control-vertex indices
  std::vector<double> p, du, dv, duu, duv, dvv;
  int size() const { return static_cast<int>(index.size()); }
};

/// Position (m) and parametric derivatives (m per unit u, v) at a surface point.
struct LimitFrame {
  Vec3 x, xu, xv, xuu, xuv, xvv;
};

/// Differential geometry at a surface point.
struct LimitCurvature {
  Vec3 normal;                   ///< unit normal, outward for an outward-oriented mesh
  Vec3 e1, e2;                   ///< orthonormal tangent basis: e1 = x_u/|x_u|, e2 = n × e1
  Mat2 first_fundamental_form;   ///< I in the (u,v) basis: [xu·xu, xu·xv; xv·xu, xv·xv]
  Mat2 second_fundamental_form;  ///< II in the (u,v) basis: [n·xuu, n·xuv; n·xuv, n·xvv]
  /// Shape operator S = -dn in the (e1, e2) basis (symmetric), i.e. II expressed in that
  /// orthonormal basis. Sign: a sphere of radius R with outward normal has S = -Id/R.
  Mat2 shape_operator;
};

class LimitProjector;

class LimitSurface {
 public:
  /// Builds every face's Bfr surface and stencil layout. Topology comes from
  /// `control.faces`; the number of control vertices is `control.vertices.rows()`
  /// (positions themselves are not used: the self-test compares stencil weights).
  /// Throws InputError if the mesh is not a closed, manifold, consistently oriented
  /// triangle mesh without degenerate faces, std::invalid_argument for bad options,
  /// SolverError if OpenSubdiv cannot build a face or the self-test finds derivatives
  /// that are wrong in an unexpected way.
  explicit LimitSurface(const TriMesh& control, LimitSurfaceOptions options = {});
  ~LimitSurface();
  LimitSurface(const LimitSurface&) = delete;
  LimitSurface& operator=(const LimitSurface&) = delete;
  LimitSurface(LimitSurface&&) noexcept;
  LimitSurface& operator=(LimitSurface&&) noexcept;

  int num_faces() const;
  int num_control_vertices() const { return num_control_vertices_; }
  const SurfaceTopology& topology() const { return *topology_; }
  const LimitSurfaceOptions& options() const { return options_; }
  /// Control vertices of `face` (one row of the control faces).
  const int* face_vertices(int face) const;
  /// True when the face has a corner of valence ≠ 6 (evaluated through a patch tree).
  bool is_irregular(int face) const;
  /// Whether the OpenSubdiv second-derivative sign bug was detected and is corrected.
  bool second_derivative_fix_active() const { return fix_second_derivatives_; }

  /// Stencil with first and second derivatives at `s`. `out` is resized (its capacity
  /// is reused, so a caller that keeps one LimitWeights allocates nothing). Throws
  /// std::invalid_argument if s is not inside its face (u,v ≥ -1e-12, u+v ≤ 1+1e-12).
  void weights(SurfacePoint s, LimitWeights& out) const;

  /// Position and derivatives at `s` for control positions `control` (num_control_vertices × 3, m).
  LimitFrame evaluate(SurfacePoint s, const Points3& control) const;
  /// Position only.
  Vec3 position(SurfacePoint s, const Points3& control) const;
  /// Unit normal (x_u × x_v normalized), outward for an outward-oriented control mesh.
  Vec3 normal(SurfacePoint s, const Points3& control) const;
  /// II in the (u,v) basis: [n·xuu, n·xuv; n·xuv, n·xvv] (1/m · m² = m).
  Mat2 second_fundamental_form(SurfacePoint s, const Points3& control) const;
  /// Normal, tangent basis, fundamental forms and shape operator at `s`.
  LimitCurvature curvature(SurfacePoint s, const Points3& control) const;

  /// Result of walking a straight line in the parameter domain.
  struct Walk {
    SurfacePoint end;
    /// d(uv_end)/d(uv_start) = d(uv_end)/d(delta): the product of the per-edge affine
    /// crossing maps (identity without crossings). It carries tangent vectors (Eq. 20):
    /// [x_u x_v](end) · J is the derivative of x(end) with respect to delta, and a
    /// search direction Δs in the start face becomes J·Δs in the end face. Exact
    /// outside the Gregory regions (see the file comment).
    Mat2 jacobian;
    int crossings = 0;
    /// False only if the line ran into a vertex and could not be continued (then `end`
    /// is that vertex and the rest of the displacement is dropped).
    bool complete = true;
  };
  /// Moves from `start` by `delta_uv` (in start's face coordinates) along a straight
  /// line, edge by edge with the affine crossing maps (Eq. 20); never evaluates or ends
  /// outside a face. Walking back by -jacobian·delta from the end returns to the start
  /// (to round-off), and splitting a walk along the same line changes nothing. Two
  /// different broken lines to the same displacement may end at different points when
  /// they enclose an extraordinary vertex (a cone point of the parameter domain).
  Walk walk(SurfacePoint start, const Vec2& delta_uv) const;

  /// Affine map of (u,v) across face edge `edge` of `face` into the neighbour face
  /// (returned in `neighbor`): uv_neighbor = offset + jacobian · uv.
  struct EdgeMap {
    int neighbor = -1;
    int edge_in_neighbor = -1;
    Mat2 jacobian;
    Vec2 offset;
  };
  EdgeMap edge_map(int face, int edge) const;

  /// Closest point on the limit surface to `p` (m) for control positions `control`.
  /// Without a hint, the start point is the nearest of a few limit samples per face
  /// (a kd-tree, cached for the last `control` seen and reused while its contents are
  /// equal); with a hint, Newton starts there. Newton/Gauss-Newton on |x(u,v) - p|²
  /// with a monotone line search, walking across faces (limit_projector.hpp). The
  /// result is a local minimum of the distance at least as close as the start point.
  /// For many queries with the same positions, a LimitProjector avoids comparing
  /// `control` with the cached copy on every call.
  SurfacePoint project(const Vec3& p, const Points3& control,
                       std::optional<SurfacePoint> hint = {}) const;

  /// True when (u,v) of an irregular face lies in a rotated (upside-down) sub-triangle
  /// of OpenSubdiv's patch tree: where the sign bug strikes. Exposed for tests.
  bool in_rotated_subpatch(int face, double u, double v) const;

 private:
  struct Impl;
  void raw_stencil(int face, double u, double v, double* p, double* du, double* dv, double* duu,
                   double* duv, double* dvv) const;
  void run_self_test();

  LimitSurfaceOptions options_;
  int num_control_vertices_ = 0;
  bool fix_second_derivatives_ = false;
  std::unique_ptr<SurfaceTopology> topology_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tightfit
