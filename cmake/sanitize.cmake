# The sanitizer build's initial cache (cmake -C cmake/sanitize.cmake -S . -B build-sanitize;
# `make test-sanitize` and `make fuzz` both use it): Debian's clang-14, every target built with
# AddressSanitizer + UndefinedBehaviorSanitizer and instrumented for libFuzzer's coverage, so one
# tree runs every test under the sanitizers and holds the harnesses of fuzz/ too.
#
# Why clang at -O1 with line tables, not GCC at -O2 -g: one build instead of two (libFuzzer is
# clang's), and it compiles ~3x faster. Measured on the 2-core CI machine, per translation unit:
# server/http/http_connection.cpp (Boost.Beast) 293 s with GCC -O2 -g, 117 s with GCC -O1 -g1, 74 s
# here; a whole GCC -O2 -g tree took longer than CI allows.
set(CMAKE_C_COMPILER clang-14 CACHE STRING "")
set(CMAKE_CXX_COMPILER clang++-14 CACHE STRING "")
set(SOIQ_SANITIZE ON CACHE BOOL "")
set(SOIQ_FUZZ ON CACHE BOOL "")
# clang warns about things GCC does not (and the reverse); the GCC build (`make test`) is the one
# that gates warnings, this one gates memory errors, undefined behaviour and crashes.
set(SOIQ_WERROR OFF CACHE BOOL "")
# No test runs the benchmarks; the release tree builds them.
set(SOIQ_BENCH OFF CACHE BOOL "")
# LLVM's linker: the sanitized test binaries are large, and GNU ld links them several times slower.
set(CMAKE_EXE_LINKER_FLAGS "-fuse-ld=lld" CACHE STRING "")
set(CMAKE_SHARED_LINKER_FLAGS "-fuse-ld=lld" CACHE STRING "")
set(CMAKE_BUILD_TYPE RelWithDebInfo CACHE STRING "")
# No -DNDEBUG: an assert is an invariant no input can break, exactly what a fuzzer and a sanitized
# test should check. Line tables are enough for symbolized stacks and keep the objects small.
set(CMAKE_C_FLAGS_RELWITHDEBINFO "-O1 -gline-tables-only" CACHE STRING "")
set(CMAKE_CXX_FLAGS_RELWITHDEBINFO "-O1 -gline-tables-only" CACHE STRING "")
# Coverage for libFuzzer in every library the harnesses link; SOIQ_SANITIZE adds the sanitizers.
set(CMAKE_C_FLAGS "-fsanitize=fuzzer-no-link" CACHE STRING "")
set(CMAKE_CXX_FLAGS "-fsanitize=fuzzer-no-link" CACHE STRING "")
