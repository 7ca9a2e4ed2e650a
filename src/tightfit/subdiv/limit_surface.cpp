#include "tightfit/subdiv/limit_surface.hpp"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

#include "tightfit/common/error.hpp"
#include "tightfit/subdiv/limit_projector.hpp"
#include "tightfit/subdiv/limit_surface_impl.hpp"
#include "tightfit/subdiv/patch_tree_rotation.hpp"

namespace tightfit {

namespace Bfr = OpenSubdiv::Bfr;
namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

namespace {

/// Per-thread scratch for raw stencils: 6 arrays of `n` doubles.
double* scratch(int n) {
  thread_local std::vector<double> buffer;
  const std::size_t need = static_cast<std::size_t>(6 * n);
  if (buffer.size() < need) buffer.resize(need);
  return buffer.data();
}

void check_options(const LimitSurfaceOptions& o) {
  if (o.approx_level_smooth < 1 || o.approx_level_smooth > 10) {
    throw std::invalid_argument("LimitSurfaceOptions: approx_level_smooth must be in 1..10, got " +
                                std::to_string(o.approx_level_smooth));
  }
  if (o.approx_level_sharp < o.approx_level_smooth || o.approx_level_sharp > 10) {
    throw std::invalid_argument(
        "LimitSurfaceOptions: approx_level_sharp must be in approx_level_smooth..10, got " +
        std::to_string(o.approx_level_sharp));
  }
}

void validate_control_mesh(const TriMesh& control, const SurfaceTopology& topo) {
  const std::string source = "limit surface control mesh";
  if (control.num_faces() == 0) throw InputError(source, "has no faces");
  for (int f = 0; f < control.num_faces(); ++f) {
    const auto row = control.faces.row(f);
    if (row[0] == row[1] || row[1] == row[2] || row[2] == row[0]) {
      throw InputError(source, "face " + std::to_string(f) + " is degenerate (repeated vertex)");
    }
  }
  if (const auto e = topo.non_manifold_edges(); !e.empty()) {
    throw InputError(source, std::to_string(e.size()) + " non-manifold edges (first: edge " +
                                 std::to_string(e.front()) + ")");
  }
  if (!topo.is_closed()) {
    throw InputError(source, "is not closed (" + std::to_string(topo.boundary_edges().size()) +
                                 " boundary edges)");
  }
  if (const auto v = topo.non_manifold_vertices(); !v.empty()) {
    throw InputError(source, std::to_string(v.size()) + " non-manifold vertices (first: " +
                                 std::to_string(v.front()) + ")");
  }
  if (const auto e = topo.inconsistently_oriented_edges(); !e.empty()) {
    throw InputError(source, std::to_string(e.size()) +
                                 " edges whose faces disagree on orientation (first: edge " +
                                 std::to_string(e.front()) + ")");
  }
}

/// Affine map of (u,v) across face edge i into the neighbour, whose shared edge is j.
/// With barycentrics b = (1-u-v, u, v), the map that turns the two parameter triangles
/// into a parallelogram is: b'[j] = b[i+1] + b[i+2], b'[j+1] = b[i] + b[i+2],
/// b'[j+2] = -b[i+2] (the shared edge is traversed in opposite directions).
void crossing_map(int i, int j, Mat2& jacobian, Vec2& offset) {
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  P(j, (i + 1) % 3) = 1.0;
  P(j, (i + 2) % 3) = 1.0;
  P((j + 1) % 3, i) = 1.0;
  P((j + 1) % 3, (i + 2) % 3) = 1.0;
  P((j + 2) % 3, (i + 2) % 3) = -1.0;
  // b = c + B (u,v) with c = (1,0,0), B = [-1 -1; 1 0; 0 1].
  Eigen::Matrix<double, 3, 2> B;
  B << -1, -1, 1, 0, 0, 1;
  const Eigen::Vector3d c(1, 0, 0);
  offset = (P * c).tail<2>();
  jacobian = (P * B).bottomRows<2>();
}

}  // namespace

LimitSurface::LimitSurface(const TriMesh& control, LimitSurfaceOptions options)
    : options_(options), num_control_vertices_(control.num_vertices()) {
  check_options(options_);
  topology_ = std::make_unique<SurfaceTopology>(control.faces, control.num_vertices());
  validate_control_mesh(control, *topology_);
  impl_ = std::make_unique<Impl>();
  Impl& m = *impl_;
  m.faces = control.faces;
  const int nf = control.num_faces();

  // Topology for OpenSubdiv: a Loop refiner over all faces.
  std::vector<int> verts_per_face(static_cast<std::size_t>(nf), 3);
  Far::TopologyDescriptor desc;
  desc.numVertices = control.num_vertices();
  desc.numFaces = nf;
  desc.numVertsPerFace = verts_per_face.data();
  desc.vertIndicesPerFace = m.faces.data();
  using RefinerFactory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  const Sdc::Options sdc_options;
  std::unique_ptr<Far::TopologyRefiner> refiner(
      RefinerFactory::Create(desc, RefinerFactory::Options(Sdc::SCHEME_LOOP, sdc_options)));
  if (!refiner)
    throw SolverError("OpenSubdiv could not build the Loop topology of the control mesh");

  Bfr::SurfaceFactory::Options factory_options;
  factory_options.SetApproxLevelSmooth(options_.approx_level_smooth);
  factory_options.SetApproxLevelSharp(options_.approx_level_sharp);
  Bfr::RefinerSurfaceFactory<> factory(*refiner, factory_options);
  // Depth of the patch tree around a smooth EV (PatchTreeBuilder: the secondary level).
  m.patch_tree_depth = std::min(options_.approx_level_smooth, options_.approx_level_sharp);

  for (int v = 0; v < control.num_vertices(); ++v) {
    m.max_valence = std::max(m.max_valence, static_cast<int>(topology_->vertex_faces(v).size()));
  }

  m.surfaces.resize(static_cast<std::size_t>(nf));
  m.cp_offset.assign(1, 0);
  m.unique_offset.assign(1, 0);
  m.ev_corners.resize(static_cast<std::size_t>(nf));
  m.has_duplicates.resize(static_cast<std::size_t>(nf));
  m.irregular.resize(static_cast<std::size_t>(nf));
  std::vector<int> local;
  for (int f = 0; f < nf; ++f) {
    Bfr::Surface<double>& surface = m.surfaces[static_cast<std::size_t>(f)];
    if (!factory.InitVertexSurface(f, &surface) || !surface.IsValid()) {
      throw SolverError("OpenSubdiv could not build the limit surface of face " +
                        std::to_string(f));
    }
    const int n = surface.GetNumControlPoints();
    m.max_control_points = std::max(m.max_control_points, n);
    local.resize(static_cast<std::size_t>(n));
    surface.GetControlPointIndices(local.data());
    bool duplicates = false;
    const int unique_begin = static_cast<int>(m.unique_index.size());
    for (int k = 0; k < n; ++k) {
      const int index = local[static_cast<std::size_t>(k)];
      int slot = -1;
      for (int q = unique_begin; q < static_cast<int>(m.unique_index.size()); ++q) {
        if (m.unique_index[static_cast<std::size_t>(q)] == index) {
          slot = q - unique_begin;
          break;
        }
      }
      if (slot < 0) {
        slot = static_cast<int>(m.unique_index.size()) - unique_begin;
        m.unique_index.push_back(index);
        m.cp_first.push_back(1);
      } else {
        duplicates = true;
        m.cp_first.push_back(0);
      }
      m.cp_index.push_back(index);
      m.cp_slot.push_back(slot);
    }
    m.cp_offset.push_back(static_cast<int>(m.cp_index.size()));
    m.unique_offset.push_back(static_cast<int>(m.unique_index.size()));
    m.has_duplicates[static_cast<std::size_t>(f)] = duplicates;

    std::uint8_t ev = 0;
    for (int k = 0; k < 3; ++k) {
      if (topology_->vertex_faces(m.faces(f, k)).size() != 6)
        ev |= static_cast<std::uint8_t>(1u << k);
    }
    m.ev_corners[static_cast<std::size_t>(f)] = ev;
    m.irregular[static_cast<std::size_t>(f)] = !surface.IsRegular();
    if ((ev != 0) != !surface.IsRegular()) {
      throw SolverError("OpenSubdiv classifies face " + std::to_string(f) +
                        (surface.IsRegular()
                             ? " as regular although it has a corner of valence ≠ 6"
                             : " as irregular although all its corners have valence 6"));
    }
  }

  m.edge_maps.resize(static_cast<std::size_t>(3 * nf));
  for (int f = 0; f < nf; ++f) {
    for (int i = 0; i < 3; ++i) {
      const SurfaceTopology::Across a = topology_->across(f, i);
      EdgeMap& e = m.edge_maps[static_cast<std::size_t>(3 * f + i)];
      e.neighbor = a.face;
      e.edge_in_neighbor = a.edge_in_face;
      crossing_map(i, a.edge_in_face, e.jacobian, e.offset);
    }
  }

  if (options_.self_test) run_self_test();
}

LimitSurface::~LimitSurface() = default;
LimitSurface::LimitSurface(LimitSurface&&) noexcept = default;
LimitSurface& LimitSurface::operator=(LimitSurface&&) noexcept = default;

int LimitSurface::num_faces() const { return static_cast<int>(impl_->surfaces.size()); }

const int* LimitSurface::face_vertices(int face) const { return impl_->faces.row(face).data(); }

bool LimitSurface::is_irregular(int face) const {
  return impl_->irregular[static_cast<std::size_t>(face)] != 0;
}

bool LimitSurface::in_rotated_subpatch(int face, double u, double v) const {
  const Impl& m = *impl_;
  if (!m.irregular[static_cast<std::size_t>(face)]) return false;
  return patch_tree_rotated(u, v, m.ev_corners[static_cast<std::size_t>(face)], m.patch_tree_depth);
}

void LimitSurface::raw_stencil(int face, double u, double v, double* p, double* du, double* dv,
                               double* duu, double* duv, double* dvv) const {
  const Impl& m = *impl_;
  const double uv[2] = {u, v};
  const Bfr::Surface<double>& surface = m.surfaces[static_cast<std::size_t>(face)];
  const int n = surface.EvaluateStencil(uv, p, du, dv, duu, duv, dvv);
  if (fix_second_derivatives_ && in_rotated_subpatch(face, u, v)) {
    for (int k = 0; k < n; ++k) {
      duu[k] = -duu[k];
      duv[k] = -duv[k];
      dvv[k] = -dvv[k];
    }
  }
}

namespace {

/// Checks that s lies in its face (is_surface_point) and returns clamped (u,v).
Vec2 checked_uv(SurfacePoint s, int num_faces) {
  if (s.face < 0 || s.face >= num_faces) {
    throw std::invalid_argument("SurfacePoint: face " + std::to_string(s.face) +
                                " out of range [0, " + std::to_string(num_faces) + ")");
  }
  if (!is_surface_point(s, num_faces)) {
    throw std::invalid_argument("SurfacePoint: (u, v) = (" + std::to_string(s.u) + ", " +
                                std::to_string(s.v) + ") is outside face " +
                                std::to_string(s.face));
  }
  double u = std::max(s.u, 0.0);
  double v = std::max(s.v, 0.0);
  const double excess = u + v - 1.0;
  if (excess > 0.0) {
    u -= 0.5 * excess;
    v -= 0.5 * excess;
  }
  return {std::max(u, 0.0), std::max(v, 0.0)};
}

}  // namespace

void LimitSurface::weights(SurfacePoint s, LimitWeights& out) const {
  const Impl& m = *impl_;
  const Vec2 uv = checked_uv(s, num_faces());
  const std::size_t f = static_cast<std::size_t>(s.face);
  const int begin = m.cp_offset[f];
  const int n = m.cp_offset[f + 1] - begin;
  out.p.resize(static_cast<std::size_t>(n));
  out.du.resize(static_cast<std::size_t>(n));
  out.dv.resize(static_cast<std::size_t>(n));
  out.duu.resize(static_cast<std::size_t>(n));
  out.duv.resize(static_cast<std::size_t>(n));
  out.dvv.resize(static_cast<std::size_t>(n));
  raw_stencil(s.face, uv[0], uv[1], out.p.data(), out.du.data(), out.dv.data(), out.duu.data(),
              out.duv.data(), out.dvv.data());
  const int ubegin = m.unique_offset[f];
  const int nu = m.unique_offset[f + 1] - ubegin;
  out.index.assign(m.unique_index.begin() + ubegin, m.unique_index.begin() + ubegin + nu);
  if (!m.has_duplicates[f]) return;
  // In-place accumulation: slots are numbered by first occurrence, so slot(k) ≤ k.
  std::vector<double>* arrays[6] = {&out.p, &out.du, &out.dv, &out.duu, &out.duv, &out.dvv};
  for (int k = 0; k < n; ++k) {
    const int slot = m.cp_slot[static_cast<std::size_t>(begin + k)];
    if (slot == k) continue;
    const bool first = m.cp_first[static_cast<std::size_t>(begin + k)] != 0;
    for (std::vector<double>* a : arrays) {
      double* w = a->data();
      w[slot] = first ? w[k] : w[slot] + w[k];
    }
  }
  for (std::vector<double>* a : arrays) a->resize(static_cast<std::size_t>(nu));
}

LimitFrame LimitSurface::evaluate(SurfacePoint s, const Points3& control) const {
  const Impl& m = *impl_;
  const Vec2 uv = checked_uv(s, num_faces());
  const std::size_t f = static_cast<std::size_t>(s.face);
  const int begin = m.cp_offset[f];
  const int n = m.cp_offset[f + 1] - begin;
  double* w = scratch(m.max_control_points);
  raw_stencil(s.face, uv[0], uv[1], w, w + n, w + 2 * n, w + 3 * n, w + 4 * n, w + 5 * n);
  Eigen::Matrix<double, 3, 6> acc = Eigen::Matrix<double, 3, 6>::Zero();
  const int* index = m.cp_index.data() + begin;
  for (int k = 0; k < n; ++k) {
    const Vec3 y = control.row(index[k]).transpose();
    for (int d = 0; d < 6; ++d) acc.col(d) += w[d * n + k] * y;
  }
  return {acc.col(0), acc.col(1), acc.col(2), acc.col(3), acc.col(4), acc.col(5)};
}

Vec3 LimitSurface::position(SurfacePoint s, const Points3& control) const {
  const Impl& m = *impl_;
  const Vec2 uv = checked_uv(s, num_faces());
  const std::size_t f = static_cast<std::size_t>(s.face);
  const int begin = m.cp_offset[f];
  const int n = m.cp_offset[f + 1] - begin;
  double* w = scratch(m.max_control_points);
  const double uvp[2] = {uv[0], uv[1]};
  m.surfaces[f].EvaluateStencil(uvp, w);
  Vec3 x = Vec3::Zero();
  const int* index = m.cp_index.data() + begin;
  for (int k = 0; k < n; ++k) x += w[k] * control.row(index[k]).transpose();
  return x;
}

Vec3 LimitSurface::normal(SurfacePoint s, const Points3& control) const {
  const LimitFrame fr = evaluate(s, control);
  return fr.xu.cross(fr.xv).normalized();
}

Mat2 LimitSurface::second_fundamental_form(SurfacePoint s, const Points3& control) const {
  return curvature(s, control).second_fundamental_form;
}

LimitCurvature LimitSurface::curvature(SurfacePoint s, const Points3& control) const {
  const LimitFrame fr = evaluate(s, control);
  LimitCurvature c;
  c.normal = fr.xu.cross(fr.xv).normalized();
  c.e1 = fr.xu.normalized();
  c.e2 = c.normal.cross(c.e1);
  c.first_fundamental_form << fr.xu.dot(fr.xu), fr.xu.dot(fr.xv), fr.xv.dot(fr.xu),
      fr.xv.dot(fr.xv);
  const double b_uv = c.normal.dot(fr.xuv);
  c.second_fundamental_form << c.normal.dot(fr.xuu), b_uv, b_uv, c.normal.dot(fr.xvv);
  // Tangent basis T = [xu xv] = E A with E = [e1 e2], A = Eᵀ T; II_E = A⁻ᵀ II A⁻¹.
  Mat2 A;
  A << c.e1.dot(fr.xu), c.e1.dot(fr.xv), c.e2.dot(fr.xu), c.e2.dot(fr.xv);
  const Mat2 Ainv = A.inverse();
  c.shape_operator = Ainv.transpose() * c.second_fundamental_form * Ainv;
  c.shape_operator = 0.5 * (c.shape_operator + c.shape_operator.transpose()).eval();
  return c;
}

LimitSurface::EdgeMap LimitSurface::edge_map(int face, int edge) const {
  return impl_->edge_maps[static_cast<std::size_t>(3 * face + edge)];
}

LimitSurface::Walk LimitSurface::walk(SurfacePoint start, const Vec2& delta_uv) const {
  const Impl& m = *impl_;
  const Vec2 uv0 = checked_uv(start, num_faces());
  Walk result;
  result.jacobian.setIdentity();
  int face = start.face;
  // Barycentrics of the current point, kept exactly on an edge after a crossing.
  double b[3] = {1.0 - uv0[0] - uv0[1], uv0[0], uv0[1]};
  Vec2 d = delta_uv;
  int stuck = 0;  // consecutive crossings without progress (line through a vertex)
  const int max_stuck = 2 * m.max_valence + 4;
  const int max_crossings = 1000000;
  for (;;) {
    const double db[3] = {-d[0] - d[1], d[0], d[1]};
    double t_exit = 1.0;
    int k_exit = -1;
    for (int k = 0; k < 3; ++k) {
      if (db[k] < 0.0) {
        const double t = std::max(b[k], 0.0) / -db[k];
        if (t < t_exit) {
          t_exit = t;
          k_exit = k;
        }
      }
    }
    if (k_exit < 0) {
      double e[3];
      double sum = 0.0;
      for (int k = 0; k < 3; ++k) {
        e[k] = std::max(b[k] + db[k], 0.0);
        sum += e[k];
      }
      result.end = {face, e[1] / sum, e[2] / sum};
      return result;
    }
    // Exit point on the edge opposite corner k_exit (face edge (k_exit+1)%3).
    double e[3];
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      e[k] = (k == k_exit) ? 0.0 : std::max(b[k] + t_exit * db[k], 0.0);
      sum += e[k];
    }
    for (double& x : e) x /= sum;
    const double progress = t_exit * (std::abs(d[0]) + std::abs(d[1]));
    stuck = (progress <= 1e-15) ? stuck + 1 : 0;
    if (stuck > max_stuck || result.crossings >= max_crossings) {
      result.end = {face, e[1], e[2]};
      result.complete = false;
      return result;
    }
    const int i = (k_exit + 1) % 3;
    const EdgeMap& em = m.edge_maps[static_cast<std::size_t>(3 * face + i)];
    const int j = em.edge_in_neighbor;
    // On the shared edge: b'[j] = b[i+1], b'[j+1] = b[i], b'[j+2] = 0.
    double nb[3];
    nb[j] = e[(i + 1) % 3];
    nb[(j + 1) % 3] = e[i];
    nb[(j + 2) % 3] = 0.0;
    b[0] = nb[0];
    b[1] = nb[1];
    b[2] = nb[2];
    d = em.jacobian * ((1.0 - t_exit) * d);
    result.jacobian = em.jacobian * result.jacobian;
    face = em.neighbor;
    ++result.crossings;
  }
}

SurfacePoint LimitSurface::project(const Vec3& p, const Points3& control,
                                   std::optional<SurfacePoint> hint) const {
  if (control.rows() != num_control_vertices_) {
    throw std::invalid_argument("LimitSurface::project: control has " +
                                std::to_string(control.rows()) + " rows, expected " +
                                std::to_string(num_control_vertices_));
  }
  if (hint) return refine_closest_point(*this, control, p, *hint);
  std::shared_ptr<const LimitProjector> projector;
  {
    std::lock_guard<std::mutex> lock(impl_->projector_mutex);
    const Points3* cached = impl_->projector ? &impl_->projector->control() : nullptr;
    const bool same = cached && cached->rows() == control.rows() &&
                      std::memcmp(cached->data(), control.data(),
                                  sizeof(double) * static_cast<std::size_t>(control.size())) == 0;
    if (!same) impl_->projector = std::make_shared<const LimitProjector>(*this, control);
    projector = impl_->projector;
  }
  return projector->project(p);
}
}  // namespace tightfit
