#include "server/util/malloc_tuning.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace soiq::server {

void keep_freed_blocks_for_reuse() {
#if defined(__GLIBC__)
  constexpr int kMiB = 1 << 20;
  mallopt(M_MMAP_THRESHOLD, 8 * kMiB);   // blocks up to this come from (and go back to) the heaps
  mallopt(M_TRIM_THRESHOLD, 16 * kMiB);  // free memory a heap keeps at its top before trimming
#endif
}

}  // namespace soiq::server
