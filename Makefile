# The two commands a newcomer needs: `make demo` and `make test`.  Each installs whatever Debian
# packages are missing, configures with a CMake preset, builds, and runs.
PRESET ?= release
BUILD  := build/$(PRESET)
JOBS   ?= $(shell nproc 2>/dev/null || echo 2)

# Build and test dependencies (Debian 12 package names).  python3-scipy and python3-jsonschema are
# independent references (rotation conventions, least squares, the scene JSON Schema) that tests use
# through /usr/bin/python3; those tests skip when they are absent.
DEBS := g++ cmake make pkg-config libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev \
        nlohmann-json3-dev libtinygltf-dev libeigen3-dev python3 python3-scipy python3-jsonschema

.PHONY: all deps configure build test demo bench asan clean

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
	@# three.js, the independent glTF reference of an optional test (skips without it).
	@if [ -f tools/threejs/node_modules/three/package.json ]; then :; \
	elif command -v npm >/dev/null 2>&1; then \
	  npm ci --prefix tools/threejs --no-audit --no-fund --loglevel=error \
	    || echo "make: npm could not install three.js; the glTF cross-check test will skip"; \
	else echo "make: npm not found; the three.js glTF cross-check test will skip"; fi

configure: deps
	cmake --preset $(PRESET)

build: configure
	cmake --build --preset $(PRESET) -j $(JOBS)

test: build
	ctest --preset $(PRESET)

demo: build
	./$(BUILD)/inbetween demo

bench: build
	@set -e; for b in $(BUILD)/bench/inbetween_bench_*; do \
	  [ -x "$$b" ] || continue; echo "== $$b"; "$$b" --benchmark_min_time=0.2; done

asan:
	$(MAKE) test PRESET=asan

clean:
	rm -rf build
