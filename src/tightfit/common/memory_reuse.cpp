#include "tightfit/common/memory_reuse.hpp"

#include <malloc.h>

namespace tightfit {

void keep_freed_memory_for_reuse() {
  mallopt(M_MMAP_THRESHOLD, 256 * 1024 * 1024);
  mallopt(M_TRIM_THRESHOLD, 1024 * 1024 * 1024);
}

}  // namespace tightfit
