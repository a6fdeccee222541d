"""Blender 3.4's NLA behaviours that docs/blender-nla-observations.md reports, each measured on a
small scene built here, and what tools/blender/export_scene.py refuses.

    blender -b --factory-startup --python tools/blender/nla_observations.py -- --count 12
    blender -b --factory-startup --python tools/blender/nla_observations.py -- --check-export

Every check prints one "observe:" (or "check-export:") line with what Blender gave; the document
quotes them.  observe_ulp_step rebuilds the random scenes of random_nla_scenes.py (--seed, --count).
"""

import itertools
import math
import os
import random
import sys
import tempfile
import json

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import export_scene  # noqa: E402
from random_nla_scenes import build_saved_scene, build_scene, record, rotation_angle, sample_frames, set_frame  # noqa: E402

# ---------------------------------------------------------------------------------------------
# The observations (each prints one "observe:" line).


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
    tmp = tempfile.mkdtemp(prefix="nla_")
    for k in range(count):
        rng = random.Random(seed * 1000 + k)
        scene = build_saved_scene(rng, k >= count // 2, k, tmp)
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


def main(argv):
    import argparse
    parser = argparse.ArgumentParser(prog="nla_observations.py")
    parser.add_argument("--seed", type=int, default=23, help="random_nla_scenes.py's seed (for the one-ulp measure)")
    parser.add_argument("--count", type=int, default=12, help="random scenes for the one-ulp measure")
    parser.add_argument("--check-export", action="store_true", help="check what export_scene.py refuses instead")
    args = parser.parse_args(argv)
    if args.check_export:
        sys.stdout.flush()
        os._exit(1 if check_export() else 0)
    observe(args.seed, args.count)


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
