#include "tightfit/common/parallel.hpp"

#include <dlfcn.h>
#include <omp.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <thread>

namespace tightfit {
namespace {

int g_threads = 0;  // 0: not chosen yet

template <typename Fn>
Fn openblas_symbol(const char* name) {
  return reinterpret_cast<Fn>(dlsym(RTLD_DEFAULT, name));
}

void apply(int n) {
  omp_set_num_threads(n);
  if (auto set = openblas_symbol<void (*)(int)>("openblas_set_num_threads")) set(n);
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
  if (auto config = openblas_symbol<char* (*)()>("openblas_get_config")) {
    info.name = "OpenBLAS";
    info.config = config();
    if (auto threads = openblas_symbol<int (*)()>("openblas_get_num_threads"))
      info.threads = threads();
  } else if (info.library.find("/blas/") != std::string::npos) {
    info.name = "reference BLAS (netlib)";
  } else {
    info.name = std::filesystem::path(info.library).filename().string();
  }
  return info;
}

}  // namespace tightfit
