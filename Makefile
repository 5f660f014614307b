# The two commands of the README: `make run` and `make test`. Both install what is missing first.
BUILD ?= build
JOBS ?= $(shell nproc)
# How `make build` configures a tree: a release build unless a target says otherwise.
CMAKE_CONFIG ?= -DCMAKE_BUILD_TYPE=Release
CMAKE_FLAGS ?=
FUZZ_SECONDS ?= 60

.PHONY: deps build run viewer demo test test-sanitize test-container fuzz soak bench format clean

deps:
	scripts/install-deps

build: deps
	cmake -S . -B $(BUILD) $(CMAKE_CONFIG) $(CMAKE_FLAGS) >/dev/null
	cmake --build $(BUILD) -j $(JOBS)

# soiqd on 127.0.0.1:50051 with the SQLite store var/soiq.db, in the foreground (scripts/run-server).
# It builds only the programs (and their man pages and completion), not the tests and benchmarks:
# a newcomer's first answer comes minutes sooner, and `make test` builds the rest.
run: deps
	cmake -S . -B $(BUILD) $(CMAKE_CONFIG) $(CMAKE_FLAGS) >/dev/null
	cmake --build $(BUILD) -j $(JOBS) --target soiqd soiq soiq_generated_docs
	scripts/run-server $(BUILD)

# OHIF's published build on 127.0.0.1:3000, reading `make run`'s soiqd (scripts/run-viewer); it
# fetches OHIF once (tests/web/install_ohif.sh, pinned by hash).
viewer:
	scripts/run-viewer

# The offline conversion demo: a real label map -> surface -> volume, voxel for voxel (scripts/demo).
demo: build
	scripts/demo $(BUILD)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The sanitizer tree (cmake/sanitize.cmake: clang-14, ASan + UBSan, libFuzzer's coverage): the
# same tests under the sanitizers, and the fuzzing harnesses. CI runs both.
SANITIZE_BUILD = build-sanitize
SANITIZE_CONFIG = -C $(CURDIR)/cmake/sanitize.cmake

# The same tests under AddressSanitizer + UndefinedBehaviorSanitizer.
test-sanitize:
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 $(MAKE) test BUILD=$(SANITIZE_BUILD) CMAKE_CONFIG="$(SANITIZE_CONFIG)"

# The container end to end (docker/test-container; not part of `make test`): podman, podman-compose
# and debootstrap installed, the debian:12 base image made from Debian's archive, soiq's and
# PostgreSQL's images built (compile jobs: JOBS), soiqd's container and the compose file's three
# replicas on PostgreSQL loaded with the demo and queried, everything it started removed. Root only.
test-container:
	scripts/install-deps --container
	JOBS=$(JOBS) docker/test-container

# Every libFuzzer harness of fuzz/ for FUZZ_SECONDS each, after replaying fuzz/regressions/; fails on
# any crash, leak, timeout or out-of-memory (FUZZING.md).
fuzz: deps
	cmake $(SANITIZE_CONFIG) -S . -B $(SANITIZE_BUILD) >/dev/null
	cmake --build $(SANITIZE_BUILD) --target soiq_fuzzers -j $(JOBS)
	fuzz/run $(SANITIZE_BUILD) $(FUZZ_SECONDS) $(FUZZ_HARNESSES)

# A soak of mixed load (uploads, imports, STOW, WADO, queries, deletes) against a real soiqd for
# SOAK_MINUTES (30): fails on any error or on memory that keeps growing (scripts/soak). Then the
# store's faults FAULT_ROUNDS times over: PostgreSQL down and back under replicas' load, a SQLite
# store's disk full (tests/integration/store_faults_test.cpp; `make test` runs them once).
SOAK_MINUTES ?= 30
FAULT_ROUNDS ?= 10
soak: build
	scripts/soak $(BUILD) $(SOAK_MINUTES)
	$(BUILD)/tests/integration/soiq_integration_tests --gtest_filter='StoreFaultsTest.*' --gtest_repeat=$(FAULT_ROUNDS) \
	  --gtest_brief=1

# Benchmarks build apart (build-bench) as `make run` builds, portably: the hot kernels pick the CPU's
# level at run time (core/base/cpu_dispatch.h). A second soiq-bench tuned for this CPU
# (build-bench-native, -march=native) runs beside it once, to show what the flag would still add.
# SOIQ_ARCH= is passed explicitly: a build-bench configured before keeps its cached -march otherwise.
bench:
	$(MAKE) build BUILD=build-bench CMAKE_FLAGS=-DSOIQ_ARCH=
	cmake -S . -B build-bench-native -DSOIQ_ARCH=native >/dev/null
	cmake --build build-bench-native -j $(JOBS) --target soiq-bench
	bench/run build-bench build-bench-native

format:
	git ls-files '*.h' '*.cpp' | xargs clang-format -i

clean:
	rm -rf build build-sanitize build-bench build-bench-native build-asan build-fuzz
