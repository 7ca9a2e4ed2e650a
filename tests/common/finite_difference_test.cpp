#include "support/finite_difference.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::test::finite_difference_test {

TEST(FiniteDifference, AcceptsExactDerivativesOfAQuartic) {
  const Eigen::VectorXd x = random_vector(4, 1);
  auto f = [](const Eigen::VectorXd& y) { return y.array().pow(4).sum() + y[0] * y[1]; };
  Eigen::VectorXd g = 4.0 * x.array().pow(3);
  g[0] += x[1];
  g[1] += x[0];
  EXPECT_LT(check_gradient(f, g, x, 1e-3).relative_error, 1e-9);
}

TEST(FiniteDifference, RejectsAWrongGradient) {
  const Eigen::VectorXd x = random_vector(3, 2);
  auto f = [](const Eigen::VectorXd& y) { return y.squaredNorm(); };
  const Eigen::VectorXd wrong = 2.1 * x;
  EXPECT_GT(check_gradient(f, wrong, x, 1e-4).relative_error, 1e-2);
}

TEST(FiniteDifference, ChecksHessianAsJacobianOfGradient) {
  const Eigen::VectorXd x = random_vector(3, 3);
  auto grad = [](const Eigen::VectorXd& y) -> Eigen::VectorXd { return y.array().sin(); };
  Eigen::MatrixXd H = x.array().cos().matrix().asDiagonal();
  EXPECT_LT(check_hessian(grad, H, x, 1e-3).relative_error, 1e-9);
}

TEST(AtomicFile, LeavesNoPartialFileOnFailure) {
  const auto dir = std::filesystem::temp_directory_path() / "tightfit_atomic_test";
  std::filesystem::create_directories(dir);
  const auto target = dir / "out.txt";
  std::filesystem::remove(target);
  EXPECT_THROW(write_file_atomically(target,
                                     [](std::ostream& out) {
                                       out << "half";
                                       throw InputError("x", "boom");
                                     }),
               InputError);
  EXPECT_FALSE(std::filesystem::exists(target));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 0);
  write_text_atomically(target, "whole");
  std::ifstream in(target);
  std::string s;
  in >> s;
  EXPECT_EQ(s, "whole");
  std::filesystem::remove_all(dir);
}

}  // namespace tightfit::test::finite_difference_test
