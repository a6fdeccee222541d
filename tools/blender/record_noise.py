"""Record Blender 3.4's original noise and the Noise F-curve modifier for tests/math/blender_noise_test.cpp.

    blender -b --factory-startup --python tools/blender/record_noise.py -- \
        -o tests/data/blender/noise-blender-3.4.1.json [--seed 23]

Writes one JSON file with two parts:

- "mathutils": [x, y, z, r] rows, r = mathutils.noise.noise((x, y, z), noise_basis='BLENDER'),
  which Blender computes as float32(2·orgBlenderNoise(x + 1, y + 1, z + 1) − 1) with the +1 in
  float32.  Points are seeded random float32 triples over a wide range: uniform in ±300, signed
  log-uniform magnitudes from 1e-3 to 1e10 (beyond 2^31 the lattice index is INT_MIN in Blender),
  integers and integers ± a few float32 ulps, one huge coordinate with two ordinary ones.
- "modifier": F-curves of a few Bézier keys with one Noise modifier of random scale, strength,
  phase, offset, depth and blend type; per curve, frames and fcurve.evaluate(frame) with the
  modifier active ("value") and muted ("curve", the curve's own value), so that a test can apply
  the modifier's formula to the curve value before the F-curve modifier stack exists.

Every number is a float32 value written as the shortest decimal of its exact double value.
"""

import argparse
import json
import sys

import bpy
import numpy as np
import mathutils.noise as mn


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", required=True)
    parser.add_argument("--seed", type=int, default=23)
    return parser.parse_args(argv)


def f32(value):
    return float(np.float32(value))


def g9(value):
    """A float32 value as a JSON number: the shortest decimal that parses back to the same double,
    which is exactly the float32 (9 significant digits would need a float parser: a double parse
    then a float cast can round twice)."""
    return float(np.float32(value))


def noise_points(rng, count):
    points = []
    kinds = ["uniform", "log", "near_integer", "one_huge"]
    for k in range(count):
        kind = kinds[k % len(kinds)]
        if kind == "uniform":
            p = rng.uniform(-300.0, 300.0, 3)
        elif kind == "log":
            p = np.sign(rng.uniform(-1, 1, 3)) * 10.0 ** rng.uniform(-3, 10, 3)
        elif kind == "near_integer":
            p = []
            for _ in range(3):
                base = np.float32(rng.integers(-600, 600))
                for _ in range(int(rng.integers(-3, 4))):
                    base = np.nextafter(base, np.float32(np.inf) if rng.uniform() < 0.5 else np.float32(-np.inf))
                p.append(float(base))
        else:
            p = list(rng.uniform(-50.0, 50.0, 3))
            p[int(rng.integers(3))] = float(np.sign(rng.uniform(-1, 1)) * 10.0 ** rng.uniform(7, 12))
        points.append([f32(c) for c in p])
    return points


BLEND_TYPES = ["REPLACE", "ADD", "SUBTRACT", "MULTIPLY"]


def modifier_cases(rng, curves, frames_per_curve):
    action = bpy.data.actions.new("noise_record")
    cases = []
    for index in range(curves):
        fcurve = action.fcurves.new("location", index=index)  # a free-standing curve
        keys = int(rng.integers(2, 6))
        frame = float(rng.uniform(-10, 10))
        for _ in range(keys):
            fcurve.keyframe_points.insert(f32(frame), f32(rng.uniform(-5, 5)))
            frame += float(rng.uniform(3, 25))
        fcurve.update()
        mod = fcurve.modifiers.new('NOISE')
        # Scale 0 once (Blender's noise is then 0), otherwise 0.3 .. 40 frames, negative for
        # every eighth curve (Blender allows it: the noise runs mirrored); strength sometimes < 0.
        mod.scale = 0.0 if index == 0 else f32(10.0 ** rng.uniform(-0.5, 1.6))
        if index % 8 == 5:
            mod.scale = -mod.scale
        mod.strength = f32(rng.uniform(0.05, 6.0) * (-1.0 if index % 6 == 4 else 1.0))
        mod.phase = f32(rng.uniform(-20.0, 20.0))
        mod.offset = f32(rng.uniform(-60.0, 60.0)) if rng.uniform() < 0.8 else 0.0
        mod.depth = int(rng.integers(0, 9))
        mod.blend_type = BLEND_TYPES[index % len(BLEND_TYPES)]
        frames = [f32(f) for f in rng.uniform(-30.0, 130.0, frames_per_curve)]
        frames += [f32(np.floor(frames[0])), f32(np.floor(frames[1]) + 0.5)]  # integer, half
        values = [fcurve.evaluate(f) for f in frames]
        mod.mute = True
        curve = [fcurve.evaluate(f) for f in frames]
        mod.mute = False
        cases.append({
            "scale": g9(mod.scale), "strength": g9(mod.strength), "phase": g9(mod.phase),
            "offset": g9(mod.offset), "depth": mod.depth, "blend_type": mod.blend_type,
            "frames": [g9(f) for f in frames], "curve": [g9(v) for v in curve],
            "value": [g9(v) for v in values],
        })
    bpy.data.actions.remove(action)
    return cases


def main():
    args = parse_args()
    rng = np.random.default_rng(args.seed)
    points = noise_points(rng, 2000)
    rows = [[g9(c) for c in p] + [g9(mn.noise(p, noise_basis='BLENDER'))] for p in points]
    record = {
        "source": f"Blender {bpy.app.version_string}, tools/blender/record_noise.py --seed {args.seed}",
        "mathutils": rows,
        "modifier": modifier_cases(rng, curves=48, frames_per_curve=22),
    }
    with open(args.output, "w") as out:
        json.dump(record, out, separators=(",", ":"))
        out.write("\n")
    print(f"wrote {args.output}: {len(rows)} noise points, {len(record['modifier'])} curves")


if __name__ == "__main__":
    main()
