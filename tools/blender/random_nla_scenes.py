"""Seeded random Blender scenes with actions, F-curve modifiers and NLA, and Blender's matrix_world.

Run inside Blender 3.4:

    blender -b --factory-startup --python tools/blender/random_nla_scenes.py -- \
        --seed 23 --count 12 --out tests/data/blender_nla

For each scene K it builds a few objects (a hierarchy root -> mid -> leaf with parent inverse
matrices, and a free object; every rotation mode), actions with random keys (bezier, linear,
constant; constant and linear extrapolation; F-curve modifiers of every type in the second half of
the scenes), NLA tracks with strips of every blend type and extrapolation, repeat / scale /
reverse, blend in / out, auto blend, animated influence and strip time, muted and solo tracks,
muted strips, and an active action on top with its own blend type, influence and extrapolation.
It saves the scene as a .blend in a temporary folder, opens it again, exports it with
export_scene.py's export_scene_doc (the same function the command line uses) to sceneK.json, and
records Blender's matrix_world of every object at fractional frames inside and outside the strips
(strip ends, blend ends and key frames exactly, and just around them) to sceneK.world.json:

    {"blender": "3.4.1", "seed": S, "scene": K, "frames": [f, ...],
     "objects": {"name": {"translation": [[x, y, z], ...], "rotation": [[w, x, y, z], ...],
                          "scale": [[x, y, z], ...]}}}

Frames are single-precision values (Blender's scene time is cfra + subframe in float); every number
is written as the shortest text of its float32 value, so reading it as a double and rounding to
float gives Blender's value exactly.  rotation is a unit quaternion, translation / rotation / scale
are mathutils' Matrix.decompose() of matrix_world.  No world matrix has shear: every object with
children has uniform scale (its three scale channels are the same curve) and a parent inverse of
uniform scale, so the decomposition reproduces matrix_world and the TRS columns of
`inbetween bake --space world` are comparable; objects with non-uniform scale are leaves.

tests/io/blender_nla_agreement_test.cpp reads both files; `make test` needs no Blender.
"""

import itertools
import json
import math
import os
import random
import sys
import tempfile

import bpy
import mathutils
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import export_scene  # noqa: E402

ROT_MODES = ["QUATERNION", "AXIS_ANGLE", "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"]
BLENDS = ["REPLACE", "COMBINE", "ADD", "SUBTRACT", "MULTIPLY"]
EXTRAPOLATIONS = ["HOLD", "HOLD_FORWARD", "NOTHING"]
INTERPOLATIONS = ["BEZIER", "LINEAR", "CONSTANT"]
HANDLES = ["AUTO_CLAMPED", "AUTO", "VECTOR"]
MODIFIERS = ["GENERATOR", "FNGENERATOR", "ENVELOPE", "CYCLES", "NOISE", "LIMITS", "STEPPED"]


def f32(x):
    """The shortest text of x's float32 value, as a Python float (json writes it back the same)."""
    return float(str(np.float32(x)))


def rotation_path(mode):
    return {"QUATERNION": "rotation_quaternion", "AXIS_ANGLE": "rotation_axis_angle"}.get(mode, "rotation_euler")


# ---------------------------------------------------------------------------------------------
# Random keys and modifiers


def key_frames(rng):
    n = rng.randint(2, 4)
    frame = rng.uniform(0, 6)
    frames = []
    for _ in range(n):
        frames.append(round(frame) if rng.random() < 0.5 else round(frame, 3))
        frame += rng.uniform(2, 10)
    return frames


def key_values(rng, path, n, scale_like):
    """n key values [component][key] of a property."""
    if path == "location":
        return [[rng.uniform(-3, 3) for _ in range(n)] for _ in range(3)]
    if path == "rotation_euler":
        return [[rng.uniform(-2, 2) for _ in range(n)] for _ in range(3)]
    if path == "scale":
        if scale_like == "uniform":
            row = [rng.uniform(0.6, 1.6) for _ in range(n)]
            return [row, list(row), list(row)]
        return [[rng.uniform(0.6, 1.6) for _ in range(n)] for _ in range(3)]
    if path == "rotation_quaternion":  # rotations within 70 degrees of the identity: w > 0.8
        cols = []
        for _ in range(n):
            axis = mathutils.Vector((rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)))
            axis = axis.normalized() if axis.length > 1e-3 else mathutils.Vector((0, 0, 1))
            q = mathutils.Quaternion(axis, rng.uniform(-1.2, 1.2))
            cols.append((q.w, q.x, q.y, q.z))
        return [[c[i] for c in cols] for i in range(4)]
    if path == "rotation_axis_angle":
        return [[rng.uniform(-2, 2) for _ in range(n)], [rng.uniform(0.6, 1.2) for _ in range(n)],
                [rng.uniform(-0.5, 0.5) for _ in range(n)], [rng.uniform(-0.5, 0.5) for _ in range(n)]]
    raise ValueError(path)


def add_modifier(rng, fc, kind, safe):
    """Adds one modifier of `kind` with random settings; `safe` keeps a scale channel positive."""
    m = fc.modifiers.new(kind)
    if m is None:
        return None
    if kind == "GENERATOR":
        m.mode = rng.choice(["POLYNOMIAL", "POLYNOMIAL_FACTORISED"])
        m.poly_order = rng.randint(1, 2)
        m.use_additive = rng.random() < 0.6
        coefficients = [rng.uniform(-0.5, 0.5), rng.uniform(-0.05, 0.05), rng.uniform(-0.002, 0.002)]
        if m.mode == "POLYNOMIAL_FACTORISED":
            coefficients = [rng.uniform(0.05, 0.3), rng.uniform(-10, 10), rng.uniform(0.02, 0.1), rng.uniform(-20, 0)]
        for i in range(len(m.coefficients)):
            m.coefficients[i] = coefficients[i % len(coefficients)]
    elif kind == "FNGENERATOR":
        m.function_type = rng.choice(["SIN", "COS", "SINC", "SQRT", "LN", "TAN"])
        m.amplitude = rng.uniform(-1, 1) if m.function_type != "TAN" else rng.uniform(-0.1, 0.1)
        m.phase_multiplier = rng.uniform(0.05, 0.4)
        m.phase_offset = rng.uniform(-1, 1) if m.function_type not in ("SQRT", "LN") else rng.uniform(20, 40)
        m.value_offset = rng.uniform(-0.5, 0.5)
        m.use_additive = rng.random() < 0.7
    elif kind == "ENVELOPE":
        m.reference_value = rng.uniform(-0.5, 0.5)
        m.default_min = rng.uniform(-1.5, -0.5)
        m.default_max = rng.uniform(0.5, 1.5)
        frame = rng.uniform(-5, 10)
        for _ in range(rng.randint(1, 3)):
            p = m.control_points.add(round(frame, 2))
            p.min = rng.uniform(-2, 0)
            p.max = rng.uniform(0, 2)
            frame += rng.uniform(3, 15)
    elif kind == "CYCLES":
        modes = ["NONE", "REPEAT", "MIRROR"] + ([] if safe else ["REPEAT_OFFSET"])
        m.mode_before = rng.choice(modes)
        m.mode_after = rng.choice(modes)
        m.cycles_before = rng.choice([0, 0, 1, 2])
        m.cycles_after = rng.choice([0, 0, 1, 3])
    elif kind == "NOISE":
        m.blend_type = rng.choice(["REPLACE", "ADD"] if safe else ["REPLACE", "ADD", "SUBTRACT", "MULTIPLY"])
        m.scale = rng.uniform(1, 10)
        m.strength = rng.uniform(0.05, 0.3) if safe else rng.uniform(0.1, 1.5)
        m.phase = rng.uniform(0.5, 5)
        m.offset = rng.uniform(-5, 5)
        m.depth = rng.randint(0, 2)
    elif kind == "LIMITS":
        m.use_min_x = rng.random() < 0.4
        m.min_x = rng.uniform(-5, 5)
        m.use_max_x = rng.random() < 0.4
        m.max_x = m.min_x + rng.uniform(5, 20)
        m.use_min_y = safe or rng.random() < 0.5
        m.min_y = rng.uniform(0.3, 0.8) if safe else rng.uniform(-2, 0)
        m.use_max_y = rng.random() < 0.5
        m.max_y = rng.uniform(1, 2) if safe else rng.uniform(0, 2)
    elif kind == "STEPPED":
        m.frame_step = rng.choice([2.0, 3.0, rng.uniform(1.5, 4)])
        m.frame_offset = rng.choice([0.0, rng.uniform(0, 2)])
        m.use_frame_start = rng.random() < 0.3
        m.frame_start = rng.uniform(0, 10)
        m.use_frame_end = rng.random() < 0.3
        m.frame_end = m.frame_start + rng.uniform(5, 20) if m.use_frame_start else rng.uniform(10, 30)
    if rng.random() < 0.3:
        m.use_influence = True
        m.influence = rng.uniform(0.2, 1)
    if kind != "STEPPED" and rng.random() < 0.3:  # a Stepped modifier's range is not readable (export_scene.py)
        m.use_restricted_range = True
        start = rng.uniform(-2, 15)
        m.frame_start = start
        m.frame_end = start + rng.uniform(4, 20)
        m.blend_in = rng.uniform(0, 2)
        m.blend_out = rng.uniform(0, 2)
    if rng.random() < 0.08:
        m.mute = True
    return m


def modifier_plan(rng, path):
    """The modifier kinds of one property's channels (the same for every component)."""
    safe = path == "scale"
    kinds = ["CYCLES", "STEPPED", "LIMITS", "NOISE"] if safe else MODIFIERS
    plan = []
    if rng.random() < 0.55:
        plan = rng.sample(kinds, rng.randint(1, 2))
        if "CYCLES" in plan:  # Blender accepts Cycles only first in the stack
            plan.remove("CYCLES")
            plan.insert(0, "CYCLES")
    return plan


def make_action(rng, name, obj_name, paths, rot_mode, scale_like, with_modifiers):
    action = bpy.data.actions.new(name)
    for path in paths:
        frames = key_frames(rng)
        values = key_values(rng, path, len(frames), scale_like)
        plan = modifier_plan(rng, path) if with_modifiers else []
        settings_seed = rng.randrange(1 << 30)
        interp = [rng.choice(INTERPOLATIONS) for _ in frames]
        handles = [rng.choice(HANDLES) for _ in frames]
        extrap = "CONSTANT" if path == "scale" or rng.random() < 0.6 else "LINEAR"
        smoothing = rng.choice(["NONE", "CONT_ACCEL"])
        components = list(range(len(values)))
        if not (path == "scale" and scale_like == "uniform") and rng.random() < 0.3:
            # some elements only: a strip blends the elements its action keys and leaves the others
            components = sorted(rng.sample(components, rng.randint(1, len(components) - 1)))
        for index in components:
            fc = action.fcurves.new(path, index=index, action_group=obj_name)
            for i, frame in enumerate(frames):
                k = fc.keyframe_points.insert(frame, values[index][i], options={"FAST"})
                k.interpolation = interp[i]
                k.handle_left_type = handles[i]
                k.handle_right_type = handles[i]
            fc.extrapolation = extrap
            fc.auto_smoothing = smoothing
            fc.update()
            # the same modifier settings on every component (a uniform scale stays uniform)
            mrng = random.Random(settings_seed if scale_like == "uniform" else settings_seed + index)
            for kind in plan:
                add_modifier(mrng, fc, kind, path == "scale")
    return action


# ---------------------------------------------------------------------------------------------
# Objects and NLA


def random_uniform_matrix(rng):
    q = mathutils.Quaternion(mathutils.Vector((rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))).normalized(),
                             rng.uniform(-3, 3))
    s = rng.uniform(0.5, 2)
    t = mathutils.Vector((rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)))
    return mathutils.Matrix.LocRotScale(t, q, (s, s, s))


def make_object(rng, name, parent, uniform):
    obj = bpy.data.objects.new(name, None)
    bpy.context.scene.collection.objects.link(obj)
    obj.rotation_mode = rng.choice(ROT_MODES)
    obj.location = (rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2))
    obj.rotation_euler = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))
    q = mathutils.Euler(obj.rotation_euler).to_quaternion()
    obj.rotation_quaternion = q
    axis, angle = q.to_axis_angle()
    obj.rotation_axis_angle = (angle, axis.x, axis.y, axis.z)
    s = rng.uniform(0.7, 1.4)
    obj.scale = (s, s, s) if uniform else (rng.uniform(0.6, 1.5), rng.uniform(0.6, 1.5), rng.uniform(0.6, 1.5))
    if parent is not None:
        obj.parent = parent
        obj.matrix_parent_inverse = random_uniform_matrix(rng) if rng.random() < 0.8 else mathutils.Matrix.Identity(4)
    return obj


def make_strip(rng, obj, track, start, actions, sub_action, names):
    blend = rng.choice(BLENDS)
    action = sub_action if blend == "SUBTRACT" else rng.choice(actions)
    strip = track.strips.new(names.pop(), int(math.floor(start)), action)
    strip.frame_start_ui = start
    lo, hi = action.frame_range
    afs = lo + rng.choice([0.0, rng.uniform(0, (hi - lo) / 3)])
    afe = hi - rng.choice([0.0, rng.uniform(0, (hi - lo) / 3)])
    strip.action_frame_end = max(afe, afs + 1)
    strip.action_frame_start = afs
    if rng.random() < 0.4:
        strip.scale = rng.uniform(0.5, 2)
    if rng.random() < 0.4:
        strip.repeat = rng.uniform(0.6, 2.5)
    strip.use_reverse = rng.random() < 0.2
    strip.blend_type = blend
    strip.extrapolation = rng.choice(EXTRAPOLATIONS)
    length = strip.frame_end - strip.frame_start
    if rng.random() < 0.5:
        strip.blend_in = rng.uniform(0, length / 2)
        strip.blend_out = rng.uniform(0, length / 2)
    strip.use_auto_blend = rng.random() < 0.15
    r = rng.random()
    if r < 0.35:  # keyed influence
        strip.use_animated_influence = True
        fc = strip.fcurves.find("influence")
        for k in list(fc.keyframe_points):
            fc.keyframe_points.remove(k)
        frame = strip.frame_start + rng.uniform(-3, 3)
        for _ in range(rng.randint(1, 3)):
            k = fc.keyframe_points.insert(frame, rng.uniform(0, 1), options={"FAST"})
            k.interpolation = rng.choice(INTERPOLATIONS)
            frame += rng.uniform(2, max(3, length / 2))
        fc.update()
    if rng.random() < 0.2:  # keyed strip time
        strip.use_animated_time = True
        fc = strip.fcurves.find("strip_time")
        for k in list(fc.keyframe_points):
            fc.keyframe_points.remove(k)
        a0, a1 = strip.action_frame_start, strip.action_frame_end
        k = fc.keyframe_points.insert(strip.frame_start, a0 + rng.uniform(0, 2), options={"FAST"})
        k = fc.keyframe_points.insert(strip.frame_end, a1 + rng.uniform(-2, 6), options={"FAST"})
        k.interpolation = rng.choice(INTERPOLATIONS)
        fc.update()
        strip.use_animated_time_cyclic = rng.random() < 0.4
    strip.mute = rng.random() < 0.1
    return strip


def build_scene(rng, with_modifiers, k):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps = rng.choice([24, 25, 30])
    scene.render.fps_base = rng.choice([1.0, 1.0, 1.001])
    scene.frame_start, scene.frame_end = 1, 60
    root = make_object(rng, "root", None, True)
    mid = make_object(rng, "mid", root, True)
    leaf = make_object(rng, "leaf", mid, False)
    free = make_object(rng, "free", None, False)
    names = ["strip%02d" % i for i in range(40, 0, -1)]
    for i, obj in enumerate((root, mid, leaf, free)):
        uniform = "uniform" if obj in (root, mid) else "any"
        rpath = rotation_path(obj.rotation_mode)
        full = make_action(rng, obj.name + "_full", obj.name, ["location", rpath, "scale"], obj.rotation_mode, uniform, with_modifiers)
        move = make_action(rng, obj.name + "_move", obj.name, ["location", rpath], obj.rotation_mode, uniform, with_modifiers)
        sub_paths = ["location"] + ([rpath] if rpath == "rotation_euler" else [])
        sub = make_action(rng, obj.name + "_sub", obj.name, sub_paths, obj.rotation_mode, uniform, with_modifiers)
        actions = [full, move, sub]
        ad = obj.animation_data_create()
        for t in range(rng.randint(1, 3)):
            track = ad.nla_tracks.new()
            track.name = "%s_track%d" % (obj.name, t)
            start = rng.uniform(-8, 30)
            for _ in range(rng.randint(1, 2)):
                try:
                    strip = make_strip(rng, obj, track, start, actions, sub, names)
                except RuntimeError:
                    break
                start = strip.frame_end + rng.uniform(1, 12)
            track.mute = rng.random() < 0.12
        if rng.random() < 0.12:
            rng.choice(list(ad.nla_tracks)).is_solo = True
        if rng.random() < 0.7:  # the active action: every blend type and extrapolation in turn
            blend = BLENDS[(4 * k + i) % len(BLENDS)]
            ad.action = sub if blend == "SUBTRACT" else rng.choice(actions)
            ad.action_blend_type = blend
            ad.action_influence = rng.uniform(0.3, 1)
            ad.action_extrapolation = EXTRAPOLATIONS[(k + i) % len(EXTRAPOLATIONS)]
        ad.use_nla = rng.random() < 0.9
    return scene


# ---------------------------------------------------------------------------------------------
# Frames and recording

KEY_DEFAULTS = {"easing": "auto", "handle_left_type": "auto_clamped", "handle_right_type": "auto_clamped",
                "interpolation": "bezier", "back": f32(1.70158), "amplitude": f32(0.8), "period": f32(4.1)}


def shorten(value, key=None):
    """The exported document with every float as the shortest text of its float32 value (what
    Blender stores) and key members equal to the format's defaults left out: the same scene in
    about half the bytes.  The fps, a double in Blender (fps / fps_base), is kept whole."""
    if isinstance(value, float):
        return value if key == "fps" else f32(value)
    if isinstance(value, list):
        return [shorten(v) for v in value]
    if isinstance(value, dict):
        out = {k: shorten(v, k) for k, v in value.items()}
        if "handle_left" in out and "frame" in out:
            for k, default in KEY_DEFAULTS.items():
                if out.get(k) == default:
                    del out[k]
        return out
    return value



def sample_frames(rng, doc, count):
    """`count` float32 frames: strip and blend ends, key frames, just around them, and random ones."""
    special = set()
    for obj in doc["objects"]:
        for track in obj.get("animation", {}).get("tracks", []):
            for s in track["strips"]:
                special.update([s["frame_start"], s["frame_end"], s["frame_start"] + s["blend_in"], s["frame_end"] - s["blend_out"]])
    for action in doc["actions"]:
        for ch in action["channels"]:
            special.update(k["frame"] for k in ch["keys"])
    special = sorted(special)
    lo, hi = special[0] - 12, special[-1] + 12
    frames = set()
    for f in rng.sample(special, min(len(special), count // 4)):
        frames.add(f32(f))
        frames.add(f32(f + rng.choice([-1e-3, 1e-3, -0.01, 0.01])))
    while len(frames) < count:
        frames.add(f32(rng.choice([round(rng.uniform(lo, hi), 3), rng.uniform(lo, hi), float(rng.randint(int(lo), int(hi)))])))
    return sorted(frames)[:count]


def set_frame(scene, frame):
    """Sets Blender's scene time as near `frame` as Blender can and returns the time it uses
    (a float32 value).  Blender's time is (float)cfra + subframe, the subframe a float in [0, 1)
    (frame_set clamps a negative one to 0), reached through a double cfra + subframe: passing the
    float32 value itself makes every step exact for frames >= 0; a fractional frame below 0 whose
    subframe is not a float32 (e.g. -0.0764...) lands on a neighbouring float32."""
    exact = float(np.float32(frame))
    whole = math.floor(exact)
    scene.frame_set(int(whole), subframe=exact - whole)
    return scene.frame_current_final


def record(scene, frames):
    """Blender's world transforms at `frames` ({object: {translation, rotation, scale}}) and the
    frames Blender evaluated (set_frame: float32 values, the same as `frames` but for some negative
    fractional ones); the world files hold the latter."""
    objects = {obj.name: {"translation": [], "rotation": [], "scale": []} for obj in scene.objects}
    used = []
    for frame in frames:
        used.append(set_frame(scene, frame))
        depsgraph = bpy.context.evaluated_depsgraph_get()
        for obj in scene.objects:
            m = obj.evaluated_get(depsgraph).matrix_world
            t, q, s = m.decompose()
            rec = objects[obj.name]
            rec["translation"].append([f32(v) for v in t])
            rec["rotation"].append([f32(q.w), f32(q.x), f32(q.y), f32(q.z)])
            rec["scale"].append([f32(v) for v in s])
    objects["_frames"] = [f32(f) for f in used]
    return objects


# ---------------------------------------------------------------------------------------------
# --observe: the Blender 3.4 behaviours docs/blender-nla-observations.md reports, each checked on a
# small scene built here (every check prints one "observe:" line with what Blender gave).


def _empty_with_action(name, paths_keys, base=None):
    """An empty with one action: paths_keys = [(path, index, [(frame, value, interpolation)])]."""
    obj = bpy.data.objects.new(name, None)
    bpy.context.scene.collection.objects.link(obj)
    if base is not None:
        obj.location = base
    action = bpy.data.actions.new(name + "_act")
    for path, index, keys in paths_keys:
        fc = action.fcurves.new(path, index=index)
        for frame, value, interp in keys:
            k = fc.keyframe_points.insert(frame, value, options={"FAST"})
            k.interpolation = interp
        fc.update()
    obj.animation_data_create()
    return obj, action


def rotation_angle(a, b):
    """Angle (rad) between rotations a and b, quaternions w, x, y, z: 2 atan2(|v|, |w|) of conj(a) b, in double
    (mathutils' rotation_difference().angle is float32 acos, blind below about 3e-4 rad)."""
    aw, ax, ay, az = (float(v) for v in a)
    bw, bx, by, bz = (float(v) for v in b)
    w = aw * bw + ax * bx + ay * by + az * bz
    x = aw * bx - ax * bw - ay * bz + az * by
    y = aw * by + ax * bz - ay * bw - az * bx
    z = aw * bz - ax * by + ay * bx - az * bw
    return 2 * math.atan2(math.sqrt(x * x + y * y + z * z), abs(w))


def _at(obj, frame):
    set_frame(bpy.context.scene, frame)
    return obj.evaluated_get(bpy.context.evaluated_depsgraph_get())


def observe_float32_strip_time():
    """NLA strip time is float arithmetic: random strips (start, scale) over a constant key at action
    frame 6; at float32 frames around the jump, is Blender's value the curve at the float32 or at
    the double strip time (Blender's nlastrip_get_frame_actionclip formula in both)?"""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    rng = random.Random(6)
    n = differ = agree32 = agree64 = 0
    cases = []
    for i in range(40):
        obj, action = _empty_with_action("t%d" % i, [("location", 0, [(1, 0.0, "CONSTANT"), (6, 1.0, "CONSTANT"), (11, 2.0, "CONSTANT")])])
        strip = obj.animation_data.nla_tracks.new().strips.new("s", 1, action)
        strip.frame_start_ui = rng.uniform(-20, 20)
        strip.scale = rng.uniform(0.3, 3)
        cases.append((obj, action.fcurves[0], strip))
    for obj, fc, strip in cases:
        start, scale, actstart = np.float32(strip.frame_start), np.float32(strip.scale), np.float32(strip.action_frame_start)
        length = np.float32(strip.action_frame_end) - actstart
        # the first float32 action time at which the constant curve shows the key's value (Blender's
        # F-curve snaps to a key within 0.01 frame, BEZT_BINARYSEARCH_THRESH, so it is not 6 itself)
        t = np.float32(5.98)
        while fc.evaluate(float(t)) != 1.0:
            t = np.nextafter(t, np.float32(1e9))
        frame = np.float32(float(start) + (float(t) - float(actstart)) * float(scale))
        for _ in range(10):
            frame = np.nextafter(frame, np.float32(-1e9))
        for _ in range(20):
            f = set_frame(bpy.context.scene, float(frame))  # the time Blender uses
            t32 = actstart + np.float32(np.fmod(np.float32(np.float32(f) - start), np.float32(length * scale))) / scale
            t64 = float(actstart) + math.fmod(f - float(start), float(length) * float(scale)) / float(scale)
            v32, v64 = fc.evaluate(float(t32)), fc.evaluate(t64)
            got = obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).location[0]
            n += 1
            differ += v32 != v64
            agree32 += got == v32
            agree64 += got == v64
            frame = np.nextafter(frame, np.float32(1e9))
    print("observe: float32 strip time: 40 random strips, the 20 float32 frames around each key jump (%d samples): Blender = "
          "the curve at the float32 strip time at %d, at the double strip time at %d; the two times give different values "
          "at %d" % (n, agree32, agree64, differ))


def observe_ulp_step(seed, count):
    """The share of samples of the random scenes that one float32 ulp of frame time moves past the tolerances."""
    moved = total = 0
    for k in range(count):
        rng = random.Random(seed * 1000 + k)
        build_scene(rng, k >= count // 2, k)
        scene = bpy.context.scene
        doc = export_scene.export_scene_doc(scene)
        frames = sample_frames(rng, doc, 170)
        here = record(scene, frames)
        frames = here.pop("_frames")
        step = record(scene, [float(np.nextafter(np.float32(f), np.float32(1e9))) for f in frames])
        step.pop("_frames")
        for name, rec in here.items():
            ext = max(max(abs(v) for v in t) for t in rec["translation"])
            sext = max(max(abs(v) for v in t) for t in rec["scale"])
            for i in range(len(frames)):
                total += 1
                a, b = rec, step[name]
                dt = max(abs(x - y) for x, y in zip(a["translation"][i], b["translation"][i]))
                ds = max(abs(x - y) for x, y in zip(a["scale"][i], b["scale"][i]))
                angle = rotation_angle(a["rotation"][i], b["rotation"][i])
                if dt > max(1e-5 * ext, 4 * np.spacing(np.float32(max(abs(v) for v in a["translation"][i])))) \
                        or ds > max(1e-5 * sext, 4 * np.spacing(np.float32(max(abs(v) for v in a["scale"][i])))) \
                        or angle > 1e-5:
                    moved += 1
    print("observe: one float32 ulp later in frame time moves %d of %d object samples (%.2f %%) of the %d random scenes past the tolerances"
          % (moved, total, 100.0 * moved / total, count))


def observe_channel_defaults():
    """Where no strip covers the frame, animated channels fall to their defaults; others keep the object's value."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    obj, action = _empty_with_action("d", [("location", 0, [(1, 3.0, "LINEAR"), (5, 4.0, "LINEAR")]),
                                           ("scale", 1, [(1, 2.0, "LINEAR"), (5, 3.0, "LINEAR")]),
                                           ("rotation_quaternion", 2, [(1, 0.5, "LINEAR"), (5, 0.7, "LINEAR")])],
                                     base=(5.0, 6.0, 7.0))
    obj.rotation_mode = "QUATERNION"
    obj.rotation_quaternion = (0.6, 0.8, 0.0, 0.0)
    obj.scale = (1.5, 1.5, 1.5)
    strip = obj.animation_data.nla_tracks.new().strips.new("s", 10, action)
    strip.extrapolation = "NOTHING"
    aa, aa_action = _empty_with_action("aa", [("rotation_axis_angle", 2, [(1, 0.5, "LINEAR"), (5, 0.7, "LINEAR")])])
    aa.rotation_mode = "AXIS_ANGLE"
    aa.rotation_axis_angle = (0.9, 0.3, 0.5, 1.0)
    aa_strip = aa.animation_data.nla_tracks.new().strips.new("s", 10, aa_action)
    aa_strip.extrapolation = "NOTHING"
    o = _at(obj, 30)
    a = aa.evaluated_get(bpy.context.evaluated_depsgraph_get())
    print("observe: channel defaults: frame 30 (no strip): location %s scale %s quaternion %s; object's own values were "
          "location (5, 6, 7), scale 1.5, quaternion (0.6, 0.8, 0, 0)"
          % (tuple(round(v, 6) for v in o.location), tuple(round(v, 6) for v in o.scale),
             tuple(round(v, 6) for v in o.rotation_quaternion)))
    print("observe: channel defaults: axis-angle (0.9, 0.3, 0.5, 1) with only its y keyed: at frame 30 %s, world rotation %s"
          % (tuple(round(v, 6) for v in a.rotation_axis_angle), tuple(round(v, 6) for v in a.matrix_world.to_quaternion())))


def observe_eighth_frame():
    """An active action with a modifier: which time does Blender evaluate it at?  One object per
    case, all built before the first evaluation (a change to an action after it would not reach
    the evaluated copy without a depsgraph tag)."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    cases = {}
    for extrapolation, modifier, track in itertools.product(("HOLD", "NOTHING"), (None, "FNGENERATOR", "NOISE", "CYCLES"),
                                                            (False, True)):
        if True:
            name = "%s_%s_%s" % (extrapolation, modifier, "with an NLA track below" if track else "without NLA tracks")
            obj, action = _empty_with_action(name, [("location", 0, [(1, 0.0, "LINEAR"), (21, 20.0, "LINEAR")])])
            if track:  # a strip on another channel: the NLA is evaluated and the action becomes a strip on top
                other = bpy.data.actions.new(name + "_other")
                other_fc = other.fcurves.new("location", index=1)
                other_fc.keyframe_points.insert(1, 1.0)
                other_fc.keyframe_points.insert(5, 2.0)
                obj.animation_data.nla_tracks.new().strips.new("below", 1, other)
            fc = action.fcurves[0]
            if modifier is not None:
                m = fc.modifiers.new(modifier)
                if modifier == "FNGENERATOR":
                    m.phase_multiplier = 3.0
                if modifier == "NOISE":
                    m.scale = 0.5
            obj.animation_data.action = action
            obj.animation_data.action_extrapolation = extrapolation
            cases[name] = (obj, fc)
    frames = [float(np.float32(-3.3 + i * 0.1317)) for i in range(200)]  # inside and outside the keys
    counts = {name: [0, 0, 0] for name in cases}
    big = np.float32(1048574.0)  # MINAFRAMEF = -MAXFRAMEF: the action's range once a modifier makes it infinite
    for f in frames:
        f = set_frame(bpy.context.scene, f)  # the time Blender uses
        depsgraph = bpy.context.evaluated_depsgraph_get()
        for name, (obj, fc) in cases.items():
            got = obj.evaluated_get(depsgraph).location[0]
            counts[name][0] += abs(got - fc.evaluate(f)) <= 1e-6 * max(1, abs(got))
            counts[name][1] += abs(got - fc.evaluate(round(f * 8) / 8)) <= 1e-6 * max(1, abs(got))
            # nlastrip_get_frame_actionclip in float32 with start = actstart = -1048574, actend = 1048574
            t = -big + np.float32(np.fmod(np.float32(np.float32(f) + big), np.float32(2) * big))
            counts[name][2] += abs(got - fc.evaluate(float(t))) <= 1e-6 * max(1, abs(got))
    for name, (exact, eighth, mapped) in counts.items():
        extrapolation, modifier, track = name.split("_", 2)
        print("observe: active action, extrapolation %s, modifier %s, %s: of %d frames in [-3.3, 22.9], %d = the F-curve at "
              "the frame, %d = at the frame rounded to 1/8, %d = at the float32 strip time of a strip over [-1048574, 1048574]"
              % (extrapolation, modifier, track, len(frames), exact, eighth, mapped))


def observe_new_strip_influence():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    obj, action = _empty_with_action("i", [("location", 0, [(1, 2.0, "LINEAR"), (11, 2.0, "LINEAR")])])
    strip = obj.animation_data.nla_tracks.new().strips.new("s", 1, action)
    before = strip.influence
    x_off = _at(obj, 5).location[0]
    strip.use_animated_influence = True
    fc = strip.fcurves.find("influence")
    keys = [(k.co[0], k.co[1]) for k in fc.keyframe_points]
    x_on = _at(obj, 5).location[0]
    print("observe: new strip: influence %.3g, location.x %.3g with animated influence off (full weight); turning it on "
          "keys the influence curve %s and location.x becomes %.3g" % (before, x_off, keys, x_on))


def observe_combine_negative_scale():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    obj, action = _empty_with_action("n", [("scale", 0, [(1, -1.0, "LINEAR"), (11, -2.0, "LINEAR")])])
    strip = obj.animation_data.nla_tracks.new().strips.new("s", 1, action)
    strip.blend_type = "COMBINE"
    strip.use_animated_influence = True
    fc = strip.fcurves.find("influence")
    fc.keyframe_points[0].co[1] = 0.5
    fc.update()
    o = _at(obj, 5)
    print("observe: COMBINE strip at influence 0.5 over scale.x keyed from -1 to -2, frame 5: scale %s, matrix_world[0] %s"
          % (tuple(o.scale), tuple(o.matrix_world[0])))
    strip.blend_type = "REPLACE"
    print("observe: the same strip as REPLACE: scale %s" % (tuple(round(v, 6) for v in _at(obj, 5).scale),))


def observe_auto_blend_and_hold():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    obj, action = _empty_with_action("a", [("location", 0, [(1, 0.0, "LINEAR"), (11, 5.0, "LINEAR")])])
    ad = obj.animation_data
    ad.nla_tracks.new().strips.new("low", 1, action)
    high = ad.nla_tracks.new().strips.new("high", 6, action)
    high.use_auto_blend = True
    print("observe: auto blend switched on through RNA on a strip (6-16) overlapping a strip of the track below (1-11): "
          "Blender sets blend_in %.3g blend_out %.3g" % (high.blend_in, high.blend_out))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    obj, action = _empty_with_action("h", [("location", 0, [(1, 1.0, "LINEAR"), (11, 2.0, "LINEAR")])])
    other, action2 = _empty_with_action("h2", [("location", 0, [(1, 7.0, "LINEAR"), (11, 8.0, "LINEAR")])])
    track = obj.animation_data.nla_tracks.new()
    first = track.strips.new("first", 1, action)
    first.extrapolation = "NOTHING"
    second = track.strips.new("second", 30, action2)
    second.extrapolation = "HOLD"
    print("observe: a track with strips 1-11 (Nothing) and 30-40 (Hold): location.x at frame 20 = %.3g, at frame -5 = %.3g, "
          "at frame 50 = %.3g (Hold on a strip that is not the track's first holds only forward)"
          % (_at(obj, 20).location[0], _at(obj, -5).location[0], _at(obj, 50).location[0]))


def observe_partial_replace():
    """A REPLACE strip whose action keys only location[0], over a strip keying all of location."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    obj, below = _empty_with_action("p", [("location", i, [(1, 5.0, "LINEAR"), (11, 5.0, "LINEAR")]) for i in range(3)])
    above = bpy.data.actions.new("x_only")
    fc = above.fcurves.new("location", index=0)
    fc.keyframe_points.insert(1, 1.0)
    fc.keyframe_points.insert(11, 1.0)
    ad = obj.animation_data
    ad.nla_tracks.new().strips.new("below", 1, below)
    top = ad.nla_tracks.new().strips.new("above", 1, above)
    for blend in ("REPLACE", "ADD", "MULTIPLY", "COMBINE"):
        top.blend_type = blend
        obj.animation_data.nla_tracks.update() if hasattr(obj.animation_data.nla_tracks, "update") else None
        print("observe: strips keying location (5, 5, 5) below and only location[0] = 1 above, %s at full influence: "
              "location %s" % (blend, tuple(round(v, 6) for v in _at(obj, 5).location)))


def observe_partial_quaternion():
    """A REPLACE strip keying only rotation_quaternion[1] over a strip keying the whole quaternion."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    values = (0.6, 0.8, 0.0, 0.0)
    obj, below = _empty_with_action("q", [("rotation_quaternion", i, [(1, v, "LINEAR"), (11, v, "LINEAR")])
                                          for i, v in enumerate(values)])
    obj.rotation_mode = "QUATERNION"
    above = bpy.data.actions.new("x_only")
    fc = above.fcurves.new("rotation_quaternion", index=1)
    fc.keyframe_points.insert(1, 0.5)
    fc.keyframe_points.insert(11, 0.5)
    ad = obj.animation_data
    ad.nla_tracks.new().strips.new("below", 1, below)
    ad.nla_tracks.new().strips.new("above", 1, above)
    print("observe: strips keying the quaternion (0.6, 0.8, 0, 0) below and only its x = 0.5 above, REPLACE at full "
          "influence: quaternion %s" % (tuple(round(v, 6) for v in _at(obj, 5).rotation_quaternion),))


def observe(seed, count):
    observe_partial_replace()
    observe_partial_quaternion()
    observe_float32_strip_time()
    observe_channel_defaults()
    observe_eighth_frame()
    observe_new_strip_influence()
    observe_combine_negative_scale()
    observe_auto_blend_and_hold()
    observe_ulp_step(seed, count)


# ---------------------------------------------------------------------------------------------
# --check-export: what export_scene.py refuses, through its command line (exit status 1, a message
# naming the object or strip, no file written), and one scene it exports.  Meta, transition and
# sound strips are made only by NLA editor operators, which need a window: they are not built here.


def _refused_scenes():
    """(what, builder) pairs; each builder makes a scene the format cannot hold."""
    def base():
        bpy.ops.wm.read_factory_settings(use_empty=True)
        obj, action = _empty_with_action("Cube", [("location", 0, [(1, 0.0, "LINEAR"), (11, 5.0, "LINEAR")])])
        obj.animation_data.action = action
        return obj, action

    def drivers():
        obj, _ = base()
        obj.driver_add("location", 1)

    def delta():
        obj, _ = base()
        obj.delta_location = (0, 0, 1)

    def constraint():
        obj, _ = base()
        obj.constraints.new("COPY_LOCATION")

    def other_path():
        obj, action = base()
        fc = action.fcurves.new("hide_viewport")
        fc.keyframe_points.insert(1, 0)

    def bone():
        bpy.ops.wm.read_factory_settings(use_empty=True)
        arm = bpy.data.armatures.new("Arm")
        obj = bpy.data.objects.new("Rig", arm)
        bpy.context.scene.collection.objects.link(obj)
        action = bpy.data.actions.new("Pose")
        fc = action.fcurves.new('pose.bones["Bone"].location', index=0)
        fc.keyframe_points.insert(1, 0)
        obj.animation_data_create().action = action

    def vertex_parent():
        obj, _ = base()
        mesh = bpy.data.meshes.new("P")
        mesh.from_pydata([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [], [])
        parent = bpy.data.objects.new("P", mesh)
        bpy.context.scene.collection.objects.link(parent)
        obj.parent = parent
        obj.parent_type = "VERTEX"

    def stepped_range():
        obj, action = base()
        m = action.fcurves[0].modifiers.new("STEPPED")
        m.use_restricted_range = True

    return [("drivers", 'object "Cube": drivers'), ("delta", 'object "Cube": delta transforms'),
            ("constraint", 'object "Cube": constraints'), ("other_path", "F-curve hide_viewport[0]: only"),
            ("bone", "bone animation"), ("vertex_parent", "parent type"),
            ("stepped_range", "a Stepped modifier with a restricted frame range")], locals()


def check_export():
    import subprocess
    tmp = tempfile.mkdtemp(prefix="export_scene_check_")
    exporter = os.path.join(os.path.dirname(os.path.abspath(__file__)), "export_scene.py")
    cases, builders = _refused_scenes()
    failures = 0
    for what, expected in cases:
        builders[what]()
        path = os.path.join(tmp, what + ".blend")
        bpy.ops.wm.save_as_mainfile(filepath=path)
        out = os.path.join(tmp, what + ".json")
        run = subprocess.run([bpy.app.binary_path, "-b", "--factory-startup", path, "--python", exporter, "--", "-o", out],
                             capture_output=True, text=True)
        message = [line for line in run.stderr.splitlines() if line.startswith("export_scene:")]
        ok = run.returncode != 0 and not os.path.exists(out) and message and expected in message[0]
        failures += not ok
        print("check-export: %-14s exit %d, %s, %s" % (what, run.returncode, "no file" if not os.path.exists(out) else "FILE WRITTEN",
                                                    message[0] if message else "NO MESSAGE"))
    # an NLA scene exports (exit 0) and the file is the version-3 document
    rng = random.Random(1)
    build_scene(rng, True, 0)
    path = os.path.join(tmp, "ok.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    out = os.path.join(tmp, "ok.json")
    run = subprocess.run([bpy.app.binary_path, "-b", "--factory-startup", path, "--python", exporter, "--", "-o", out],
                         capture_output=True, text=True)
    ok = run.returncode == 0 and os.path.exists(out) and json.load(open(out))["inbetween"] == 3
    failures += not ok
    print("check-export: %-14s exit %d, %s" % ("random scene", run.returncode, "written" if ok else "NOT WRITTEN"))
    print("check-export: %s" % ("all as expected" if failures == 0 else "%d FAILED" % failures))
    return failures


# ---------------------------------------------------------------------------------------------
# --check-reference: an independent reading of the exported document.  A small NLA evaluator
# written from Blender 3.4's anim_sys.cc / nla.c (quoted in docs/blender-nla-observations.md) takes
# every NLA, object and parent member from the exported JSON and only the F-curve values from
# Blender (FCurve.evaluate, modifiers included), and is compared with matrix_world.  If it agrees,
# the document holds everything Blender's NLA uses; it is also a readable statement of the
# semantics for the C++ evaluator.

F32 = np.float32
FLT_EPSILON = 1.1920928955078125e-07
MAXAFRAMEF = F32(1048574.0)


def _is_eqf(a, b):
    return abs(float(a) - float(b)) < FLT_EPSILON


def _calc_action_range(action):
    """calc_action_range(act, .., incl_modifiers=1): keys' range widened by each curve's last modifier."""
    lo, hi, found = 999999999.0, -999999999.0, False
    for fc in action.fcurves:
        if len(fc.keyframe_points):
            lo = min(lo, min(k.co[0] for k in fc.keyframe_points))
            hi = max(hi, max(k.co[0] for k in fc.keyframe_points))
            found = True
        if len(fc.modifiers):
            m = fc.modifiers[-1]
            if m.type == "LIMITS":
                if m.use_min_x:
                    lo = min(lo, m.min_x)
                if m.use_max_x:
                    hi = max(hi, m.max_x)
            elif m.type == "CYCLES":
                if m.mode_before != "NONE":
                    lo = -float(MAXAFRAMEF)
                if m.mode_after != "NONE":
                    hi = float(MAXAFRAMEF)
            else:
                lo, hi = -float(MAXAFRAMEF), float(MAXAFRAMEF)
            found = True
    if not found:
        return 0.0, 1.0
    if lo == hi:
        hi += 1.0
    return lo, hi


def _strip_frame(st, cframe):
    """nlastrip_get_frame_actionclip, NLATIME_CONVERT_EVAL, in float32."""
    repeat = F32(st["repeat"]) if not _is_eqf(st["repeat"], 0) else F32(1)
    scale = abs(F32(st["scale"])) if not _is_eqf(st["scale"], 0) else F32(1)
    actstart, actend = F32(st["action_frame_start"]), F32(st["action_frame_end"])
    actlength = actend - actstart
    if _is_eqf(actlength, 0):
        actlength = F32(1)
    start, end, cframe = F32(st["frame_start"]), F32(st["frame_end"]), F32(cframe)
    whole_end = _is_eqf(cframe, end) and _is_eqf(repeat, np.floor(repeat))
    step = F32(np.fmod(F32(cframe - start), F32(actlength * scale))) / scale
    if st.get("reverse"):
        return actstart if whole_end else F32(actend - step)
    return actend if whole_end else F32(actstart + step)


def _strip_influence(st, cframe):
    """nlastrip_get_influence in float32."""
    bi, bo = abs(F32(st.get("blend_in", 0))), abs(F32(st.get("blend_out", 0)))
    start, end, cframe = F32(st["frame_start"]), F32(st["frame_end"]), F32(cframe)
    if not _is_eqf(bi, 0) and cframe <= F32(start + bi):
        return float(abs(F32(cframe - start)) / bi)
    if not _is_eqf(bo, 0) and cframe >= F32(end - bo):
        return float(abs(F32(end - cframe)) / bo)
    return 1.0


def _pick_strip(strips, ctime):
    """nlastrips_ctime_get_strip: (strip, clamped time) or None."""
    est, side = None, None
    for i, st in enumerate(strips):
        if st.get("_no_time_map") or F32(st["frame_start"]) <= F32(ctime) <= F32(st["frame_end"]):
            est, side = st, "within"
            break
        if F32(ctime) < F32(st["frame_start"]):
            if i == 0:
                if st.get("extrapolation", "hold") == "hold":
                    est = st
                side = "before"
            else:
                prev = strips[i - 1]
                if prev.get("extrapolation", "hold") != "nothing":
                    est = prev
                side = "after"
            break
        if F32(ctime) > F32(st["frame_end"]) and i == len(strips) - 1:
            if st.get("extrapolation", "hold") != "nothing":
                est = st
            side = "after"
            break
    if est is None or est.get("mute"):
        return None
    t = {"before": est["frame_start"], "after": est["frame_end"]}.get(side, ctime)
    return est, float(F32(t))


class _Reference:
    CHANNEL_DEFAULTS = {"location": [0, 0, 0], "rotation_euler": [0, 0, 0], "scale": [1, 1, 1],
                        "rotation_quaternion": [1, 0, 0, 0], "rotation_axis_angle": [0, 0, 0, 0]}
    MIX = {"location": "add", "rotation_euler": "add", "scale": "multiply", "rotation_quaternion": "quaternion",
           "rotation_axis_angle": "add"}

    def __init__(self, doc):
        self.doc = doc
        self.actions = {a["name"]: a for a in doc["actions"]}

    def action_values(self, name, t):
        """{path: (values, keyed)} of an action at time t: the curves over the channel defaults, and
        the elements they key (the blend domain; a quaternion is keyed whole or not at all)."""
        out = {}
        for fc in bpy.data.actions[name].fcurves:
            vals, keyed = out.setdefault(fc.data_path, (list(self.CHANNEL_DEFAULTS[fc.data_path]), set()))
            vals[fc.array_index] = fc.evaluate(float(t))
            keyed.update(range(4) if fc.data_path == "rotation_quaternion" else [fc.array_index])
        return out

    @staticmethod
    def action_direct(name, t):
        """The active action without the NLA (animsys_evaluate_action): each curve writes its element."""
        out = {}
        for fc in bpy.data.actions[name].fcurves:
            out.setdefault(fc.data_path, {})[fc.array_index] = fc.evaluate(float(t))
        return out

    def controls(self, obj, ti, si, st, ctime):
        """Strip influence and time at the (clamped) time: nlastrip_evaluate_controls."""
        strip = bpy.data.objects[obj["name"]].animation_data.nla_tracks[ti].strips[si]
        curves = {fc.data_path: fc for fc in strip.fcurves}
        if "influence" in st:
            influence = st["influence"] if not isinstance(st["influence"], dict) else curves["influence"].evaluate(ctime)
        else:
            influence = _strip_influence(st, ctime)
        if "strip_time" in st:
            t = F32(curves["strip_time"].evaluate(ctime))
            if st.get("strip_time_cyclic"):
                t = F32(math.fmod(float(t - F32(st["action_frame_start"])),
                                  float(F32(st["action_frame_end"]) - F32(st["action_frame_start"]))))
        else:
            t = _strip_frame(st, ctime)
        return float(F32(influence)), t

    @staticmethod
    def blend(mode, lower, upper_keyed, influence, path):
        """nlaevalchan_blendOrcombine: elements outside the upper blend domain keep the lower value."""
        upper, keyed = upper_keyed
        if influence == 0:
            return list(lower)
        blended = _Reference.blend_all(mode, lower, upper, influence, path)
        return [b if i in keyed else lw for i, (b, lw) in enumerate(zip(blended, lower))]

    @staticmethod
    def blend_all(mode, lower, upper, influence, path):
        if mode == "combine":
            mix = _Reference.MIX[path]
            if mix == "quaternion":
                lq = mathutils.Quaternion(lower).normalized()
                uq = mathutils.Quaternion(upper).normalized()
                angle = influence * math.acos(max(-1.0, min(1.0, uq.w)))
                v = mathutils.Vector((uq.x, uq.y, uq.z))
                v = v.normalized() * math.sin(angle) if v.length > 0 else v
                r = lq @ mathutils.Quaternion((math.cos(angle), v.x, v.y, v.z))
                return [r.w, r.x, r.y, r.z]
            base = _Reference.CHANNEL_DEFAULTS[path]
            if mix == "multiply":
                return [lw * (u / (b if b != 0 else 1)) ** influence for lw, u, b in zip(lower, upper, base)]
            return [lw + (u - b) * influence for lw, u, b in zip(lower, upper, base)]
        if mode == "add":
            return [lw + u * influence for lw, u in zip(lower, upper)]
        if mode == "subtract":
            return [lw - u * influence for lw, u in zip(lower, upper)]
        if mode == "multiply":
            return [influence * (lw * u) + (1 - influence) * lw for lw, u in zip(lower, upper)]
        return [lw * (1 - influence) + u * influence for lw, u in zip(lower, upper)]

    def channels(self, obj, frame):
        """The object's animated property values at the frame ({path: values}), domain only."""
        anim = obj.get("animation")
        if anim is None:
            return {}
        tracks = anim.get("tracks", [])
        active = anim.get("action")
        if not anim.get("nla", True) or not tracks:
            return self.action_direct(active, frame) if active else {}
        soloing = any(t.get("solo") for t in tracks)
        enabled = [(ti, t) for ti, t in enumerate(tracks) if (t.get("solo") if soloing else not t.get("mute"))]
        has_strips = any(t["strips"] for _, t in enabled)
        if active and not has_strips and not soloing:
            return self.action_direct(active, frame)
        evaluated = []  # (action, time, mode, influence)
        for ti, t in enabled:
            picked = _pick_strip(t["strips"], frame)
            if picked is None:
                continue
            st, ctime = picked
            influence, strip_time = self.controls(obj, ti, t["strips"].index(st), st, ctime)
            if influence <= 0:
                continue
            evaluated.append((st["action"], strip_time, st.get("blend", "replace"), influence))
        if active and not soloing:
            lo, hi = (F32(v) for v in _calc_action_range(bpy.data.actions[active]))
            extrapolation = anim.get("action_extrapolation", "hold")
            act_strip = {"action": active, "frame_start": float(lo), "frame_end": float(hi if not _is_eqf(lo, hi) else lo + F32(1)),
                         "action_frame_start": float(lo), "action_frame_end": float(hi), "scale": 1.0, "repeat": 1.0,
                         "extrapolation": extrapolation, "_no_time_map": extrapolation != "nothing"}
            picked = _pick_strip([act_strip], frame)
            influence = float(F32(anim.get("action_influence", 1.0)))
            if picked is not None and influence > 0:
                t = picked[1] if act_strip["_no_time_map"] else _strip_frame(act_strip, picked[1])
                evaluated.append((active, t, anim.get("action_blend", "replace"), influence))
        snapshot = {}
        for action, t, mode, influence in evaluated:
            upper = self.action_values(action, t)
            for path in set(upper) | set(snapshot):
                lower = snapshot.get(path, self.CHANNEL_DEFAULTS[path])
                if path in upper:
                    snapshot[path] = self.blend(mode, lower, upper[path], influence, path)
        # the domain: every element any enabled track's strip or the active action animates
        domain = {}
        names = [s["action"] for _, t in enabled for s in t["strips"]] + ([active] if active else [])
        for name in names:
            for fc in bpy.data.actions[name].fcurves:
                idx = domain.setdefault(fc.data_path, set())
                idx.update(range(4) if fc.data_path == "rotation_quaternion" else [fc.array_index])
        return {path: {i: snapshot.get(path, self.CHANNEL_DEFAULTS[path])[i] for i in idx} for path, idx in domain.items()}

    def local_matrix(self, obj, frame):
        loc = list(obj.get("translation", [0, 0, 0]))
        scale = list(obj.get("scale", [1, 1, 1]))
        quat = list(obj.get("rotation", [1, 0, 0, 0]))
        euler = list(obj.get("rotation_euler", [0, 0, 0]))
        axis_angle = list(obj.get("rotation_axis_angle", [0, 0, 1, 0]))
        props = {"location": loc, "scale": scale, "rotation_quaternion": quat, "rotation_euler": euler,
                 "rotation_axis_angle": axis_angle}
        for path, values in self.channels(obj, frame).items():
            for i, v in values.items():
                props[path][i] = float(F32(v))
        mode = obj.get("rotation_mode", "quaternion")
        if mode == "quaternion":
            q = mathutils.Quaternion(quat)
            r = q.normalized().to_matrix() if q.magnitude > 0 else mathutils.Matrix.Identity(3)
        elif mode == "axis_angle":
            axis = mathutils.Vector(axis_angle[1:])
            r = mathutils.Matrix.Rotation(axis_angle[0], 3, axis.normalized()) if axis.length > 0 else mathutils.Matrix.Identity(3)
        else:
            r = mathutils.Euler(euler, mode.upper()).to_matrix()
        m = r.to_4x4()
        for i in range(3):
            for j in range(3):
                m[i][j] *= scale[j]
            m[i][3] = loc[i]
        return m

    def world(self, frame):
        objs = {o["name"]: o for o in self.doc["objects"]}
        cache = {}

        def world_of(name):
            if name not in cache:
                o = objs[name]
                local = self.local_matrix(o, frame)
                if "parent" in o:
                    pinv = mathutils.Matrix(o.get("parent_inverse", mathutils.Matrix.Identity(4)))
                    cache[name] = world_of(o["parent"]) @ pinv @ local
                else:
                    cache[name] = local
            return cache[name]
        return {name: world_of(name) for name in objs}


def _rotation_of(m):
    """The rotation of a 4x4 matrix without shear as a quaternion in double (Shepperd's method)."""
    cols = [[m[r][c] for r in range(3)] for c in range(3)]
    cols = [[v / math.sqrt(sum(x * x for x in col)) for v in col] for col in cols]
    r = [[cols[c][row] for c in range(3)] for row in range(3)]
    tr = r[0][0] + r[1][1] + r[2][2]
    if tr > 0:
        s4 = math.sqrt(tr + 1) * 2
        return (s4 / 4, (r[2][1] - r[1][2]) / s4, (r[0][2] - r[2][0]) / s4, (r[1][0] - r[0][1]) / s4)
    i = max(range(3), key=lambda k: r[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s4 = math.sqrt(1 + r[i][i] - r[j][j] - r[k][k]) * 2
    q = [0.0, 0.0, 0.0, 0.0]
    q[0] = (r[k][j] - r[j][k]) / s4
    q[1 + i] = s4 / 4
    q[1 + j] = (r[j][i] + r[i][j]) / s4
    q[1 + k] = (r[k][i] + r[i][k]) / s4
    return tuple(q)


def check_reference(seed, count, frames_per_scene):
    worst_all = 0.0
    over = total = 0
    for k in range(count):
        rng = random.Random(seed * 1000 + k)
        build_scene(rng, k >= count // 2, k)
        scene = bpy.context.scene
        doc = export_scene.export_scene_doc(scene)
        frames = sample_frames(rng, doc, frames_per_scene)
        recorded = record(scene, frames)
        frames = recorded.pop("_frames")
        reference = _Reference(doc)
        worst, where = 0.0, ""
        for i, f in enumerate(frames):
            ours = reference.world(f)
            for name, rec in recorded.items():
                t, _, sc = ours[name].decompose()
                q = _rotation_of(ours[name])
                ext = max(max(abs(v) for v in tr) for tr in rec["translation"])
                sext = max(max(abs(v) for v in tr) for tr in rec["scale"])
                dt = max(abs(a - b) for a, b in zip(t, rec["translation"][i])) / max(1e-5 * ext, 4 * float(np.spacing(F32(max(abs(v) for v in rec["translation"][i])))))
                ds = max(abs(a - b) for a, b in zip(sc, rec["scale"][i])) / max(1e-5 * sext, 4 * float(np.spacing(F32(max(abs(v) for v in rec["scale"][i])))))
                dr = rotation_angle(q, rec["rotation"][i]) / 1e-5
                ratio = max(dt, ds, dr)
                total += 1
                over += ratio > 1
                if not ratio <= worst:
                    worst, where = ratio, "%s at frame %r (translation %.3g, scale %.3g, rotation %.3g x tolerance)" % (name, f, dt, ds, dr)
        worst_all = max(worst_all, worst)
        print("check-reference: scene %d: worst %.3g x tolerance, %s" % (k, worst, where))
    print("check-reference: %d of %d object samples over the tolerances, worst %.3g x" % (over, total, worst_all))
    return over


def main(argv):
    import argparse
    parser = argparse.ArgumentParser(prog="random_nla_scenes.py")
    parser.add_argument("--seed", type=int, default=23)
    parser.add_argument("--count", type=int, default=12)
    parser.add_argument("--frames", type=int, default=170)
    parser.add_argument("--out", help="folder for sceneK.json and sceneK.world.json")
    parser.add_argument("--observe", action="store_true", help="check the observations of docs/blender-nla-observations.md")
    parser.add_argument("--check-export", action="store_true", help="check what export_scene.py refuses")
    parser.add_argument("--check-reference", action="store_true",
                        help="compare matrix_world with a Python NLA evaluator reading the exported document")
    args = parser.parse_args(argv)
    if args.check_reference:
        sys.stdout.flush()
        os._exit(1 if check_reference(args.seed, args.count, args.frames) else 0)
    if args.check_export:
        sys.stdout.flush()
        os._exit(1 if check_export() else 0)
    if args.observe:
        observe(args.seed, args.count)
        return
    if not args.out:
        parser.error("--out is required")
    os.makedirs(args.out, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="random_nla_")
    for k in range(args.count):
        rng = random.Random(args.seed * 1000 + k)
        with_modifiers = k >= args.count // 2
        build_scene(rng, with_modifiers, k)
        path = os.path.join(tmp, "scene%d.blend" % k)
        bpy.ops.wm.save_as_mainfile(filepath=path)
        bpy.ops.wm.open_mainfile(filepath=path)
        scene = bpy.context.scene
        doc = export_scene.export_scene_doc(scene)
        frames = sample_frames(rng, doc, args.frames)
        objects = record(scene, frames)
        world = {"blender": bpy.app.version_string, "seed": args.seed, "scene": k,
                 "modifiers": with_modifiers, "frames": objects.pop("_frames"), "objects": objects}
        export_scene.write_json(shorten(doc), os.path.join(args.out, "scene%d.json" % k), compact=True)
        export_scene.write_json(world, os.path.join(args.out, "scene%d.world.json" % k), compact=True)
        print("scene %d: %d objects, %d actions, %d frames" % (k, len(doc["objects"]), len(doc["actions"]), len(frames)))


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
