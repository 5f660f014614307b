# The fuzzing build's initial cache (cmake -C fuzz/config.cmake -S . -B build-fuzz; `make fuzz` does
# it): Debian's clang-14 with libFuzzer, every soiq library instrumented for coverage and built with
# AddressSanitizer + UndefinedBehaviorSanitizer, the harnesses of fuzz/ linked with libFuzzer's main.
set(CMAKE_C_COMPILER clang-14 CACHE STRING "")
set(CMAKE_CXX_COMPILER clang++-14 CACHE STRING "")
set(SOIQ_FUZZ ON CACHE BOOL "")
# clang warns about things GCC does not (and the reverse); the GCC build is the one that gates
# warnings, this one gates crashes.
set(SOIQ_WERROR OFF CACHE BOOL "")
set(CMAKE_BUILD_TYPE RelWithDebInfo CACHE STRING "")
# No -DNDEBUG: an assert is an invariant no input can break, exactly what a fuzzer should test.
# Line tables are enough for symbolized stacks and keep the objects small.
set(CMAKE_C_FLAGS_RELWITHDEBINFO "-O1 -gline-tables-only" CACHE STRING "")
set(CMAKE_CXX_FLAGS_RELWITHDEBINFO "-O1 -gline-tables-only" CACHE STRING "")
set(soiq_fuzz_flags "-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer")
set(CMAKE_C_FLAGS "${soiq_fuzz_flags}" CACHE STRING "")
set(CMAKE_CXX_FLAGS "${soiq_fuzz_flags}" CACHE STRING "")
set(CMAKE_EXE_LINKER_FLAGS "-fsanitize=address,undefined" CACHE STRING "")
