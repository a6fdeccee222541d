#!/bin/sh
# `make bench-acl ACL_SRC=/path/to/acl`: ACL 2.1 (nfrechette/acl) and inbetween's compressor on the
# CMU clips of Debian's assimp-testmodels, by inbetween's own clip-error metric, in one binary (issue 24).  ACL is not
# packaged in Debian, so the user supplies its source (`git clone --recursive
# https://github.com/nfrechette/acl`, with its external/rtm submodule); nothing is downloaded here
# and nothing of ACL enters the repository.  ACL is header-only: none of its tests or tools are built.
# Steps:
#   1. build libinbetween.a, libinbetween_io.a (the BVH reader) and libinbetween_eigen.a with the preset;
#   2. compile tools/bench/acl_clip_bench.cpp against ACL's and rtm's headers and those libraries
#      (-O3 -DNDEBUG as the release preset, plus ACL_CXXFLAGS, e.g. -march=native);
#   3. run it on 01_01.bvh, 01_03.bvh, Boxing_Toes.bvh at E = 0.01 and 0.1, shell D = 3 (clip
#      units): ACL's and inbetween's bytes, errors, decode ns per joint and compression times side
#      by side, with JSON output to build/acl/acl_clip_bench.json, ACL's version and commit,
#      inbetween's commit, the flags, the date and the machine in its context;
#   4. write the in-tree reference bench/acl_reference.json from it (what `make bench` reports
#      against without ACL) and rewrite the generated section of bench/RESULTS.md with
#      tools/bench/write_results.py, which adds the "ACL 2.1 vs inbetween compression" table.
# Environment (the Makefile passes them): ACL_SRC, BUILD (build/release), PRESET, JOBS,
# BENCH_MIN_TIME, ACL_CXXFLAGS, CXX, BVH_DIR (/usr/share/assimp/models/BVH).
set -eu

ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT"
BUILD=${BUILD:-build/release}
PRESET=${PRESET:-release}
JOBS=${JOBS:-2}
BENCH_MIN_TIME=${BENCH_MIN_TIME:-0.1}
ACL_CXXFLAGS=${ACL_CXXFLAGS:-}
CXX=${CXX:-g++}
BVH_DIR=${BVH_DIR:-/usr/share/assimp/models/BVH}
OUT=build/acl

if [ -z "${ACL_SRC:-}" ] || [ ! -f "$ACL_SRC/includes/acl/compression/compress.h" ]; then
  echo "make bench-acl: ACL_SRC must name an ACL (nfrechette/acl) source tree (got '${ACL_SRC:-}')." >&2
  echo "  ACL is not packaged in Debian; get it with its rtm submodule:" >&2
  echo "    git clone --recursive --branch v2.1.0 https://github.com/nfrechette/acl /path/to/acl" >&2
  echo "  then: make bench-acl ACL_SRC=/path/to/acl   (measured with v2.1.0, commit 414689d5)" >&2
  exit 2
fi
ACL_SRC=$(cd "$ACL_SRC" && pwd)
if [ ! -f "$ACL_SRC/external/rtm/includes/rtm/qvvf.h" ]; then
  echo "make bench-acl: $ACL_SRC/external/rtm has no Realtime Math headers (includes/rtm/qvvf.h)." >&2
  echo "  Fetch ACL's submodule: git -C $ACL_SRC submodule update --init external/rtm" >&2
  exit 2
fi
for clip in 01_01 01_03 Boxing_Toes; do
  if [ ! -f "$BVH_DIR/$clip.bvh" ]; then
    echo "make bench-acl: $BVH_DIR/$clip.bvh is missing (Debian package assimp-testmodels; make deps installs it)." >&2
    exit 2
  fi
done

# Which ACL: the version its acl/version.h declares and, for a git checkout, the commit (rtm's too).
acl_version=$(sed -n 's/^#define ACL_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9][0-9]*\)$/\2/p' "$ACL_SRC/includes/acl/version.h" | paste -sd. -)
acl_commit=$(git -C "$ACL_SRC" rev-parse --short=8 HEAD 2>/dev/null || echo "unknown (not a git checkout)")
rtm_commit=$(git -C "$ACL_SRC/external/rtm" rev-parse --short=8 HEAD 2>/dev/null || echo "unknown (not a git checkout)")
echo "== ACL ${acl_version:-unknown version} ($acl_commit, rtm $rtm_commit) from $ACL_SRC"

mkdir -p "$OUT"
cmake --build --preset "$PRESET" -j "$JOBS" --target inbetween_core inbetween_io
flags=$(echo "-std=c++20 -O3 -DNDEBUG $ACL_CXXFLAGS" | sed "s/ *$//")
eigen_lib=""
[ -f "$BUILD/libinbetween_eigen.a" ] && eigen_lib="$BUILD/libinbetween_eigen.a"
# shellcheck disable=SC2086,SC2046  # flags and libraries are words on purpose
"$CXX" $flags -Iinclude -isystem "$ACL_SRC/includes" -isystem "$ACL_SRC/external/rtm/includes" \
  tools/bench/acl_clip_bench.cpp -o "$OUT/acl_clip_bench" \
  "$BUILD/libinbetween_io.a" $eigen_lib "$BUILD/libinbetween.a" \
  -lassimp -ltinyobjloader_double $(pkg-config --libs libhwy) -lpthread

"$OUT/acl_clip_bench" -o "$OUT/acl_clip_bench.json.tmp" --errors 0.01,0.1 --shell 3 \
  "$BVH_DIR/01_01.bvh" "$BVH_DIR/01_03.bvh" "$BVH_DIR/Boxing_Toes.bvh"
# What was measured, into the JSON's context.
inbetween_commit=$(git describe --always --dirty --abbrev=8 2>/dev/null || echo unknown)
python3 - "$OUT/acl_clip_bench.json.tmp" "${acl_version:-unknown}" "$acl_commit" "$rtm_commit" "$flags" "$inbetween_commit" <<'PY'
import datetime, json, platform, sys
path, version, commit, rtm, flags, ours = sys.argv[1:]
with open(path, encoding="utf-8") as f:
    doc = json.load(f)
cpu = platform.processor() or platform.machine()
try:
    with open("/proc/cpuinfo", encoding="utf-8") as f:
        cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
except (OSError, StopIteration):
    pass
doc["context"].update({"acl_version_tree": version, "acl_commit": commit, "rtm_commit": rtm, "cxxflags": flags,
                       "inbetween_commit": ours, "command": "make bench-acl",
                       "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
                       "machine": cpu})
with open(path, "w", encoding="utf-8") as f:
    json.dump(doc, f, indent=2)
PY
mv "$OUT/acl_clip_bench.json.tmp" "$OUT/acl_clip_bench.json"
python3 tools/bench/acl_reference.py "$OUT/acl_clip_bench.json" bench/acl_reference.json

if ls "$BUILD"/bench/inbetween_bench_*.json >/dev/null 2>&1; then
  # Re-render the in-tree tables from the last `make bench` (their own date stays) with the ACL table.
  python3 tools/bench/write_results.py --build-dir "$BUILD" --json-dir "$BUILD/bench" \
    --acl-json "$OUT/acl_clip_bench.json" \
    --command "make bench PRESET=$PRESET (re-rendered from its JSON by make bench-acl)"
else
  echo "make bench-acl: no in-tree benchmark JSON in $BUILD/bench (run make bench); bench/RESULTS.md not rewritten." >&2
fi
