#include "tightfit/solve/coupled_hessian.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "tightfit/common/parallel.hpp"

namespace tightfit {

/// A dense accumulator of one column block of H: a 3×3 block (column-major) per DOF
/// block start, with the list of the blocks this column touched.
struct CoupledHessian::Accumulator {
  Accumulator(Eigen::Index num_dofs, int num_garment_vertices)
      : values(9 * static_cast<std::size_t>(num_dofs)),
        stamp(num_dofs, -1),
        garment_values(9 * static_cast<std::size_t>(num_garment_vertices)),
        garment_stamp(num_garment_vertices, -1) {}
  std::vector<double> values;  // per DOF block start
  std::vector<int> stamp;
  std::vector<int> touched;
  // H_xx J of the column, per garment vertex, before it goes through Jᵀ.
  std::vector<double> garment_values;
  std::vector<int> garment_stamp;
  std::vector<int> garment_touched;
  int column = -1;

  /// The block at row DOF `dof` of the current column (zeroed on first use).
  Eigen::Map<Mat3> at(int dof) { return block(values, stamp, touched, dof); }
  /// The block of (H_xx J)_{i, column} for garment vertex i (zeroed on first use).
  Eigen::Map<Mat3> at_garment(int i) {
    return block(garment_values, garment_stamp, garment_touched, i);
  }

 private:
  Eigen::Map<Mat3> block(std::vector<double>& v, std::vector<int>& s, std::vector<int>& t, int k) {
    double* p = v.data() + 9 * static_cast<std::size_t>(k);
    if (s[k] != column) {
      s[k] = column;
      t.push_back(k);
      std::fill_n(p, 9, 0.0);
    }
    return Eigen::Map<Mat3>(p);
  }
};

CoupledHessian::CoupledHessian(CoupledHessianFactors factors) : f_(std::move(factors)) {
  const int ng = static_cast<int>(f_.garment_dof.size());
  const int nb = static_cast<int>(f_.body_dof.size());
  if (static_cast<int>(f_.stencil_start.size()) != ng + 1 ||
      static_cast<int>(f_.tangents.size()) != ng ||
      static_cast<int>(f_.curvature_terms.size()) != ng || f_.garment_forces.rows() != ng ||
      f_.garment.num_vertices() != ng || (f_.body.layout() && f_.body.num_vertices() != nb))
    throw std::invalid_argument("CoupledHessian: factor sizes disagree");
  const std::size_t entries = f_.stencil_vertex.size();
  if (static_cast<std::size_t>(f_.stencil_start.back()) != entries || f_.weight.size() != entries ||
      f_.weight_u.size() != entries || f_.weight_v.size() != entries)
    throw std::invalid_argument("CoupledHessian: stencil sizes disagree");
  for (int d : f_.garment_dof) garment_dof_end_ = std::max(garment_dof_end_, d + 2);
  garment_of_dof_.assign(static_cast<std::size_t>(garment_dof_end_), -1);
  for (int i = 0; i < ng; ++i)
    if (const int d = f_.garment_dof[i]; d >= 0) garment_of_dof_[d] = i;
  body_of_dof_.assign(static_cast<std::size_t>(f_.num_dofs), -1);
  for (int a = 0; a < nb; ++a)
    if (const int d = f_.body_dof[a]; d >= 0) {
      if (d < garment_dof_end_ || d + 3 > f_.num_dofs)
        throw std::invalid_argument("CoupledHessian: DOFs are not numbered garment first");
      body_of_dof_[d] = a;
    }
  entry_owner_.resize(entries);
  inverse_start_.assign(static_cast<std::size_t>(nb) + 1, 0);
  for (int i = 0; i < ng; ++i)
    for (int e = f_.stencil_start[i]; e < f_.stencil_start[i + 1]; ++e) {
      const int a = f_.stencil_vertex[e];
      if (a < 0 || a >= nb)
        throw std::invalid_argument("CoupledHessian: stencil vertex out of range");
      entry_owner_[e] = i;
      ++inverse_start_[a + 1];
    }
  for (int a = 0; a < nb; ++a) inverse_start_[a + 1] += inverse_start_[a];
  inverse_entries_.resize(entries);
  std::vector<int> next(inverse_start_.begin(), inverse_start_.end() - 1);
  for (std::size_t e = 0; e < entries; ++e)
    inverse_entries_[next[f_.stencil_vertex[e]]++] = static_cast<int>(e);
}

double CoupledHessian::column_work(int dof) const {
  const auto neighbours = [&](int i) {
    return f_.garment.column_end(i) - f_.garment.column_begin(i);
  };
  if (dof < garment_dof_end_) {
    const int k = garment_of_dof_[dof];
    return 1.0 + neighbours(k);
  }
  const int a = body_of_dof_[dof];
  double work = 1.0;
  for (int j = inverse_start_[a]; j < inverse_start_[a + 1]; ++j)
    work += neighbours(entry_owner_[inverse_entries_[j]]);
  if (f_.body.layout()) work += 0.1 * (f_.body.column_end(a) - f_.body.column_begin(a));
  return work;
}

void CoupledHessian::accumulate_column(int dof, Accumulator& spa) const {
  spa.column = dof;
  spa.touched.clear();
  spa.garment_touched.clear();
  // Jᵀ H_xx J: first H_xx J per garment vertex i, then through i's row of J.
  const auto add_hxx = [&](int k, const Mat3& C) {
    for (int kk = f_.garment.column_begin(k); kk < f_.garment.column_end(k); ++kk)
      spa.at_garment(f_.garment.row(kk)) += Eigen::Map<const Mat3>(f_.garment.block(kk)) * C;
  };
  if (dof < garment_dof_end_) {
    const int k = garment_of_dof_[dof];
    Mat3 C = Mat3::Zero();
    C.leftCols<2>() = f_.tangents[k];
    add_hxx(k, C);
  } else {
    const int a = body_of_dof_[dof];
    for (int j = inverse_start_[a]; j < inverse_start_[a + 1]; ++j) {
      const int e = inverse_entries_[j];
      add_hxx(entry_owner_[e], f_.weight[e] * Mat3::Identity());
    }
  }
  for (const int i : spa.garment_touched) {
    const Eigen::Map<const Mat3> W(spa.garment_values.data() + 9 * static_cast<std::size_t>(i));
    if (const int d = f_.garment_dof[i]; d >= 0)
      spa.at(d).topRows<2>() += f_.tangents[i].transpose() * W;
    for (int e = f_.stencil_start[i]; e < f_.stencil_start[i + 1]; ++e)
      if (const int b = f_.body_dof[f_.stencil_vertex[e]]; b >= 0) spa.at(b) += f_.weight[e] * W;
  }
  // E: the second-derivative terms and the body.
  if (dof < garment_dof_end_) {
    const int k = garment_of_dof_[dof];
    spa.at(dof).topLeftCorner<2, 2>() += f_.curvature_terms[k];
    const Vec3 g = f_.garment_forces.row(k).transpose();
    for (int e = f_.stencil_start[k]; e < f_.stencil_start[k + 1]; ++e)
      if (const int b = f_.body_dof[f_.stencil_vertex[e]]; b >= 0) {
        auto block = spa.at(b);
        block.col(0) += f_.weight_u[e] * g;
        block.col(1) += f_.weight_v[e] * g;
      }
    return;
  }
  const int a = body_of_dof_[dof];
  for (int j = inverse_start_[a]; j < inverse_start_[a + 1]; ++j) {
    const int e = inverse_entries_[j];
    const int k = entry_owner_[e];
    if (const int d = f_.garment_dof[k]; d >= 0) {
      const Vec3 g = f_.garment_forces.row(k).transpose();
      auto block = spa.at(d);
      block.row(0) += f_.weight_u[e] * g.transpose();
      block.row(1) += f_.weight_v[e] * g.transpose();
    }
  }
  if (f_.body.layout())
    for (int kk = f_.body.column_begin(a); kk < f_.body.column_end(a); ++kk)
      if (const int b = f_.body_dof[f_.body.row(kk)]; b >= 0)
        spa.at(b) += Eigen::Map<const Mat3>(f_.body.block(kk));
}

SparseMatrix CoupledHessian::matrix() const {
  const Eigen::Index n = f_.num_dofs;
  // The column blocks (first DOFs), split between the threads by their work.
  std::vector<int> columns;
  std::vector<double> work_before{0.0};
  for (int d = 0; d < n; d += block_size(d)) {
    columns.push_back(d);
    work_before.push_back(work_before.back() + column_work(d));
  }
  const int threads = std::max(1, std::min<int>(thread_count(), static_cast<int>(columns.size())));
  std::vector<std::size_t> first_column(threads + 1, columns.size());
  first_column[0] = 0;
  for (int t = 1; t < threads; ++t)
    first_column[t] =
        static_cast<std::size_t>(std::lower_bound(work_before.begin(), work_before.end() - 1,
                                                  work_before.back() * t / threads) -
                                 work_before.begin());

  std::vector<int> column_nonzeros(static_cast<std::size_t>(n) + 1, 0);
  std::vector<std::vector<int>> inner(threads);
  std::vector<std::vector<double>> values(threads);
  run_on_threads(threads, [&](int t) {
    Accumulator spa(n, static_cast<int>(f_.garment_dof.size()));
    for (std::size_t c = first_column[t]; c < first_column[t + 1]; ++c) {
      const int dof = columns[c];
      accumulate_column(dof, spa);
      std::sort(spa.touched.begin(), spa.touched.end());
      int count = 0;  // nonzeros of each scalar column of this block
      for (const int r : spa.touched) count += block_size(r);
      for (int col = 0; col < block_size(dof); ++col) {
        const std::size_t first = inner[t].size();
        inner[t].resize(first + static_cast<std::size_t>(count));
        values[t].resize(first + static_cast<std::size_t>(count));
        int* row_out = inner[t].data() + first;
        double* value_out = values[t].data() + first;
        for (const int r : spa.touched) {
          const double* block = spa.values.data() + 9 * static_cast<std::size_t>(r) + 3 * col;
          for (int row = 0; row < block_size(r); ++row) {
            *row_out++ = r + row;
            *value_out++ = block[row];
          }
        }
        column_nonzeros[dof + col + 1] = count;
      }
    }
  });
  SparseMatrix H(n, n);
  for (Eigen::Index j = 0; j < n; ++j) column_nonzeros[j + 1] += column_nonzeros[j];
  H.resizeNonZeros(column_nonzeros[n]);
  std::copy(column_nonzeros.begin(), column_nonzeros.end(), H.outerIndexPtr());
  run_on_threads(threads, [&](int t) {
    if (first_column[t] >= columns.size()) return;
    const int start = column_nonzeros[columns[first_column[t]]];
    std::copy(inner[t].begin(), inner[t].end(), H.innerIndexPtr() + start);
    std::copy(values[t].begin(), values[t].end(), H.valuePtr() + start);
  });
  return H;
}

VecX CoupledHessian::multiply(const VecX& v) const {
  const int ng = static_cast<int>(f_.garment_dof.size());
  const int nb = static_cast<int>(f_.body_dof.size());
  // x = J v, per garment vertex.
  Points3 x(ng, 3), y(ng, 3);
  parallel_for(ng, [&](std::int64_t i) {
    Vec3 xi = Vec3::Zero();
    if (const int d = f_.garment_dof[i]; d >= 0) xi += f_.tangents[i] * v.segment<2>(d);
    for (int e = f_.stencil_start[i]; e < f_.stencil_start[i + 1]; ++e)
      if (const int b = f_.body_dof[f_.stencil_vertex[e]]; b >= 0)
        xi += f_.weight[e] * v.segment<3>(b);
    x.row(i) = xi.transpose();
  });
  // y = H_xx x, each y_k from block column k (H_xx is symmetric: H_kr = H_rkᵀ).
  parallel_for(ng, [&](std::int64_t k) {
    Vec3 yk = Vec3::Zero();
    for (int kk = f_.garment.column_begin(static_cast<int>(k));
         kk < f_.garment.column_end(static_cast<int>(k)); ++kk)
      yk += Eigen::Map<const Mat3>(f_.garment.block(kk)).transpose() *
            x.row(f_.garment.row(kk)).transpose();
    y.row(k) = yk.transpose();
  });
  VecX out = VecX::Zero(f_.num_dofs);
  // The garment DOFs: Jᵀ y and the second-derivative terms.
  parallel_for(ng, [&](std::int64_t i) {
    const int d = f_.garment_dof[i];
    if (d < 0) return;
    const Vec3 g = f_.garment_forces.row(i).transpose();
    Vec2 o =
        f_.tangents[i].transpose() * y.row(i).transpose() + f_.curvature_terms[i] * v.segment<2>(d);
    for (int e = f_.stencil_start[i]; e < f_.stencil_start[i + 1]; ++e)
      if (const int b = f_.body_dof[f_.stencil_vertex[e]]; b >= 0)
        o += Vec2(f_.weight_u[e], f_.weight_v[e]) * g.dot(v.segment<3>(b));
    out.segment<2>(d) = o;
  });
  // The body DOFs, each gathered from the stencil entries that name its vertex and from
  // its block column of the (symmetric) body Hessian.
  parallel_for(nb, [&](std::int64_t a) {
    const int da = f_.body_dof[a];
    if (da < 0) return;
    Vec3 o = Vec3::Zero();
    for (int j = inverse_start_[a]; j < inverse_start_[a + 1]; ++j) {
      const int e = inverse_entries_[j];
      const int i = entry_owner_[e];
      o += f_.weight[e] * y.row(i).transpose();
      if (const int d = f_.garment_dof[i]; d >= 0)
        o += f_.garment_forces.row(i).transpose() *
             (f_.weight_u[e] * v[d] + f_.weight_v[e] * v[d + 1]);
    }
    if (f_.body.layout())
      for (int kk = f_.body.column_begin(static_cast<int>(a));
           kk < f_.body.column_end(static_cast<int>(a)); ++kk)
        if (const int b = f_.body_dof[f_.body.row(kk)]; b >= 0)
          o += Eigen::Map<const Mat3>(f_.body.block(kk)).transpose() * v.segment<3>(b);
    out.segment<3>(da) = o;
  });
  return out;
}

}  // namespace tightfit
