#include "tightfit/design/memory_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tightfit {
namespace {

/// Per point: the mean distance to the nearest other point of its piece (the spacing).
VecX spacing(const ParameterPoints& pts) {
  const Eigen::Index n = pts.positions.rows();
  VecX h = VecX::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < n; ++j)
      if (j != i && pts.piece[static_cast<size_t>(j)] == pts.piece[static_cast<size_t>(i)])
        nearest = std::min(nearest, (pts.positions.row(j) - pts.positions.row(i)).norm());
    h[i] = std::isfinite(nearest) ? nearest : 0.0;
  }
  return h;
}

/// One row of the transfer: old points and weights for a new point.
struct Stencil {
  Eigen::Index a = -1, b = -1;
  double wa = 1.0, wb = 0.0;
  double scale = 1.0;  // spacing ratio new / old, for y
};

std::vector<Stencil> stencils(const ParameterPoints& from, const ParameterPoints& to) {
  const VecX h_from = spacing(from), h_to = spacing(to);
  std::vector<Stencil> out(static_cast<size_t>(to.positions.rows()));
  for (Eigen::Index j = 0; j < to.positions.rows(); ++j) {
    double da = std::numeric_limits<double>::infinity(), db = da;
    Stencil& s = out[static_cast<size_t>(j)];
    for (Eigen::Index i = 0; i < from.positions.rows(); ++i) {
      if (from.piece[static_cast<size_t>(i)] != to.piece[static_cast<size_t>(j)]) continue;
      const double d = (from.positions.row(i) - to.positions.row(j)).norm();
      if (d < da) {
        db = da;
        s.b = s.a;
        da = d;
        s.a = i;
      } else if (d < db) {
        db = d;
        s.b = i;
      }
    }
    if (s.a < 0) throw std::invalid_argument("transfer_memory: a piece lost all its points");
    if (s.b >= 0 && da > 0.0) {
      s.wa = db / (da + db);
      s.wb = da / (da + db);
    }
    const double h_old = s.wa * h_from[s.a] + (s.b >= 0 ? s.wb * h_from[s.b] : 0.0);
    s.scale = h_old > 0.0 ? h_to[j] / h_old : 1.0;
  }
  return out;
}

VecX apply(const std::vector<Stencil>& st, const VecX& v, bool scaled) {
  VecX out(2 * static_cast<Eigen::Index>(st.size()));
  for (size_t j = 0; j < st.size(); ++j) {
    const Stencil& s = st[j];
    Eigen::Vector2d value = s.wa * v.segment<2>(2 * s.a);
    if (s.b >= 0) value += s.wb * v.segment<2>(2 * s.b);
    out.segment<2>(2 * static_cast<Eigen::Index>(j)) =
        scaled ? Eigen::Vector2d(s.scale * value) : value;
  }
  return out;
}

}  // namespace

std::vector<int> parameter_pieces(const BiharmonicCoordinates& coordinates) {
  const std::vector<int>& offset = coordinates.piece_offset();
  std::vector<int> out;
  for (int v : coordinates.parameter_vertices())
    out.push_back(
        static_cast<int>(std::upper_bound(offset.begin(), offset.end(), v) - offset.begin()) - 1);
  return out;
}

ParameterPoints parameter_points(const VecX& p, std::vector<int> piece_of_point) {
  ParameterPoints pts;
  pts.positions = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>>(
      p.data(), p.size() / 2, 2);
  pts.piece = std::move(piece_of_point);
  if (static_cast<Eigen::Index>(pts.piece.size()) != pts.positions.rows())
    throw std::invalid_argument("parameter_points: one piece per point expected");
  return pts;
}

LbfgsMemory transfer_memory(const LbfgsMemory& memory, const ParameterPoints& from,
                            const ParameterPoints& to) {
  const std::vector<Stencil> st = stencils(from, to);
  LbfgsMemory out;
  for (size_t k = 0; k < memory.s.size(); ++k) {
    VecX s = apply(st, memory.s[k], false), y = apply(st, memory.y[k], true);
    if (!(s.dot(y) > 1e-12 * s.norm() * y.norm())) continue;
    out.s.push_back(std::move(s));
    out.y.push_back(std::move(y));
  }
  return out;
}

}  // namespace tightfit
