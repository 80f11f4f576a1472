# Thin wrapper over CMake and scripts/. The README's two commands are `make demo` and `make test`.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release
# The sanitizer build (clang, AddressSanitizer + UBSan, libFuzzer instrumentation; fuzz/README.md):
# unit tests run there once, and the fuzz targets. `make fuzz` runs each target FUZZ_SECONDS,
# FUZZ_JOBS at a time; `make test` adds a pass of CI_FUZZ_SECONDS per target. -O1 with line
# tables only: what OSS-Fuzz builds with, and the cheapest level that keeps the unit tests fast
# enough for CI (docs/reliability.md "CI time" has the measured costs of -O1, -O2 and gcc).
SANITIZE_BUILD ?= build-sanitize
FUZZ_WORK ?= $(SANITIZE_BUILD)/fuzz-work
FUZZ_SECONDS ?= 60
FUZZ_JOBS ?= 1
CI_FUZZ_SECONDS ?= 20
# EIGEN_NO_DEBUG: asserts stay on in this build (no NDEBUG), but not Eigen's index assert on every
# coefficient access: ASan checks the same bounds.
SANITIZE_OPT ?= -O1 -gline-tables-only -DEIGEN_NO_DEBUG
SANITIZE_FLAGS ?= -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMAPFUSE_FUZZ=ON -DMAPFUSE_BUILD_BENCH=OFF \
  -DMAPFUSE_GENERATE_FORESTS=OFF \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$(SANITIZE_OPT)" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=$(SANITIZE_OPT)"

.PHONY: deps deps-demo configure configure-demo build demo unity-check test test-release sanitizer-pass bench format clean \
        sanitize-configure sanitize-build test-sanitize test-sanitize-and-fuzz fuzz-corpus fuzz

deps:
	bash scripts/install-deps.sh

deps-demo:
	bash scripts/install-deps.sh --demo

configure: deps
	@if [ ! -f $(BUILD)/build.ninja ]; then cmake -S . -B $(BUILD) -G Ninja $(CMAKE_FLAGS); fi

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# The demo installs and builds only what it runs (install-deps.sh --demo; CMake target
# demo_tools), not the tests and benchmarks, in a folder of its own compiled in unity batches
# (CMakeLists.txt, MAPFUSE_UNITY_BUILD: half the compile time; the tools keep shared runtimes).
DEMO_BUILD ?= build-demo
DEMO_FLAGS ?= $(CMAKE_FLAGS) -DMAPFUSE_UNITY_BUILD=ON -DMAPFUSE_BUILD_TESTS=OFF -DMAPFUSE_BUILD_BENCH=OFF
configure-demo: deps-demo
	@if [ ! -f $(DEMO_BUILD)/build.ninja ]; then cmake -S . -B $(DEMO_BUILD) -G Ninja $(DEMO_FLAGS); fi

demo: configure-demo
	cmake --build $(DEMO_BUILD) -j $(JOBS) --target demo_tools
	bash scripts/demo.sh $(DEMO_BUILD)/bin out/demo

# CI (.ci/run) and the README's test command: the release build and all its tests (unit tests,
# e2e scripts, the real Lanelet2 validator, the Slurm test). The sanitizer and fuzz pass is
# `make sanitizer-pass`, by hand: its second build of everything (clang, ASan + UBSan) alone
# took longer than CI's budget leaves on 2 cores (docs/reliability.md "CI time").
test: test-release

# Only the release build's tests (unit tests, e2e scripts, the Slurm test): the quick check.
test-release: build unity-check
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# make demo's unity batches must compile too: the library as make demo builds it (two sources of
# one area that define the same name at namespace scope meet in a batch; about 4 minutes cold).
unity-check: configure-demo
	cmake --build $(DEMO_BUILD) -j $(JOBS) --target mapfuse

# The sanitizer pass of CI: the unit tests under ASan + UBSan, then every fuzz target
# CI_FUZZ_SECONDS, JOBS at a time. Skipped, loudly, only where clang cannot build a libFuzzer
# program even after `make deps` (not on Debian 12: install-deps.sh installs clang and its
# runtimes); fuzz/check-toolchain.sh says what is missing.
sanitizer-pass: deps
	@if bash fuzz/check-toolchain.sh; then \
	  $(MAKE) --no-print-directory test-sanitize-and-fuzz; \
	else \
	  echo "*** SKIPPED: the sanitizer and fuzz pass of make test (no clang with libFuzzer," \
	       "see above); the release tests passed ***" >&2; \
	fi

# The sanitizer pass by hand (same as in `make test`; FUZZ_SECONDS=600 for the long runs: `make fuzz`).
test-sanitize-and-fuzz:
	$(MAKE) --no-print-directory test-sanitize
	$(MAKE) --no-print-directory fuzz FUZZ_SECONDS=$(CI_FUZZ_SECONDS) FUZZ_JOBS=$(JOBS)

sanitize-configure: deps
	@if [ ! -f $(SANITIZE_BUILD)/build.ninja ]; then \
	  cmake -S . -B $(SANITIZE_BUILD) -G Ninja $(SANITIZE_FLAGS); fi

# Everything: the tools too, since unit tests of the apps run them.
sanitize-build: sanitize-configure
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)

# The unit tests (not the e2e scripts) under AddressSanitizer + UBSan: any report fails the test.
test-sanitize: sanitize-build
	cd $(SANITIZE_BUILD) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/fuzz/lsan.supp:print_suppressions=0 \
	  ctest --output-on-failure -j $(JOBS) -E '^e2e: '

# Seeds from the samples and small outputs of the tools (release build), regenerated each time.
fuzz-corpus: build
	bash fuzz/make-corpus.sh $(BUILD)/bin $(FUZZ_WORK)/seeds

fuzz: sanitize-build fuzz-corpus
	bash fuzz/run.sh $(SANITIZE_BUILD)/fuzz $(FUZZ_WORK) $(FUZZ_SECONDS) $(FUZZ_JOBS)

bench: build
	bash scripts/bench/run-all.sh $(BUILD)/bin

format:
	find apps libmapfuse tests scripts/bench -name '*.cpp' -o -name '*.hpp' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(DEMO_BUILD) $(SANITIZE_BUILD) out
