// soiqd's allocator tuning takes effect: glibc accepts both settings, and a block of a few MiB then
// comes from the heap instead of a fresh mapping.
#include "server/util/malloc_tuning.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "tests/support/address_sanitizer.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace soiq::server {
namespace {

TEST(MallocTuning, GlibcTakesBothSettingsAndServesAFewMiBFromTheHeap) {
#if SOIQ_TEST_UNDER_ASAN
  GTEST_SKIP() << "AddressSanitizer replaces the allocator (and ignores mallopt)";
#elif !defined(__GLIBC__)
  GTEST_SKIP() << "not glibc";
#else
  ASSERT_TRUE(keep_freed_blocks_for_reuse());
  const size_t mapped_before = mallinfo2().hblkhd;
  void* block = std::malloc(4 << 20);  // above glibc's default threshold of 128 KiB
  ASSERT_NE(block, nullptr);
  EXPECT_EQ(mallinfo2().hblkhd, mapped_before);  // not a fresh mapping
  std::free(block);
#endif
}

}  // namespace
}  // namespace soiq::server
