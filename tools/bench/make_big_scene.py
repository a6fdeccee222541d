#!/usr/bin/env python3
"""Writes a large scene for measuring `inbetween bake` (memory and time; see bench/RESULTS.md).

    python3 tools/bench/make_big_scene.py --tracks 10000 --frames 10000 > big.json
    /usr/bin/time -v inbetween bake big.json -o big.csv

Every track is a scalar F-curve (Blender semantics, the common case in a real scene) with KEYS keys
spread over the range, mixed interpolations (bezier with auto-clamped handles, linear, sine easing)
and a repeat cycle, so evaluation is not trivially constant.  The scene's range is [1, FRAMES], so
a plain `bake` evaluates TRACKS x FRAMES values.  Seeded: the same arguments give the same file.
"""
import argparse
import json
import random
import sys


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tracks", type=int, default=10000, help="number of scalar tracks (columns)")
    ap.add_argument("--frames", type=int, default=10000, help="scene range [1, FRAMES]")
    ap.add_argument("--keys", type=int, default=6, help="keys per track (>= 2)")
    ap.add_argument("--seed", type=int, default=1, help="random seed")
    args = ap.parse_args()
    if args.tracks < 1 or args.frames < 1 or args.keys < 2:
        ap.error("--tracks and --frames must be >= 1, --keys >= 2")
    rng = random.Random(args.seed)
    interpolations = ["bezier", "bezier", "linear", "sine"]
    out = sys.stdout
    out.write('{"inbetween": 1, "fps": 24, "range": [1, %d], "tracks": [\n' % args.frames)
    # Keys cover a span shorter than the range; the cycle modifier repeats it to the end.
    span = max(2.0, min(args.frames, 200.0))
    for t in range(args.tracks):
        keys = []
        for k in range(args.keys):
            keys.append({"frame": round(1 + span * k / (args.keys - 1), 3),
                         "value": round(rng.uniform(-10, 10), 4),
                         "interpolation": rng.choice(interpolations)})
        track = {"name": "obj%05d.prop" % t, "keys": keys,
                 "cycles": {"before": "repeat", "after": "repeat"}}
        out.write(("  " if t == 0 else ", ") + json.dumps(track, separators=(",", ":")) + "\n")
    out.write("]}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
