#include "server/util/malloc_tuning.h"

#include <cstdlib>  // defines __GLIBC__ on glibc, which the test below needs

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace soiq::server {

bool keep_freed_blocks_for_reuse() {
#if defined(__GLIBC__)
  constexpr int kMiB = 1 << 20;
  // Blocks up to this come from (and go back to) the heaps.
  const bool mmap_set = mallopt(M_MMAP_THRESHOLD, 8 * kMiB) == 1;
  // Free memory a heap keeps at its top before it gives it back.
  const bool trim_set = mallopt(M_TRIM_THRESHOLD, 16 * kMiB) == 1;
  return mmap_set && trim_set;
#else
  return false;
#endif
}

}  // namespace soiq::server
