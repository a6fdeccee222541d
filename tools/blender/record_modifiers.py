"""Recorded Blender reference values for F-curve modifiers: tests/data/blender/fmodifiers-blender-3.4.1.json.

Run inside Blender (Debian package blender, 3.4.1):

    blender -b --factory-startup --python-exit-code 1 --python tools/blender/record_modifiers.py -- \\
        tests/data/blender/fmodifiers-blender-3.4.1.json [SEED]

Builds seeded random F-curves (2-6 keys, random interpolation, handles, extrapolation, smoothing; as
agreement_cases.py) and gives each a random modifier stack: every modifier type alone (Generator expanded
and factorised, additive or not; Built-in Function of every kind, with tan poles, sqrt/ln of negatives
and sinc at 0 among the frames; Envelope with 0-4 control points; Cycles in every mode with counts;
Noise in every blend type and depth; Limits; Stepped with start/end), random stacks of 2-3, and
Cycles below the top of the stack (Blender refuses to add it there: it is pasted there with the Graph
Editor's copy/paste operators, as a user gets it there by dragging).  Each modifier is muted with
probability 0.1, has an influence with probability 0.4 and a restricted range with blend in/out with
probability 0.4 (not Stepped: its restricted range cannot be read through Python, export_fcurves.py).
Every curve is exported with export_fcurves.fcurve_to_track before it is first evaluated (a Cycles
modifier below the top disables itself on its first evaluation), evaluated once at every frame (so
that it has), then recorded: Blender's FCurve.evaluate(frame) at random fractional frames inside and up
to three key spans outside the keys, at the modifiers' range ends and envelope points, and at whole
frames.  Format as record_reference.py's (float32 numbers, one curve per line);
tests/tracks/fmodifier_blender_test.cpp compares inbetween against it.
"""

import importlib.util
import math
import os
import random
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))


def _load(name):
    spec = importlib.util.spec_from_file_location(name, os.path.join(HERE, name + ".py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


agreement = _load("agreement_cases")
export_fcurves = agreement.export_fcurves

TYPES = ["GENERATOR", "FNGENERATOR", "ENVELOPE", "CYCLES", "NOISE", "LIMITS", "STEPPED"]
FUNCTIONS = ["SIN", "COS", "TAN", "SQRT", "LN", "SINC"]


# float32 rounding and the shortest text that reads back to the same float32: record_reference.py's.
reference = _load("record_reference")
f32, short, shorten = reference.f32, reference.short, reference.shorten


def set_common(rng, m, lo, hi):
    """Mute, influence and restricted range at random; returns frames of interest (range ends)."""
    special = []
    if rng.random() < 0.1:
        m.mute = True
    if rng.random() < 0.4:
        m.use_influence = True
        m.influence = rng.choice([rng.uniform(0, 1), 0.5, 1.0, 0.0])
    if m.type != "STEPPED" and rng.random() < 0.4:
        m.use_restricted_range = True
        width = max(hi - lo, 1.0)
        a = rng.uniform(lo - width, hi)
        b = a + rng.uniform(0.5, 2 * width)
        m.frame_start = a
        m.frame_end = b
        if rng.random() < 0.6:
            m.blend_in = rng.uniform(0, (b - a) / 2)
        if rng.random() < 0.6:
            m.blend_out = rng.uniform(0, (b - a) / 2)
        special += [m.frame_start, m.frame_end, m.frame_start + m.blend_in, m.frame_end - m.blend_out]
    return special


def set_params(rng, m, lo, hi, values):
    """The type's own settings at random; returns frames of interest."""
    special = []
    width = max(hi - lo, 1.0)
    vlo, vhi = min(values), max(values)
    if m.type == "GENERATOR":
        m.mode = rng.choice(["POLYNOMIAL", "POLYNOMIAL_FACTORISED"])
        m.poly_order = rng.randint(1, 3)
        m.use_additive = rng.random() < 0.5
        for i in range(len(m.coefficients)):
            m.coefficients[i] = rng.uniform(-2, 2) * (0.2 ** (i // (2 if m.mode == "POLYNOMIAL_FACTORISED" else 1)))
    elif m.type == "FNGENERATOR":
        m.function_type = rng.choice(FUNCTIONS)
        m.use_additive = rng.random() < 0.4
        m.amplitude = rng.choice([1.0, rng.uniform(-3, 3)])
        m.value_offset = rng.choice([0.0, rng.uniform(-2, 2)])
        if m.function_type == "TAN" and rng.random() < 0.5:
            # Poles at odd whole frames: arg = pi/2 * frame.
            m.phase_multiplier = math.pi / 2
            m.phase_offset = 0.0
            special += [float(f) for f in range(int(lo) - 3, int(hi) + 4) if f % 2]
        else:
            m.phase_multiplier = rng.choice([1.0, rng.uniform(-2, 2), 0.25])
            m.phase_offset = rng.choice([0.0, rng.uniform(-5, 5)])
            if m.phase_multiplier != 0:
                # sinc at 0, sqrt at 0, ln at 1: the frames where the argument crosses them.
                for target in (0.0, 1.0):
                    special.append((target - m.phase_offset) / m.phase_multiplier)
    elif m.type == "ENVELOPE":
        m.reference_value = rng.uniform(vlo, vhi)
        m.default_min = rng.uniform(-3, -0.5)
        m.default_max = rng.uniform(0.5, 3)
        for _ in range(rng.choice([0, 1, 2, 3, 4])):
            f = round(rng.uniform(lo - width / 2, hi + width / 2), 2)
            p = m.control_points.add(f)
            p.min = rng.uniform(-4, 0)
            p.max = rng.uniform(0, 4)
        special += [p.frame for p in m.control_points]
    elif m.type == "CYCLES":
        m.mode_before = rng.choice(agreement.CYCLE_MODES)
        m.mode_after = rng.choice(agreement.CYCLE_MODES)
        m.cycles_before = rng.choice([0, 0, 1, 2, 3])
        m.cycles_after = rng.choice([0, 0, 1, 2, 3])
    elif m.type == "NOISE":
        m.blend_type = rng.choice(["REPLACE", "ADD", "SUBTRACT", "MULTIPLY"])
        m.scale = rng.choice([1.0, rng.uniform(0.3, 10)])
        m.strength = rng.choice([1.0, rng.uniform(0, 4)])
        m.phase = rng.choice([1.0, rng.uniform(-5, 5)])
        m.offset = rng.choice([0.0, rng.uniform(-10, 10)])
        m.depth = rng.choice([0, 0, 1, 2, 3])
    elif m.type == "LIMITS":
        m.use_min_x, m.use_max_x = rng.random() < 0.5, rng.random() < 0.5
        m.use_min_y, m.use_max_y = rng.random() < 0.5, rng.random() < 0.5
        m.min_x = rng.uniform(lo - width / 2, (lo + hi) / 2)
        m.max_x = rng.uniform((lo + hi) / 2, hi + width / 2)
        m.min_y = rng.uniform(vlo - 1, (vlo + vhi) / 2)
        m.max_y = rng.uniform((vlo + vhi) / 2, vhi + 1)
        special += [m.min_x, m.max_x]
    elif m.type == "STEPPED":
        m.frame_step = rng.choice([2.0, float(rng.randint(1, 5)), rng.uniform(0.3, 5)])
        m.frame_offset = rng.choice([0.0, rng.uniform(-3, 3)])
        if rng.random() < 0.4:
            m.use_frame_start = True
            m.frame_start = rng.uniform(lo - width / 2, hi)
            special.append(m.frame_start)
        if rng.random() < 0.4:
            m.use_frame_end = True
            m.frame_end = rng.uniform(lo, hi + width / 2)
            special.append(m.frame_end)
    return special


def new_curve(rng, action, index):
    fc, frames = agreement.make_curve(
        action, index, rng, rng.randint(2, 6),
        interp=lambda: rng.choice(["BEZIER", "BEZIER", "LINEAR", "CONSTANT", "SINE"]), easing="AUTO",
        handles=lambda: rng.choice([("AUTO_CLAMPED", "AUTO_CLAMPED"), ("AUTO", "AUTO"), ("FREE", "FREE"),
                                     ("VECTOR", "AUTO")]),
        extrapolation=rng.choice(["CONSTANT", "LINEAR"]), smoothing=rng.choice(["NONE", "CONT_ACCEL"]), cycles=None)
    return fc, frames


def add_stack(rng, fc, types):
    """Adds modifiers of `types` (Cycles only first) with random settings; returns frames of interest."""
    xs = [k.co[0] for k in fc.keyframe_points]
    ys = [k.co[1] for k in fc.keyframe_points]
    special = []
    for t in types:
        m = fc.modifiers.new(t)
        assert m is not None, t
        special += set_params(rng, m, xs[0], xs[-1], ys)
        special += set_common(rng, m, xs[0], xs[-1])
    fc.update()
    return special


def graph_context():
    win = bpy.context.window_manager.windows[0]
    area = win.screen.areas[0]
    area.type = "GRAPH_EDITOR"
    region = [r for r in area.regions if r.type == "WINDOW"][0]
    return dict(window=win, area=area, region=region)


def cycles_below_top(rng, index, ctx):
    """A curve whose stack has Cycles below the top: [X, Cycles, X'] (X' a copy of X) made by copying
    [Cycles, X], removing the Cycles and pasting the copy at the end, as the Graph Editor does."""
    for ob in bpy.context.scene.objects:
        ob.select_set(False)
    ob = bpy.data.objects.new("below%03d" % index, None)
    bpy.context.scene.collection.objects.link(ob)
    ob.animation_data_create()
    action = bpy.data.actions.new("below%03d" % index)
    ob.animation_data.action = action
    ob.select_set(True)
    bpy.context.view_layer.objects.active = ob
    fc, _ = new_curve(rng, action, 0)
    fc.select = True
    special = add_stack(rng, fc, ["CYCLES", rng.choice([t for t in TYPES if t != "CYCLES"])])
    with bpy.context.temp_override(**ctx):
        fc.modifiers[0].active = True
        assert bpy.ops.graph.fmodifier_copy() == {"FINISHED"}
        fc.modifiers.remove(fc.modifiers[0])
        assert bpy.ops.graph.fmodifier_paste(only_active=False, replace=False) == {"FINISHED"}
    fc.update()
    ob.select_set(False)
    assert [m.type for m in fc.modifiers][1] == "CYCLES", [m.type for m in fc.modifiers]
    return fc, special


def frames_for(rng, fc, special):
    xs = [k.co[0] for k in fc.keyframe_points]
    lo, hi = xs[0], xs[-1]
    width = max(hi - lo, 1.0)
    out = [rng.uniform(lo, hi) for _ in range(20)]
    out += [rng.uniform(lo - 3 * width, lo) for _ in range(8)]
    out += [rng.uniform(hi, hi + 3 * width) for _ in range(8)]
    out += [float(f) for f in range(int(lo) - 2, int(hi) + 3)][:12]
    for s in special:
        out += [s, s + 1e-3, s - 1e-3]
    out += xs
    return [f32(x) for x in out if math.isfinite(x) and abs(x) < 1e6]


def main(out_path, seed):
    rng = random.Random(seed)
    action = bpy.data.actions.new("modifiers")
    ctx = graph_context()
    cases = []  # (group, fcurve, special frames)
    idx = [0]

    def add(group, types_fn, count):
        for _ in range(count):
            fc, _ = new_curve(rng, action, idx[0])
            idx[0] += 1
            special = add_stack(rng, fc, types_fn())
            cases.append((group, fc, special))

    for t in TYPES:
        add("single " + t.lower(), lambda t=t: [t], 12 if t in ("FNGENERATOR", "GENERATOR", "CYCLES") else 8)
    add("stack of 2", lambda: rng.sample([t for t in TYPES if t != "CYCLES"], 2), 16)
    add("stack of 3", lambda: rng.sample([t for t in TYPES if t != "CYCLES"], 3), 16)
    add("cycles first, then 1-2 more",
        lambda: ["CYCLES"] + rng.sample([t for t in TYPES if t != "CYCLES"], rng.randint(1, 2)), 16)
    for i in range(8):
        fc, special = cycles_below_top(rng, i, ctx)
        cases.append(("cycles below the top", fc, special))

    curves = []
    for i, (group, fc, special) in enumerate(cases):
        track = shorten(export_fcurves.fcurve_to_track(fc, "case%03d" % i))
        xs = frames_for(rng, fc, special)
        for x in xs:  # first evaluation: a Cycles modifier below the top disables itself
            fc.evaluate(x)
        if any(m.type == "CYCLES" and pos > 0 and m.is_valid and not m.mute for pos, m in enumerate(fc.modifiers)):
            # A Cycles modifier below the top that never ran (its range missed every frame) has not
            # disabled itself yet; Blender's value step would read uninitialised storage: left out.
            continue
        curves.append({"group": group, "track": track, "frames": [short(x) for x in xs],
                       "values": [short(fc.evaluate(x)) for x in xs]})

    reference.write_recording(out_path, "record_modifiers", seed, curves)


if __name__ == "__main__":
    args = sys.argv[sys.argv.index("--") + 1:]
    main(args[0], int(args[1]) if len(args) > 1 else 20261128)
