#pragma once
/// Eigen aliases shared by every layer. Point arrays are row-major so that an n×3
/// array maps onto a flat vector (x0,y0,z0,x1,...) without copying.
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace tightfit {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;
using Mat32 = Eigen::Matrix<double, 3, 2>;
using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;

/// n×3 points (metres unless stated), one row per point.
using Points3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// n×2 points (metres unless stated), one row per point.
using Points2 = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;
/// m×3 vertex indices of triangles, one row per triangle, counter-clockwise seen from outside.
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// m×4 vertex indices of tetrahedra with positive orientation.
using Tetrahedra = Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor>;

using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplet = Eigen::Triplet<double>;

/// Pressure conversion: 1 mmHg = 133.322 Pa.
inline constexpr double kPascalPerMmHg = 133.322387415;

}  // namespace tightfit
