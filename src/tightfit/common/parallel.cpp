#include "tightfit/common/parallel.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace tightfit {
namespace {

int g_threads = 0;  // 0: not chosen yet

/// A symbol of a library the process has loaded (OpenBLAS, libgomp), or null.
template <typename Fn>
Fn loaded_symbol(const char* name) {
  return reinterpret_cast<Fn>(dlsym(RTLD_DEFAULT, name));
}

/// OpenBLAS's worker threads spin (sched_yield) for 2^28 cycles, about 0.1 s, after each
/// BLAS call before they sleep. On two cores the spinning thread takes turns on the
/// cores of tightfit's own loop threads between factorizations (measured on the pants
/// example: 4–7 % of the wall time, half the system time). Unless the user set
/// OPENBLAS_THREAD_TIMEOUT, OpenBLAS re-reads it as 20 (2^20 cycles, about 0.4 ms) and
/// restarts its thread pool once, through its exported openblas_read_env,
/// blas_thread_shutdown_ and blas_thread_init; the environment is left as it was.
void shorten_blas_spin() {
  static bool done = false;
  if (done) return;
  done = true;
  if (std::getenv("OPENBLAS_THREAD_TIMEOUT")) return;
  auto read_env = loaded_symbol<void (*)()>("openblas_read_env");
  auto shutdown = loaded_symbol<int (*)()>("blas_thread_shutdown_");
  auto init = loaded_symbol<int (*)()>("blas_thread_init");
  if (!read_env || !shutdown || !init) return;
  setenv("OPENBLAS_THREAD_TIMEOUT", "20", 0);
  read_env();
  unsetenv("OPENBLAS_THREAD_TIMEOUT");
  shutdown();
  init();
}

void apply(int n) {
  shorten_blas_spin();
  if (auto set = loaded_symbol<void (*)(int)>("openblas_set_num_threads")) set(n);
  // CHOLMOD's OpenMP teams (a fixed 4 threads) run serially: see the header.
  if (auto levels = loaded_symbol<void (*)(int)>("omp_set_max_active_levels")) levels(0);
}

/// Worker threads 1 … count−1 of run_on_threads. Between jobs a worker polls for the
/// next one for kSpinSeconds, then sleeps on a condition variable; the caller likewise
/// polls for the workers' end before it sleeps. On a virtual machine a futex wake-up
/// costs 2–40 µs, as much as a whole parallel Hessian–vector product; the Krylov loops
/// start a parallel step every 50–300 µs, which a polling worker catches at once.
class ThreadPool {
 public:
  ~ThreadPool() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& w : workers_) w.join();
  }

  void run(int count, const std::function<void(int)>& body) {
    std::vector<std::exception_ptr> errors(static_cast<size_t>(count));
    {
      std::unique_lock lock(mutex_);
      while (static_cast<int>(workers_.size()) < count - 1) {
        const int index = static_cast<int>(workers_.size()) + 1;
        workers_.emplace_back([this, index] { work(index); });
      }
      body_ = &body;
      errors_ = &errors;
      count_.store(count, std::memory_order_relaxed);
      pending_.store(count - 1, std::memory_order_relaxed);
      job_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    run_one(0);
    if (!poll([this] { return pending_.load(std::memory_order_acquire) == 0; })) {
      std::unique_lock lock(mutex_);
      done_.wait(lock, [this] { return pending_.load(std::memory_order_acquire) == 0; });
    }
    body_ = nullptr;
    for (const std::exception_ptr& e : errors)
      if (e) std::rethrow_exception(e);
  }

  static thread_local bool inside;

 private:
  static constexpr double kSpinSeconds = 200e-6;

  /// Polls `ready` for up to kSpinSeconds; whether it became true.
  template <typename Ready>
  static bool poll(Ready ready) {
    const auto start = std::chrono::steady_clock::now();
    for (int k = 1;; ++k) {
      if (ready()) return true;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
      if (k % 64 == 0 &&
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
              kSpinSeconds)
        return ready();
    }
  }

  void run_one(int index) {
    inside = true;
    try {
      (*body_)(index);
    } catch (...) {
      (*errors_)[static_cast<size_t>(index)] = std::current_exception();
    }
    inside = false;
  }

  void work(int index) {
    long seen = 0;
    const auto has_job = [&] {
      return job_.load(std::memory_order_acquire) != seen &&
             index < count_.load(std::memory_order_relaxed);
    };
    for (;;) {
      if (!poll(has_job)) {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stop_ || has_job(); });
        if (stop_) return;
      }
      seen = job_.load(std::memory_order_acquire);
      run_one(index);
      if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        std::lock_guard lock(mutex_);  // the caller may be between its test and its wait
        done_.notify_one();
      }
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::vector<std::thread> workers_;
  const std::function<void(int)>* body_ = nullptr;
  std::vector<std::exception_ptr>* errors_ = nullptr;
  std::atomic<int> count_{0};
  std::atomic<int> pending_{0};
  std::atomic<long> job_{0};
  bool stop_ = false;
};

thread_local bool ThreadPool::inside = false;

ThreadPool& pool() {
  static ThreadPool instance;
  return instance;
}

std::mutex& pool_user() {  // one run_on_threads at a time from different outside threads
  static std::mutex m;
  return m;
}

}  // namespace

int default_thread_count() {
  if (const char* v = std::getenv("TIGHTFIT_THREADS"); v && *v) {
    char* end = nullptr;
    const long n = std::strtol(v, &end, 10);
    if (*end != '\0' || n < 1 || n > 1024)
      throw std::invalid_argument("TIGHTFIT_THREADS: '" + std::string(v) +
                                  "' is not a thread count (a whole number from 1 to 1024)");
    return static_cast<int>(n);
  }
  const unsigned cores = std::thread::hardware_concurrency();
  return cores > 0 ? static_cast<int>(cores) : 1;
}

void set_thread_count(int n) {
  if (n < 1) throw std::invalid_argument("thread count must be at least 1");
  g_threads = n;
  apply(n);
}

int thread_count() {
  if (g_threads == 0) set_thread_count(default_thread_count());
  return g_threads;
}

void run_on_threads(int count, const std::function<void(int)>& body) {
  if (count <= 1 || ThreadPool::inside) {
    std::exception_ptr first;
    for (int t = 0; t < count; ++t) {
      try {
        body(t);
      } catch (...) {
        if (!first) first = std::current_exception();
      }
    }
    if (first) std::rethrow_exception(first);
    return;
  }
  std::lock_guard lock(pool_user());
  pool().run(count, body);
}

BlasInfo blas_info() {
  BlasInfo info;
  // dgemm_ is the Fortran BLAS entry every implementation exports; CHOLMOD calls it.
  if (void* sym = dlsym(RTLD_DEFAULT, "dgemm_")) {
    Dl_info dl{};
    if (dladdr(sym, &dl) && dl.dli_fname) {
      std::error_code ec;
      const auto resolved = std::filesystem::canonical(dl.dli_fname, ec);
      info.library = ec ? std::string(dl.dli_fname) : resolved.string();
    }
  }
  if (auto config = loaded_symbol<char* (*)()>("openblas_get_config")) {
    info.name = "OpenBLAS";
    info.config = config();
    if (auto threads = loaded_symbol<int (*)()>("openblas_get_num_threads"))
      info.threads = threads();
    if (auto timeout = loaded_symbol<int (*)()>("openblas_thread_timeout"))
      info.thread_timeout = timeout();
  } else if (info.library.find("/blas/") != std::string::npos) {
    info.name = "reference BLAS (netlib)";
  } else {
    info.name = std::filesystem::path(info.library).filename().string();
  }
  return info;
}

}  // namespace tightfit
