#include "tightfit/body/loop_limit.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace tightfit {

double loop_limit_chi(int valence) {
  if (valence < 3) throw std::invalid_argument("loop_limit_chi: valence < 3");
  const double n = valence;
  const double c = 3.0 / 8.0 + 0.25 * std::cos(2.0 * std::numbers::pi / n);
  const double beta = (5.0 / 8.0 - c * c) / n;
  return 1.0 / (n + 3.0 / (8.0 * beta));
}

namespace {

/// Per vertex: valence and the sum of its one-ring positions, from directed face edges.
void one_ring_sums(const TriMesh& mesh, std::vector<int>& valence, Points3& sums) {
  const int n = mesh.num_vertices();
  valence.assign(n, 0);
  sums = Points3::Zero(n, 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int i = 0; i < 3; ++i) {
      const int a = mesh.faces(f, i), b = mesh.faces(f, (i + 1) % 3);
      ++valence[a];
      sums.row(a) += mesh.vertices.row(b);
    }
}

double mean_edge_length(const TriMesh& mesh) {
  double sum = 0.0;
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int i = 0; i < 3; ++i)
      sum += (mesh.vertices.row(mesh.faces(f, i)) - mesh.vertices.row(mesh.faces(f, (i + 1) % 3)))
                 .norm();
  return mesh.num_faces() > 0 ? sum / (3.0 * mesh.num_faces()) : 0.0;
}

}  // namespace

Points3 loop_limit_positions(const TriMesh& mesh) {
  std::vector<int> valence;
  Points3 sums;
  one_ring_sums(mesh, valence, sums);
  Points3 limit(mesh.num_vertices(), 3);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (valence[v] < 3)
      throw std::invalid_argument("loop_limit_positions: vertex " + std::to_string(v) +
                                  " has valence < 3 (mesh not closed?)");
    const double chi = loop_limit_chi(valence[v]);
    limit.row(v) = (1.0 - valence[v] * chi) * mesh.vertices.row(v) + chi * sums.row(v);
  }
  return limit;
}

LimitFitResult fit_loop_limit(TriMesh& mesh, const SurfaceProjector& project,
                              const LimitFitOptions& options) {
  LimitFitResult result;
  if (mesh.num_vertices() == 0) return result;
  const Points3 original = mesh.vertices;
  const double tolerance = options.relative_tolerance * mean_edge_length(mesh);
  for (int it = 0;; ++it) {
    const Points3 limit = loop_limit_positions(mesh);
    Points3 correction(limit.rows(), 3);
    double max_residual = 0.0;
    for (Eigen::Index v = 0; v < limit.rows(); ++v) {
      const Vec3 p = limit.row(v).transpose();
      correction.row(v) = (project(p) - p).transpose();
      max_residual = std::max(max_residual, correction.row(v).norm());
    }
    result.iterations = it;
    result.max_residual = max_residual;
    if (max_residual <= tolerance || it == options.max_iterations) break;
    mesh.vertices += correction;
  }
  result.max_displacement = (mesh.vertices - original).rowwise().norm().maxCoeff();
  return result;
}

}  // namespace tightfit
