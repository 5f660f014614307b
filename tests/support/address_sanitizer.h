#pragma once
// Test support: SOIQ_TEST_UNDER_ASAN is 1 when this code is built with AddressSanitizer, else 0.
// GCC says so with __SANITIZE_ADDRESS__, clang (the sanitizer build, cmake/sanitize.cmake) only
// through __has_feature; tests that measure the heap (ASan replaces the allocator and keeps freed
// blocks in quarantine) ask here.

#if defined(__SANITIZE_ADDRESS__)
#define SOIQ_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SOIQ_TEST_UNDER_ASAN 1
#endif
#endif
#ifndef SOIQ_TEST_UNDER_ASAN
#define SOIQ_TEST_UNDER_ASAN 0
#endif
