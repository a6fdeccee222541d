#!/bin/sh
# `make bench-ozz OZZ_SRC=/path/to/ozz-animation`: inbetween's RigClip against ozz-animation's
# SamplingJob on the same clips, in one binary: the 30-key rig of bench/ (issue 12) and the long
# clip, 10 s at 31 keys/s, with each side's bytes (issue 24).  ozz-animation is not packaged in Debian,
# so the user supplies its source (`git clone https://github.com/guillaumeblanc/ozz-animation`);
# nothing is downloaded here and nothing of ozz enters the repository.  Steps:
#   1. configure and build ozz's runtime and offline libraries out of tree in build/ozz/build
#      (Release, tools/samples/tests off);
#   2. compile tools/bench/ozz_rig_bench.cpp against them and build/<preset>/libinbetween.a
#      (-O3 -DNDEBUG as the release preset, plus OZZ_CXXFLAGS on both sides, e.g. -march=native);
#   3. run it (3 interleaved repetitions, medians) with JSON output to build/ozz/ozz_rig_bench.json,
#      with ozz's version and commit, inbetween's commit and the flags added to the JSON's context;
#   4. rewrite the generated section of bench/RESULTS.md with tools/bench/write_results.py, which
#      adds the "ozz-animation SamplingJob vs RigClip" table when that JSON exists: from the
#      in-tree benchmarks' JSON of the last `make bench` if there is one, else by running them.
# Environment (the Makefile passes them): OZZ_SRC, BUILD (build/release), PRESET, JOBS,
# BENCH_MIN_TIME, OZZ_CXXFLAGS, CXX.
set -eu

ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
BUILD=${BUILD:-build/release}
PRESET=${PRESET:-release}
JOBS=${JOBS:-2}
BENCH_MIN_TIME=${BENCH_MIN_TIME:-0.1}
OZZ_CXXFLAGS=${OZZ_CXXFLAGS:-}
CXX=${CXX:-g++}
OUT=build/ozz

if [ -z "${OZZ_SRC:-}" ] || [ ! -f "$OZZ_SRC/include/ozz/animation/runtime/sampling_job.h" ]; then
  echo "make bench-ozz: OZZ_SRC must name an ozz-animation source tree (got '${OZZ_SRC:-}')." >&2
  echo "  ozz-animation is not packaged in Debian; get it with" >&2
  echo "    git clone https://github.com/guillaumeblanc/ozz-animation /path/to/ozz-animation" >&2
  echo "  then: make bench-ozz OZZ_SRC=/path/to/ozz-animation   (measured with 0.16.0, commit 6cbdc790)" >&2
  exit 2
fi
OZZ_SRC=$(cd "$OZZ_SRC" && pwd)

# Which ozz: the version its CMakeLists.txt declares and, for a git checkout, the commit.
ozz_version=$(sed -n 's/^set(OZZ_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9][0-9]*\))$/\2/p' "$OZZ_SRC/CMakeLists.txt" | paste -sd. -)
ozz_commit=$(git -C "$OZZ_SRC" rev-parse --short=8 HEAD 2>/dev/null || echo "unknown (not a git checkout)")
echo "== ozz-animation ${ozz_version:-unknown version} ($ozz_commit) from $OZZ_SRC"

mkdir -p "$OUT"
cmake -S "$OZZ_SRC" -B "$OUT/build" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS=$OZZ_CXXFLAGS" \
  -Dozz_build_tools=OFF -Dozz_build_fbx=OFF -Dozz_build_gltf=OFF -Dozz_build_samples=OFF \
  -Dozz_build_howtos=OFF -Dozz_build_tests=OFF -Dozz_build_data=OFF -Dozz_build_postfix=OFF >"$OUT/configure.log" \
  || { cat "$OUT/configure.log"; exit 1; }
cmake --build "$OUT/build" -j "$JOBS" --target ozz_animation_offline ozz_animation ozz_base

# libinbetween.a only builds the clip (build_rig_clip) and holds the Highway kernels that
# sample_rig<double> dispatches to (hence -lhwy); sample_rig is a header template compiled into the
# benchmark with the flags below, as ozz's headers are.
cmake --build --preset "$PRESET" -j "$JOBS" --target inbetween_core
flags=$(echo "-std=c++20 -O3 -DNDEBUG $OZZ_CXXFLAGS" | sed "s/ *$//")
# shellcheck disable=SC2086  # flags are words on purpose
"$CXX" $flags -Iinclude -Ibench -I"$OZZ_SRC/include" tools/bench/ozz_rig_bench.cpp -o "$OUT/ozz_rig_bench" \
  "$OUT/build/src/animation/offline/libozz_animation_offline.a" "$OUT/build/src/animation/runtime/libozz_animation.a" \
  "$OUT/build/src/base/libozz_base.a" "$BUILD/libinbetween.a" $(pkg-config --libs libhwy) -lbenchmark -lpthread

"$OUT/ozz_rig_bench" "--benchmark_min_time=$BENCH_MIN_TIME" --benchmark_repetitions=3 \
  --benchmark_report_aggregates_only=true --benchmark_enable_random_interleaving=true \
  "--benchmark_out=$OUT/ozz_rig_bench.json.tmp" --benchmark_out_format=json
# What was measured, into the JSON's context (--benchmark_context cannot carry '=' in a value).
inbetween_commit=$(git describe --always --dirty --abbrev=8 2>/dev/null || echo unknown)
python3 - "$OUT/ozz_rig_bench.json.tmp" "${ozz_version:-unknown}" "$ozz_commit" "$flags" "$inbetween_commit" <<'PY'
import json, sys
path, version, commit, flags, ours = sys.argv[1:]
with open(path, encoding="utf-8") as f:
    doc = json.load(f)
doc["context"].update({"ozz_version": version, "ozz_commit": commit, "cxxflags": flags,
                       "inbetween_commit": ours, "command": "make bench-ozz"})
with open(path, "w", encoding="utf-8") as f:
    json.dump(doc, f, indent=2)
PY
mv "$OUT/ozz_rig_bench.json.tmp" "$OUT/ozz_rig_bench.json"

if ls "$BUILD"/bench/inbetween_bench_*.json >/dev/null 2>&1; then
  # Re-render the in-tree tables from the last `make bench` (their own date stays) with the ozz table.
  python3 tools/bench/write_results.py --build-dir "$BUILD" --json-dir "$BUILD/bench" \
    --ozz-json "$OUT/ozz_rig_bench.json" \
    --command "make bench PRESET=$PRESET (re-rendered from its JSON by make bench-ozz)"
else
  cmake --build --preset "$PRESET" -j "$JOBS" --target inbetween_benchmarks
  python3 tools/bench/write_results.py --build-dir "$BUILD" --min-time "$BENCH_MIN_TIME" \
    --ozz-json "$OUT/ozz_rig_bench.json" --command "make bench-ozz PRESET=$PRESET"
fi

# ---- issue 23 (blend helper): blend_poses against ozz-animation's BlendingJob on the same poses
# (tools/bench/ozz_blend_bench.cpp, poses from bench/blend_fixture.hpp), JSON to
# build/ozz/ozz_blend_bench.json, then the tables re-rendered from the JSON files (write_results.py's
# blend_section reads it).  Same flags and the same ozz libraries as above.
# shellcheck disable=SC2086  # flags are words on purpose
# (libinbetween.a holds blend_poses<float>'s kernel, src/tracks/blend_kernel.cpp, with its CPU dispatch.)
"$CXX" $flags -Iinclude -Ibench -I"$OZZ_SRC/include" tools/bench/ozz_blend_bench.cpp -o "$OUT/ozz_blend_bench" \
  "$OUT/build/src/animation/runtime/libozz_animation.a" "$OUT/build/src/base/libozz_base.a" "$BUILD/libinbetween.a" \
  $(pkg-config --libs libhwy) -lbenchmark -lpthread
"$OUT/ozz_blend_bench" "--benchmark_min_time=$BENCH_MIN_TIME" --benchmark_repetitions=3 \
  --benchmark_report_aggregates_only=true --benchmark_enable_random_interleaving=true \
  "--benchmark_out=$OUT/ozz_blend_bench.json.tmp" --benchmark_out_format=json
python3 - "$OUT/ozz_blend_bench.json.tmp" "${ozz_version:-unknown}" "$ozz_commit" "$flags" "$inbetween_commit" "$(cut -d' ' -f1-3 /proc/loadavg)" <<'PY'
import json, sys
path, version, commit, flags, ours, load = sys.argv[1:]
with open(path, encoding="utf-8") as f:
    doc = json.load(f)
doc["context"].update({"ozz_version": version, "ozz_commit": commit, "cxxflags": flags,
                       "inbetween_commit": ours, "command": "make bench-ozz", "load": load})
with open(path, "w", encoding="utf-8") as f:
    json.dump(doc, f, indent=2)
PY
mv "$OUT/ozz_blend_bench.json.tmp" "$OUT/ozz_blend_bench.json"
if ls "$BUILD"/bench/inbetween_bench_*.json >/dev/null 2>&1; then
  python3 tools/bench/write_results.py --build-dir "$BUILD" --json-dir "$BUILD/bench" \
    --ozz-json "$OUT/ozz_rig_bench.json" \
    --command "make bench PRESET=$PRESET (re-rendered from its JSON by make bench-ozz)"
fi
