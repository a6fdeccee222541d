"""Random F-curves for the Blender agreement test (tests/io/blender_agreement_test.cpp).

Run inside Blender:  blender -b --factory-startup --python tools/blender/agreement_cases.py -- OUTDIR SEED
Builds random curves in every mode inside Blender, recomputes their handles with FCurve.update(),
exports them with export_fcurves.py to OUTDIR/scene.json and writes Blender's own values
(FCurve.evaluate) at fractional frames inside and outside the keyed range to OUTDIR/reference.json:
{"<track name>": {"group": "<mode>", "frames": [...], "values": [...]}}.

    ... agreement_cases.py -- OUTDIR SEED --stress COUNT [VARIANT]

writes COUNT random curves of one kind instead: every key mixes handle types (free, aligned, vector,
auto, auto_clamped on either side) and interpolations (Bézier, every easing with random easing
direction and parameters, linear, constant), with random extrapolation and smoothing.  VARIANT is a
comma-separated set of: "aligned" (every key has an aligned handle on one side), "sel" (random
handle selection, then a second update(), which makes Blender align in its other order), "far"
(samples up to five key spans outside the keyed range, where linear extrapolation magnifies a
handle's last bit).  The same SEED, COUNT and VARIANT give the same curves.
"""

import importlib.util
import json
import os
import random
import struct
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("export_fcurves", os.path.join(HERE, "export_fcurves.py"))
export_fcurves = importlib.util.module_from_spec(spec)
spec.loader.exec_module(export_fcurves)

EASINGS = ["BACK", "BOUNCE", "CIRC", "CUBIC", "ELASTIC", "EXPO", "QUAD", "QUART", "QUINT", "SINE"]
HANDLES = ["FREE", "ALIGNED", "VECTOR", "AUTO", "AUTO_CLAMPED"]
CYCLE_MODES = ["NONE", "REPEAT", "REPEAT_OFFSET", "MIRROR"]


def f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


def random_keys(rng, n, frame_scale=1.0):
    frames, x = [], rng.uniform(-30, 30) * frame_scale
    for _ in range(n):
        frames.append(x)
        x += rng.choice([rng.uniform(0.3, 3), rng.uniform(3, 15), float(rng.randint(1, 12))]) * frame_scale
    values = [rng.choice([rng.uniform(-10, 10), float(rng.randint(-3, 3))]) for _ in range(n)]
    return frames, values


def authored_state(fc):
    """The curve as authored, before update(): enough for record_reference.py to rebuild it."""
    keys = []
    for k in fc.keyframe_points:
        keys.append([k.co[0], k.co[1], k.interpolation, k.easing, k.handle_left_type, k.handle_right_type,
                     k.handle_left[0], k.handle_left[1], k.handle_right[0], k.handle_right[1],
                     k.back, k.amplitude, k.period])
    return {"extrapolation": fc.extrapolation, "auto_smoothing": fc.auto_smoothing, "keys": keys}


def make_curve(action, index, rng, n, interp, easing, handles, extrapolation, smoothing, cycles, frame_scale=1.0,
               authored=None):
    fc = action.fcurves.new("location", index=index)
    fc.extrapolation = extrapolation
    fc.auto_smoothing = smoothing
    frames, values = random_keys(rng, n, frame_scale)
    fc.keyframe_points.add(n)
    for i, k in enumerate(fc.keyframe_points):
        k.co = (frames[i], values[i])
        k.interpolation = interp() if callable(interp) else interp
        k.easing = easing() if callable(easing) else easing
        hl, hr = handles()
        k.handle_left_type = hl
        k.handle_right_type = hr
        # free/aligned handles: random lengths, sometimes longer than the segment, sometimes on the wrong side
        dl = rng.choice([rng.uniform(0.1, 4), rng.uniform(4, 25), rng.uniform(-2, 0)])
        dr = rng.choice([rng.uniform(0.1, 4), rng.uniform(4, 25), rng.uniform(-2, 0)])
        k.handle_left = (frames[i] - dl * frame_scale, values[i] + rng.uniform(-8, 8))
        k.handle_right = (frames[i] + dr * frame_scale, values[i] + rng.uniform(-8, 8))
        k.back = rng.choice([0.0, 1.70158, rng.uniform(0, 4)])
        k.amplitude = rng.choice([0.0, 0.8, rng.uniform(0, 20)])
        k.period = rng.choice([0.0, 4.1, rng.uniform(0.5, 10)])
        k.select_control_point = False
        k.select_left_handle = False
        k.select_right_handle = False
    if cycles is not None:
        m = fc.modifiers.new("CYCLES")
        m.mode_before, m.mode_after, m.cycles_before, m.cycles_after = cycles
    if authored is not None:
        authored.append(authored_state(fc))
    fc.update()
    return fc, frames


def sample_frames(rng, frames, span_out):
    lo, hi = frames[0], frames[-1]
    width = max(hi - lo, 1.0)
    out = []
    for _ in range(40):
        out.append(rng.uniform(lo, hi))
    for _ in range(12):
        out.append(rng.uniform(lo - span_out * width, lo))
        out.append(rng.uniform(hi, hi + span_out * width))
    for x in frames:
        out += [x, x + 5e-5, x - 5e-5, x + 2e-4, x - 2e-4, x + 0.5, x - 0.5]
    for x in range(int(lo) - 3, int(hi) + 4):
        out.append(float(x))
    return [f32(x) for x in out]


STRESS_INTERPOLATIONS = ["BEZIER"] * 4 + EASINGS + ["LINEAR", "CONSTANT"]
EASING_DIRECTIONS = ["AUTO", "EASE_IN", "EASE_OUT", "EASE_IN_OUT"]


def stress_curves(rng, action, count, variant, authored=None):
    """COUNT random mixed-handle curves (see the module text); yields (fcurve, frames to sample)."""
    def handles():
        if "aligned" in variant:
            pair = ["ALIGNED", rng.choice(HANDLES)]
            rng.shuffle(pair)
            return tuple(pair)
        return (rng.choice(HANDLES), rng.choice(HANDLES))

    span_out = 5.0 if "far" in variant else 0.5
    for i in range(count):
        fc, _ = make_curve(action, i, rng, rng.randint(2, 7), interp=lambda: rng.choice(STRESS_INTERPOLATIONS),
                           easing=lambda: rng.choice(EASING_DIRECTIONS), handles=handles,
                           extrapolation=rng.choice(["CONSTANT", "LINEAR"]),
                           smoothing=rng.choice(["NONE", "CONT_ACCEL"]), cycles=None, authored=authored)
        if "sel" in variant:
            for k in fc.keyframe_points:
                k.select_control_point = rng.random() < 0.5
                k.select_left_handle = rng.random() < 0.5
                k.select_right_handle = rng.random() < 0.5
            fc.update()
        yield fc, sample_frames(rng, [k.co[0] for k in fc.keyframe_points], span_out)


def main_stress(outdir, seed, count, variant):
    rng = random.Random(seed)
    action = bpy.data.actions.new("stress")
    tracks, reference = [], {}
    for i, (fc, xs) in enumerate(stress_curves(rng, action, count, variant)):
        name = "case%05d" % i
        tracks.append(export_fcurves.fcurve_to_track(fc, name))
        reference[name] = {"group": "random mixed handles and easings (%s)" % (variant or "plain"), "frames": xs,
                           "values": [fc.evaluate(x) for x in xs]}
    os.makedirs(outdir, exist_ok=True)
    with open(os.path.join(outdir, "scene.json"), "w") as f:
        json.dump({"inbetween": 1, "fps": 24, "range": [1, 100], "tracks": tracks}, f)
    with open(os.path.join(outdir, "reference.json"), "w") as f:
        json.dump(reference, f)
    print("agreement_cases: %d stress curves (%s) written to %s" % (count, variant or "plain", outdir))


def main(outdir, seed):
    rng = random.Random(seed)
    action = bpy.data.actions.new("agreement")
    cases = []  # (group, fcurve, frames, span_out)
    idx = [0]

    def add(group, count, n=None, **kw):
        for _ in range(count):
            fc, frames = make_curve(action, idx[0], rng, n or rng.randint(2, 7), **kw)
            idx[0] += 1
            cases.append((group, fc, frames, 2.0 if fc.modifiers else 0.5))

    both = lambda h: (lambda: (h, h))
    any_handles = lambda: (rng.choice(HANDLES), rng.choice(HANDLES))
    ext = lambda: rng.choice(["CONSTANT", "LINEAR"])
    smooth = lambda: rng.choice(["NONE", "CONT_ACCEL"])
    for interp in ["CONSTANT", "LINEAR"]:
        add(interp.lower(), 6, interp=interp, easing="AUTO", handles=any_handles, extrapolation="LINEAR",
            smoothing="NONE", cycles=None)
    for h in HANDLES:
        for sm in ["NONE", "CONT_ACCEL"]:
            for ex in ["CONSTANT", "LINEAR"]:
                add("bezier %s smoothing=%s extrapolation=%s" % (h.lower(), sm.lower(), ex.lower()), 4,
                    interp="BEZIER", easing="AUTO", handles=both(h), extrapolation=ex, smoothing=sm, cycles=None)
    for sm in ["NONE", "CONT_ACCEL"]:
        add("bezier mixed handles smoothing=%s" % sm.lower(), 12, interp="BEZIER", easing="AUTO",
            handles=any_handles, extrapolation=ext(), smoothing=sm, cycles=None)
    for e in EASINGS:
        for easing in ["AUTO", "EASE_IN", "EASE_OUT", "EASE_IN_OUT"]:
            add("%s %s" % (e.lower(), easing.lower()), 4, interp=e, easing=easing, handles=any_handles,
                extrapolation="LINEAR", smoothing="NONE", cycles=None)
    for mb in CYCLE_MODES:
        for ma in CYCLE_MODES:
            counts = (rng.choice([0, 0, 1, 2, 3]), rng.choice([0, 0, 1, 2, 3]))
            add("cycles before=%s after=%s" % (mb.lower(), ma.lower()), 3,
                interp=lambda: rng.choice(["BEZIER", "BEZIER", "LINEAR", "CONSTANT", "SINE"]), easing="AUTO",
                handles=lambda: rng.choice([("AUTO_CLAMPED", "AUTO_CLAMPED"), ("AUTO", "AUTO"), ("FREE", "FREE"),
                                             ("VECTOR", "AUTO")]),
                extrapolation=ext(), smoothing=smooth(), cycles=(mb, ma) + counts)
    add("single key", 4, n=1, interp=lambda: rng.choice(["BEZIER", "LINEAR", "CONSTANT"]), easing="AUTO",
        handles=any_handles, extrapolation="LINEAR", smoothing="NONE", cycles=None)
    add("large frames (x1000)", 6, interp="BEZIER", easing="AUTO", handles=any_handles, extrapolation=ext(),
        smoothing=smooth(), cycles=None, frame_scale=1000.0)

    tracks, reference = [], {}
    for i, (group, fc, frames, span_out) in enumerate(cases):
        name = "case%03d" % i
        tracks.append(export_fcurves.fcurve_to_track(fc, name))
        xs = sample_frames(rng, [k.co[0] for k in fc.keyframe_points], span_out)
        reference[name] = {"group": group, "frames": xs, "values": [fc.evaluate(x) for x in xs]}
    # The command-line path of the exporter on a saved .blend: an animated object, saved, reloaded
    # and exported by export_fcurves.py's main(), with Blender's values for its curves.
    obj = bpy.data.objects.new("Animated", None)
    bpy.context.scene.collection.objects.link(obj)
    for f, loc in [(1, (0, 0, 0)), (12, (2, -1, 3)), (30, (5, 4, 1))]:
        obj.location = loc
        obj.keyframe_insert("location", frame=f)
    obj.rotation_mode = "QUATERNION"
    obj.rotation_quaternion = (1, 0, 0, 0)
    obj.keyframe_insert("rotation_quaternion", frame=1)
    obj.rotation_quaternion = (0.5, 0.5, 0.5, 0.5)
    obj.keyframe_insert("rotation_quaternion", frame=20)
    blend = os.path.join(outdir, "saved.blend")
    os.makedirs(outdir, exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    bpy.ops.wm.open_mainfile(filepath=blend)
    export_fcurves.main(["-o", os.path.join(outdir, "exported.json")])
    obj = bpy.data.objects["Animated"]
    for fc in obj.animation_data.action.fcurves:
        name = export_fcurves.curve_name(obj.name, fc)
        xs = [f32(x * 0.37) for x in range(-20, 120)]
        reference[name] = {"group": "exported from a saved .blend", "frames": xs, "values": [fc.evaluate(x) for x in xs]}

    scene = {"inbetween": 1, "fps": 24, "range": [1, 100], "tracks": tracks}
    os.makedirs(outdir, exist_ok=True)
    with open(os.path.join(outdir, "scene.json"), "w") as f:
        json.dump(scene, f)
    with open(os.path.join(outdir, "reference.json"), "w") as f:
        json.dump(reference, f)
    print("agreement_cases: %d curves written to %s" % (len(cases), outdir))


if __name__ == "__main__":
    args = sys.argv[sys.argv.index("--") + 1:]
    if "--stress" in args:
        at = args.index("--stress")
        main_stress(args[0], int(args[1]), int(args[at + 1]), args[at + 2] if len(args) > at + 2 else "")
    else:
        main(args[0], int(args[1]) if len(args) > 1 else 1)
