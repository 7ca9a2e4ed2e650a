#include "tightfit/design/lbfgs.hpp"

#include <cmath>

namespace tightfit {

VecX lbfgs_direction(const LbfgsMemory& memory, const VecX& g) {
  const int m = static_cast<int>(memory.s.size());
  if (m == 0) return -g;
  VecX q = g;
  std::vector<double> alpha(m), rho(m);
  for (int i = m - 1; i >= 0; --i) {
    rho[i] = 1.0 / memory.y[i].dot(memory.s[i]);
    alpha[i] = rho[i] * memory.s[i].dot(q);
    q -= alpha[i] * memory.y[i];
  }
  const double gamma = memory.s[m - 1].dot(memory.y[m - 1]) / memory.y[m - 1].squaredNorm();
  q *= gamma;
  for (int i = 0; i < m; ++i) {
    const double beta = rho[i] * memory.y[i].dot(q);
    q += (alpha[i] - beta) * memory.s[i];
  }
  return -q;
}

bool lbfgs_push(LbfgsMemory& memory, const VecX& s, const VecX& y, int capacity) {
  if (!(s.dot(y) > 1e-12 * s.norm() * y.norm())) return false;
  memory.s.push_back(s);
  memory.y.push_back(y);
  lbfgs_trim(memory, capacity);
  return true;
}

void lbfgs_trim(LbfgsMemory& memory, int capacity) {
  while (static_cast<int>(memory.s.size()) > capacity) {
    memory.s.erase(memory.s.begin());
    memory.y.erase(memory.y.begin());
  }
}

double max_point_move(const VecX& d) {
  double m = 0.0;
  for (Eigen::Index i = 0; i + 1 < d.size(); i += 2) m = std::max(m, std::hypot(d[i], d[i + 1]));
  return m;
}

}  // namespace tightfit
