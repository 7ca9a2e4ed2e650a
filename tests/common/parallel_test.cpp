#include "tightfit/common/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <thread>
#include <vector>

#include "tightfit/common/sparse_cholesky.hpp"

namespace tightfit::parallel_test {

/// Restores the thread count a test changed.
class ThreadCountGuard {
 public:
  ThreadCountGuard() : saved_(thread_count()) {}
  ~ThreadCountGuard() { set_thread_count(saved_); }

 private:
  int saved_;
};

std::vector<double> squares(std::int64_t n) {
  std::vector<double> out(static_cast<size_t>(n));
  parallel_for(n,
               [&](std::int64_t i) { out[static_cast<size_t>(i)] = 0.5 * double(i) * double(i); });
  return out;
}

TEST(ParallelFor, SameResultForEveryThreadCount) {
  ThreadCountGuard guard;
  set_thread_count(1);
  const std::vector<double> one = squares(10007);
  for (int threads : {2, 3, 5}) {
    set_thread_count(threads);
    EXPECT_EQ(squares(10007), one) << threads << " threads";
  }
}

TEST(ParallelFor, VisitsEveryItemOnce) {
  ThreadCountGuard guard;
  set_thread_count(4);
  std::vector<std::atomic<int>> visits(5000);
  parallel_for(5000, [&](std::int64_t i) { ++visits[static_cast<size_t>(i)]; });
  for (const auto& v : visits) EXPECT_EQ(v.load(), 1);
}

TEST(ParallelFor, RethrowsTheExceptionOfTheLowestItem) {
  ThreadCountGuard guard;
  set_thread_count(3);
  try {
    parallel_for(3000, [](std::int64_t i) {
      if (i == 2500 || i == 1200) throw std::runtime_error("item " + std::to_string(i));
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "item 1200");
  }
  // The pool is usable after an exception.
  EXPECT_EQ(squares(1000).back(), 0.5 * 999.0 * 999.0);
}

TEST(ParallelFor, NestedLoopsRunSerially) {
  ThreadCountGuard guard;
  set_thread_count(2);
  std::vector<double> sums(600, 0.0);
  parallel_for(600, [&](std::int64_t i) {
    std::vector<double> inner(300);
    parallel_for(300, [&](std::int64_t j) { inner[static_cast<size_t>(j)] = double(i + j); });
    for (double v : inner) sums[static_cast<size_t>(i)] += v;
  });
  EXPECT_DOUBLE_EQ(sums[10], 300.0 * 10 + 299.0 * 300.0 / 2.0);
}

TEST(RunOnThreads, JobsInQuickSuccessionAndAfterIdlePausesEachRunEveryBodyOnce) {
  // Workers poll for the next job a short while, then sleep: jobs microseconds apart and
  // jobs after a pause longer than the polling, with changing body counts, must each run
  // every body exactly once and show the caller everything the bodies wrote.
  std::vector<int> slot(3, -1);
  std::atomic<int> calls{0};
  for (int job = 0; job < 3000; ++job) {
    const int count = job % 3 == 0 ? 2 : 3;
    run_on_threads(count, [&](int t) {
      slot[static_cast<size_t>(t)] = job;
      calls.fetch_add(1, std::memory_order_relaxed);
    });
    ASSERT_EQ(slot[0], job);
    ASSERT_EQ(slot[1], job);
    if (count == 3) {
      ASSERT_EQ(slot[2], job);
    }
    if (job % 1000 == 999) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  EXPECT_EQ(calls.load(), 1000 * 2 + 2000 * 3);
}

TEST(ThreadCount, RejectsZeroAndReadsTheEnvironment) {
  ThreadCountGuard guard;
  EXPECT_THROW(set_thread_count(0), std::invalid_argument);
  setenv("TIGHTFIT_THREADS", "3", 1);
  EXPECT_EQ(default_thread_count(), 3);
  setenv("TIGHTFIT_THREADS", "two", 1);
  EXPECT_THROW(default_thread_count(), std::invalid_argument);
  unsetenv("TIGHTFIT_THREADS");
  EXPECT_GE(default_thread_count(), 1);
}

TEST(BlasInfo, NamesTheLoadedLibrary) {
  const BlasInfo info = blas_info();
  EXPECT_FALSE(info.library.empty()) << "dgemm_ should come from a loaded BLAS (CHOLMOD's)";
  EXPECT_FALSE(info.name.empty());
  EXPECT_GE(info.threads, 1);
}

TEST(BlasInfo, OpenBlasIdleThreadsSpinBriefly) {
  if (blas_info().name != "OpenBLAS" || std::getenv("OPENBLAS_THREAD_TIMEOUT"))
    GTEST_SKIP() << "not OpenBLAS, or its timeout set by the user";
  set_thread_count(thread_count());
  EXPECT_EQ(blas_info().thread_timeout, 20);
  EXPECT_EQ(std::getenv("OPENBLAS_THREAD_TIMEOUT"), nullptr);  // the environment as it was
  // The restarted pool still computes: a supernodal factorization (dense BLAS blocks)
  // of a 2D Laplacian.
  const int m = 120;
  std::vector<Triplet> t;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      t.emplace_back(i * m + j, i * m + j, 4.01);
      if (i + 1 < m) t.emplace_back(i * m + j, (i + 1) * m + j, -1.0);
      if (i + 1 < m) t.emplace_back((i + 1) * m + j, i * m + j, -1.0);
      if (j + 1 < m) t.emplace_back(i * m + j, i * m + j + 1, -1.0);
      if (j + 1 < m) t.emplace_back(i * m + j + 1, i * m + j, -1.0);
    }
  SparseMatrix A(m * m, m * m);
  A.setFromTriplets(t.begin(), t.end());
  SparseCholesky cholesky;
  ASSERT_TRUE(cholesky.factorize(A));
  const VecX b = VecX::LinSpaced(m * m, -1.0, 1.0);
  EXPECT_LT((A * cholesky.solve(b) - b).norm(), 1e-10 * b.norm());
}

}  // namespace tightfit::parallel_test
