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

Frames are the single-precision times Blender evaluated (set_frame: cfra + subframe in float); every number
is written as the shortest text of its float32 value, so reading it as a double and rounding to
float gives Blender's value exactly.  rotation is a unit quaternion, translation / rotation / scale
are mathutils' Matrix.decompose() of matrix_world.  No world matrix has shear: every object with
children has uniform scale (its three scale channels are the same curve) and a parent inverse of
uniform scale, so the decomposition reproduces matrix_world and the TRS columns of
`inbetween bake --space world` are comparable; objects with non-uniform scale are leaves.

tests/io/blender_nla_agreement_test.cpp reads both files; `make test` needs no Blender.
nla_reference.py checks the files against a Python NLA evaluator; nla_observations.py measures the
Blender behaviours docs/blender-nla-observations.md reports.
"""

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


def build_saved_scene(rng, with_modifiers, k, folder):
    """build_scene, saved as folder/sceneK.blend and opened again (what the exporter reads from a
    file: objects' channels hold their values at the file's current frame); returns the scene."""
    build_scene(rng, with_modifiers, k)
    path = os.path.join(folder, "scene%d.blend" % k)
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path)
    return bpy.context.scene


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


def main(argv):
    import argparse
    parser = argparse.ArgumentParser(prog="random_nla_scenes.py")
    parser.add_argument("--seed", type=int, default=23)
    parser.add_argument("--count", type=int, default=12)
    parser.add_argument("--frames", type=int, default=170)
    parser.add_argument("--out", required=True, help="folder for sceneK.json and sceneK.world.json")
    args = parser.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="random_nla_")
    for k in range(args.count):
        rng = random.Random(args.seed * 1000 + k)
        with_modifiers = k >= args.count // 2
        scene = build_saved_scene(rng, with_modifiers, k, tmp)
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
