# The two commands a newcomer needs: `make demo` and `make test`.  Each installs whatever Debian
# packages are missing, configures with a CMake preset, builds, and runs.
PRESET ?= release
BUILD  := build/$(PRESET)
JOBS   ?= $(shell nproc 2>/dev/null || echo 2)

# Build and test dependencies (Debian 12 package names).  python3-scipy and python3-jsonschema are
# independent references (rotation conventions, least squares, the scene JSON Schema) that tests use
# through /usr/bin/python3; those tests skip when they are absent.  clang and libclang-rt-dev
# (libFuzzer, the sanitizer runtimes) build the asan preset that `make test` also runs.  esbuild
# bundles three.js into the page of `inbetween view` at build time; chromium runs that page in the
# browser test (docs/preview.md).  libhwy-dev: Highway, the double rig kernel's run-time SIMD
# dispatch; libxsimd-dev: the benchmarks' xsimd comparison (docs/runtime.md).  libassimp-dev:
# FBX, Collada, … (docs/assimp.md); assimp-testmodels: its test files (FBX, Collada, CMU BVH clips)
# that the assimp and BVH tests read, and the CMU
# motion-capture clips (models/BVH/) that `make demo` shows and the BVH bench reads (tests/data/bvh/README.md).
# python3-distributed, python3-dask: the batch on Dask (python/inbetween/batch.py, docs/batch.md) and
# its test (python.batch) and bench.
DEBS := g++ cmake make pkg-config libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev \
        nlohmann-json3-dev libtinyobjloader-dev libtinygltf-dev gltfpack libeigen3-dev libglm-dev libboost-dev \
        python3 python3-scipy python3-jsonschema clang libclang-rt-dev esbuild chromium \
        pybind11-dev python3-dev python3-pytest python3-numpy libhwy-dev libxsimd-dev \
        libassimp-dev assimp-testmodels python3-distributed python3-dask

.PHONY: all deps configure build test demo screenshots bench bench-ozz bench-acl asan fuzz clean

all: build

deps:
	@missing=""; \
	for p in $(DEBS); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "make: installing missing Debian packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" -eq 0 ] || SUDO=sudo; \
	  $$SUDO apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing; \
	fi
	@# npm (Debian's) for the JavaScript references below, where the machine has none: a fresh
	@# Debian 12 has no npm; a machine with its own Node.js and npm keeps them.
	@if ! command -v npm >/dev/null 2>&1; then \
	  echo "make: installing Debian's npm (for three.js, gltf-validator and the browser tests)"; \
	  SUDO=""; [ "$$(id -u)" -eq 0 ] || SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends npm \
	    || echo "make: npm could not be installed; the JavaScript cross-checks will skip"; \
	fi
	@# three.js: the page of `inbetween view` (bundled at build time; without it `view` says how to
	@# get it) and the independent glTF reference of an optional test (skips without it).
	@if [ -f tools/threejs/node_modules/three/package.json ]; then :; \
	elif command -v npm >/dev/null 2>&1; then \
	  npm ci --prefix tools/threejs --no-audit --no-fund --loglevel=error \
	    || echo "make: npm could not install three.js; the glTF cross-check test will skip"; \
	else echo "make: npm not found; the three.js glTF cross-check test will skip"; fi
	@# playwright-core, which drives chromium in the browser test of the preview (skips without it).
	@if [ -f tools/browser/node_modules/playwright-core/package.json ]; then :; \
	elif command -v npm >/dev/null 2>&1; then \
	  npm ci --prefix tools/browser --no-audit --no-fund --loglevel=error \
	    || echo "make: npm could not install playwright-core; the browser test will skip"; \
	else echo "make: npm not found; the browser test will skip"; fi
	@# The Khronos glTF validator, run on exported files by an optional test (skips without it).
	@if [ -f tools/gltf-validator/node_modules/gltf-validator/package.json ]; then :; \
	elif command -v npm >/dev/null 2>&1; then \
	  npm ci --prefix tools/gltf-validator --no-audit --no-fund --loglevel=error \
	    || echo "make: npm could not install gltf-validator; the glTF validation test will skip"; \
	else echo "make: npm not found; the glTF validation test will skip"; fi

# The module tests (tests/<module>/) are compiled and run once, in the asan preset: the release
# suite of `make test` builds tests/apps only, which with Python, the browser page, the package and
# the benchmarks' smoke runs is what only the optimised build shows (INBETWEEN_MODULE_TESTS, about
# 4 minutes of CPU less).  With SKIP_ASAN=1 the release suite keeps them.  `make build`, `make demo`
# and a plain `cmake --preset release` keep whatever the build folder was configured with
# (`-DINBETWEEN_MODULE_TESTS=ON` to have them again in release).
MODULE_TESTS = $(if $(filter release,$(PRESET)),$(if $(SKIP_ASAN),ON,OFF),ON)
CONFIGURE_ARGS ?=
test: CONFIGURE_ARGS += -DINBETWEEN_MODULE_TESTS=$(MODULE_TESTS)

configure: deps
	cmake --preset $(PRESET) $(CONFIGURE_ARGS)

build: configure
	cmake --build --preset $(PRESET) -j $(JOBS)

# `make test` (what CI runs) is the release suite (without the module tests, see MODULE_TESTS
# above), then the asan preset: the whole suite under AddressSanitizer + UndefinedBehaviorSanitizer
# and a short fixed run of each fuzz target (fuzz/README.md).  SKIP_ASAN=1 runs the release suite
# alone, module tests included.  Skipped tests (a reference tool
# absent) are listed with their reason after each ctest summary.
test: build
	ctest --preset $(PRESET)
	@tools/report_skips.sh $(BUILD)
	@if [ "$(PRESET)" = release ] && [ -z "$(SKIP_ASAN)" ]; then $(MAKE) --no-print-directory asan; fi

demo: build
	./$(BUILD)/inbetween demo

# The README's preview image is the screenshot the browser test takes (tests/browser): run that
# test, then copy its picture to docs/images/preview.png.
screenshots: build
	ctest --preset $(PRESET) -L browser
	@test -f $(BUILD)/preview-test/preview.png || { echo "make: the browser test wrote no screenshot (skipped?)"; exit 1; }
	cp $(BUILD)/preview-test/preview.png docs/images/preview.png
	@# the CMU clip once the tool reads BVH, else the test's own 31-joint skeleton
	if [ -f $(BUILD)/preview-test/01_01.png ]; then cp $(BUILD)/preview-test/01_01.png docs/images/preview-skeleton.png; \
	else cp $(BUILD)/preview-test/skeleton.png docs/images/preview-skeleton.png; fi
	@echo "make: docs/images/preview.png and preview-skeleton.png updated from the browser test"

# Runs every bench program (3 interleaved repetitions, medians) and writes the generated section of
# bench/RESULTS.md (tools/bench/write_results.py; the hand-written analysis below it stays).
BENCH_MIN_TIME ?= 0.1
# Then the batch on Dask (issue 25, bench/batch_bench.py): 2 workers against 1 on 200 scenes and the
# overhead per job against the tool; it prints its table (the figures go to RESULTS.md's notes by hand).
BATCH_PYTHON ?= $(shell test -x /usr/bin/python3 && echo /usr/bin/python3 || echo python3)
bench: build
	cmake --build --preset $(PRESET) -j $(JOBS) --target inbetween_benchmarks
	python3 tools/bench/write_results.py --build-dir $(BUILD) --min-time $(BENCH_MIN_TIME) \
	  --command "make bench PRESET=$(PRESET)"
	PYTHONPATH=$(BUILD)/python $(BATCH_PYTHON) bench/batch_bench.py --cli $(BUILD)/inbetween

# ozz-animation's SamplingJob against RigClip on the same clip (issue 12).  ozz is not packaged in
# Debian: give its source tree (git clone https://github.com/guillaumeblanc/ozz-animation); it is
# built out of tree in build/ozz, nothing is downloaded.  Not part of `make bench` or `make test`.
# OZZ_CXXFLAGS (e.g. -march=native) goes to ozz's build and to the benchmark, both sides alike.
# tools/bench/bench_ozz.sh says what it does step by step; the table lands in bench/RESULTS.md.
OZZ_SRC ?=
OZZ_CXXFLAGS ?=
bench-ozz: configure
	OZZ_SRC="$(OZZ_SRC)" OZZ_CXXFLAGS="$(OZZ_CXXFLAGS)" BUILD="$(BUILD)" PRESET="$(PRESET)" JOBS="$(JOBS)" \
	  BENCH_MIN_TIME="$(BENCH_MIN_TIME)" CXX="$(CXX)" tools/bench/bench_ozz.sh

# ACL 2.1 (nfrechette/acl) against inbetween's compression on the CMU clips of assimp-testmodels,
# by inbetween's clip-error metric (issue 24).  ACL is not packaged in Debian: give its source tree
# (git clone --recursive https://github.com/nfrechette/acl, with its external/rtm submodule); it is
# header-only, compiled into one benchmark in build/acl, nothing is downloaded.  Not part of `make
# bench` or `make test`; it rewrites the tracked reference bench/acl_reference.json that `make bench`
# reports against.  tools/bench/bench_acl.sh says what it does step by step.
ACL_SRC ?=
ACL_CXXFLAGS ?=
bench-acl: configure
	ACL_SRC="$(ACL_SRC)" ACL_CXXFLAGS="$(ACL_CXXFLAGS)" BUILD="$(BUILD)" PRESET="$(PRESET)" JOBS="$(JOBS)" \
	  BENCH_MIN_TIME="$(BENCH_MIN_TIME)" CXX="$(CXX)" tools/bench/bench_acl.sh

asan:
	$(MAKE) test PRESET=asan

# Each libFuzzer target for FUZZ_SECONDS (asan preset); the corpus grows in build/asan/fuzz/corpus-*,
# crashes land in build/asan/fuzz/artifacts-*/ (see fuzz/README.md for what to do with them).
FUZZ_SECONDS ?= 60
FUZZ_TARGETS := scene curve csv rotation_line obj environment gltf bvh assimp surface ibc
fuzz:
	$(MAKE) configure PRESET=asan
	cmake --build --preset asan -j $(JOBS) --target $(addprefix inbetween_fuzz_,$(FUZZ_TARGETS))
	@set -e; for t in $(FUZZ_TARGETS); do \
	  d=build/asan/fuzz; mkdir -p $$d/corpus-$$t $$d/artifacts-$$t; \
	  echo "== fuzz $$t for $(FUZZ_SECONDS) s"; \
	  supp=fuzz/lsan-$$t.supp; if [ -f $$supp ]; then export LSAN_OPTIONS=suppressions=$$PWD/$$supp; else unset LSAN_OPTIONS; fi; \
	  $$d/inbetween_fuzz_$$t -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
	    -max_total_time=$(FUZZ_SECONDS) -timeout=10 -dict=fuzz/dict/$$t.dict -print_final_stats=1 \
	    -artifact_prefix=$$d/artifacts-$$t/ $$d/corpus-$$t fuzz/corpus/$$t 2>&1 | grep -E '^#|INFO: (exiting|fuzzed)' | tail -3; \
	done
	@n=$$(ls build/asan/fuzz/artifacts-*/ 2>/dev/null | grep -c -E '^(crash|timeout|oom|leak)-'); \
	if [ "$$n" -gt 0 ]; then ls build/asan/fuzz/artifacts-*/; echo "make: $$n fuzz findings (fuzz/README.md)"; exit 1; fi

clean:
	rm -rf build
