"""Records Blender 3.4's matrix_world for hand-built NLA scenes (tests/scene/nla_blender_test.cpp).

    blender -b --factory-startup --python tools/blender/record_nla_cases.py -- OUT.json

Each case is built in an empty Blender scene from a small description (below), one feature at a
time: every blend type of strips and of the active action, extrapolation Hold / Hold Forward /
Nothing, repeat / scale / reverse, action frame ranges, muted strips, muted and solo tracks,
animated influence and strip time, blend in/out, channel defaults, parent_inverse and every rotation
mode.  The scene file of the case is then read back from what Blender stores (frame_end,
extrapolation, influence after Blender's own setters), so the file is what an exporter would
write, and matrix_world of every object is sampled at fractional frames inside and outside the
strips.  The output holds, per case, the version-3 scene and the recorded matrices (the first three
rows, row-major, at 9 significant digits: Blender's floats exactly).
"""
import json
import math
import sys

import bpy

FRAMES = [f * 1.25 - 6.0 for f in range(0, 49)]  # -6 .. 54, fractional (.0 .25 .5 .75)

LOC = ("location", 3)


def keys(*pairs, interpolation="BEZIER"):
    return {"keys": [(f, v) for f, v in pairs], "interpolation": interpolation}


# ------------------------------------------------------------------ cases
# An action: {name: {(path, index): keys(...)}}; an object: dict of settings.
WALK = {("location", 0): keys((1, 0.0), (11, 4.0), (21, 2.0)),
        ("location", 2): keys((1, 1.0), (21, 3.0), interpolation="LINEAR"),
        ("rotation_euler", 2): keys((1, 0.0), (21, 1.5)),
        ("rotation_quaternion", 0): keys((1, 1.0), (21, 0.8)),
        ("rotation_quaternion", 3): keys((1, 0.0), (21, 0.6)),
        ("rotation_axis_angle", 0): keys((1, 0.2), (21, 1.2)),
        ("rotation_axis_angle", 1): keys((1, 0.0), (21, 1.0)),
        ("rotation_axis_angle", 3): keys((1, 1.0), (21, 0.5)),
        ("scale", 1): keys((1, 1.0), (21, 2.0))}
LEAN = {("location", 0): keys((0, 1.0), (10, -1.0), interpolation="LINEAR"),
        ("location", 1): keys((0, 0.5), (10, 1.5)),
        ("rotation_euler", 0): keys((0, 0.3), (10, -0.4)),
        ("rotation_quaternion", 0): keys((0, 0.9), (10, 0.7)),
        ("rotation_quaternion", 1): keys((0, 0.3), (10, 0.5)),
        ("rotation_axis_angle", 0): keys((0, 0.5), (10, 0.1)),
        ("rotation_axis_angle", 2): keys((0, 1.0), (10, 0.2)),
        ("scale", 0): keys((0, 1.5), (10, 0.5)),
        ("scale", 2): keys((0, 2.0), (10, 1.2))}
STEP = {("location", 1): keys((5, 2.0), (9, -1.0), interpolation="CONSTANT"),
        ("scale", 2): keys((5, 3.0), (9, 0.5), interpolation="CONSTANT")}
SWING = {("location", 0): keys((0, 0.0), (20, 3.0)),
         ("location", 1): keys((0, 1.0), (12, -1.0)),
         ("rotation_euler", 1): keys((0, 0.0), (20, 1.2)),
         ("rotation_euler", 2): keys((0, 0.5), (20, -0.5))}
ACTIONS = {"Walk": WALK, "Lean": LEAN, "Step": STEP, "Swing": SWING}


def strip(action, start, **kw):
    s = {"action": action, "start": start}
    s.update(kw)
    return s


def obj(name, mode="QUATERNION", **kw):
    o = {"name": name, "mode": mode, "location": (0.5, -0.25, 0.75), "scale": (1.0, 1.0, 1.0),
         "rotation_euler": (0.1, 0.2, 0.3), "rotation_quaternion": (0.9, 0.1, 0.2, 0.3),
         "rotation_axis_angle": (0.4, 0.0, 0.0, 1.0)}
    o.update(kw)
    return o


def cases():
    out = {}
    modes = ["QUATERNION", "AXIS_ANGLE", "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"]
    # The active action alone, each rotation mode (plain action evaluation).
    out["active_action_modes"] = [obj("m_" + m.lower(), m, action="Walk") for m in modes]
    # Each blend type of a strip over a base strip, in every rotation mode of interest.
    for blend in ["REPLACE", "COMBINE", "ADD", "SUBTRACT", "MULTIPLY"]:
        out["blend_" + blend.lower()] = [
            obj("b_" + m.lower(), m, tracks=[{"strips": [strip("Walk", 1)]},
                                             {"strips": [strip("Lean", 4, blend=blend, influence=0.6)]}])
            for m in ["QUATERNION", "AXIS_ANGLE", "ZXY"]]
    # The active action's blend type and influence on top of a track.
    for blend in ["REPLACE", "COMBINE", "ADD", "SUBTRACT", "MULTIPLY"]:
        out["action_blend_" + blend.lower()] = [
            obj("a_" + m.lower(), m, action="Lean", action_blend=blend, action_influence=0.7,
                tracks=[{"strips": [strip("Walk", 3)]}]) for m in ["QUATERNION", "XYZ", "AXIS_ANGLE"]]
    # Extrapolation of strips: first strip of the bottom track, later strips, upper tracks.
    out["extrapolation"] = [
        obj("hold", tracks=[{"strips": [strip("Walk", 5, extrapolation="HOLD"), strip("Lean", 40, extrapolation="HOLD")]}]),
        obj("hold_forward", tracks=[{"strips": [strip("Walk", 5, extrapolation="HOLD_FORWARD"),
                                                strip("Lean", 40, extrapolation="HOLD_FORWARD")]}]),
        obj("nothing", tracks=[{"strips": [strip("Walk", 5, extrapolation="NOTHING"), strip("Lean", 40, extrapolation="NOTHING")]}]),
        obj("upper_hold", tracks=[{"strips": [strip("Step", 1)]}, {"strips": [strip("Lean", 20, extrapolation="HOLD")]}]),
        obj("action_nothing", action="Lean", action_extrapolation="NOTHING", tracks=[{"strips": [strip("Step", 30)]}]),
        obj("action_hold_forward", action="Lean", action_extrapolation="HOLD_FORWARD", tracks=[{"strips": [strip("Step", 30)]}]),
    ]
    # Time mapping: repeat, scale, reverse, action frame range, fractional repeat.
    out["time_mapping"] = [
        obj("repeat", tracks=[{"strips": [strip("Walk", 2, repeat=2.0)]}]),
        obj("scale", tracks=[{"strips": [strip("Walk", 2, scale=1.5)]}]),
        obj("reverse", tracks=[{"strips": [strip("Walk", 2, reverse=True, repeat=1.5)]}]),
        obj("range", tracks=[{"strips": [strip("Walk", 4, action_frame=(6.0, 16.0), scale=0.75, repeat=2.5)]}]),
        obj("stepped", tracks=[{"strips": [strip("Step", 0, repeat=3.0, scale=1.25)]}]),
    ]
    # Mute and solo.
    out["mute_solo"] = [
        obj("muted_strip", tracks=[{"strips": [strip("Walk", 1), strip("Lean", 30, mute=True)]}]),
        obj("muted_track", tracks=[{"strips": [strip("Walk", 1)]}, {"mute": True, "strips": [strip("Lean", 5)]}]),
        obj("solo_track", action="Step", tracks=[{"strips": [strip("Walk", 1)]}, {"solo": True, "strips": [strip("Lean", 5)]}]),
        obj("nla_off", action="Lean", use_nla=False, tracks=[{"strips": [strip("Walk", 1)]}]),
    ]
    # Influence: blend in/out ramps, a fixed influence, a keyed influence, keyed strip time.
    out["influence"] = [
        obj("ramps", tracks=[{"strips": [strip("Walk", 1)]}, {"strips": [strip("Lean", 10, scale=2.0, blend_in=4.0, blend_out=6.0)]}]),
        obj("ramps_hold", tracks=[{"strips": [strip("Lean", 10, scale=2.0, blend_in=3.0, blend_out=5.0)]}]),
        obj("fixed", tracks=[{"strips": [strip("Walk", 1)]}, {"strips": [strip("Lean", 5, influence=0.35)]}]),
        obj("keyed", tracks=[{"strips": [strip("Walk", 1)]},
                             {"strips": [strip("Lean", 5, influence_keys=[(5, 0.0), (12, 1.0), (18, 0.2)])]}]),
        obj("strip_time", tracks=[{"strips": [strip("Walk", 2, time_keys=[(2, 1.0), (22, 40.0)])]}]),
        obj("strip_time_cyclic", tracks=[{"strips": [strip("Walk", 2, time_keys=[(2, 1.0), (22, 45.0)], cyclic=True)]}]),
    ]
    # Channel defaults: animated channels fall to their default outside the strips; others keep the base.
    out["channel_defaults"] = [
        obj("defaults", "XYZ", location=(3.0, 2.0, 1.0), scale=(2.0, 2.0, 2.0),
            tracks=[{"strips": [strip("Step", 10, extrapolation="NOTHING")]}]),
        obj("defaults_quat", location=(3.0, 2.0, 1.0), scale=(0.5, 1.5, 2.5),
            tracks=[{"strips": [strip("Lean", 10, extrapolation="NOTHING")]}]),
    ]
    # parent_inverse: a child parented with a non-identity inverse under an animated parent.  The
    # parent's scale stays uniform: a non-uniform parent scale under a rotated child is a shear,
    # which a TRS column set cannot hold (docs/nla.md).
    out["parent_inverse"] = [
        obj("parent", "XYZ", action="Swing", scale=(1.5, 1.5, 1.5)),
        obj("child", "ZXY", parent="parent", parent_inverse=True, action="Swing", location=(1.0, 0.0, 0.5)),
        obj("grandchild", "AXIS_ANGLE", parent="child", tracks=[{"strips": [strip("Walk", 0, scale=0.5)]}]),
    ]
    return out


# ------------------------------------------------------------------ building in Blender
def build_action(name, channels):
    act = bpy.data.actions.new(name)
    for (path, index), spec in channels.items():
        fc = act.fcurves.new(path, index=index)
        for f, v in spec["keys"]:
            kp = fc.keyframe_points.insert(f, v, options={"FAST"})
            kp.interpolation = spec["interpolation"]
        fc.update()
    return act


def build_object(o, actions):
    ob = bpy.data.objects.new(o["name"], None)
    bpy.context.scene.collection.objects.link(ob)
    ob.rotation_mode = o["mode"]
    ob.location = o["location"]
    ob.scale = o["scale"]
    ob.rotation_euler = o["rotation_euler"]
    ob.rotation_quaternion = o["rotation_quaternion"]
    ob.rotation_axis_angle = o["rotation_axis_angle"]
    if "parent" in o:
        parent = bpy.data.objects[o["parent"]]
        ob.parent = parent
        if o.get("parent_inverse"):
            # As Blender's "Object (Keep Transform)" parenting leaves it: the parent's inverse at some pose.
            m = parent.matrix_basis.copy()
            bpy.context.scene.frame_set(7)
            ob.matrix_parent_inverse = parent.matrix_world.inverted()
    if not any(k in o for k in ("action", "tracks")):
        return ob
    ad = ob.animation_data_create()
    for t in o.get("tracks", []):
        tr = ad.nla_tracks.new()
        for s in t["strips"]:
            st = tr.strips.new(s["action"], s["start"], actions[s["action"]])
            st.use_auto_blend = False
            st.use_sync_length = False
            if "action_frame" in s:
                st.action_frame_start, st.action_frame_end = s["action_frame"]
            st.scale = s.get("scale", 1.0)
            st.repeat = s.get("repeat", 1.0)
            st.use_reverse = s.get("reverse", False)
            st.blend_type = s.get("blend", "REPLACE")
            st.extrapolation = s.get("extrapolation", "HOLD")
            st.blend_in = s.get("blend_in", 0.0)
            st.blend_out = s.get("blend_out", 0.0)
            st.mute = s.get("mute", False)
            if "influence" in s or "influence_keys" in s:
                # Turning animated influence on keys the stored influence (0 on a new strip) at the
                # strip's start; delete that key so that the constant below (or the keys) act alone.
                st.use_animated_influence = True
                for fc in list(st.fcurves):
                    if fc.data_path == "influence":
                        for f in [kp.co[0] for kp in fc.keyframe_points]:
                            st.keyframe_delete("influence", frame=f)
            if "influence" in s:
                st.influence = s["influence"]
            if "influence_keys" in s:
                for f, v in s["influence_keys"]:
                    st.influence = v
                    st.keyframe_insert("influence", frame=f)
            if "time_keys" in s:
                st.use_animated_time = True
                st.use_animated_time_cyclic = s.get("cyclic", False)
                for f, v in s["time_keys"]:
                    st.strip_time = v
                    st.keyframe_insert("strip_time", frame=f)
        tr.mute = t.get("mute", False)
        if t.get("solo"):
            tr.is_solo = True
    if "action" in o:
        ad.action = actions[o["action"]]
        ad.action_blend_type = o.get("action_blend", "REPLACE")
        ad.action_influence = o.get("action_influence", 1.0)
        ad.action_extrapolation = o.get("action_extrapolation", "HOLD")
    ad.use_nla = o.get("use_nla", True)
    return ob


# ------------------------------------------------------------------ reading back as a scene file
def fcurve_json(fc):
    out = {"keys": []}
    if fc.extrapolation == "LINEAR":
        out["extrapolation"] = "linear"
    for kp in fc.keyframe_points:
        # Handles as Blender stores them, written as free handles: Blender evaluates the stored
        # handles, and this keeps the NLA cases independent of inbetween's recomputation of
        # automatic handles (which disagrees with Blender's on these curves: see docs/nla.md).
        k = {"frame": kp.co[0], "value": kp.co[1], "handle_left_type": "free", "handle_right_type": "free",
             "handle_left": list(kp.handle_left), "handle_right": list(kp.handle_right)}
        if kp.interpolation != "BEZIER":
            k["interpolation"] = kp.interpolation.lower()
        out["keys"].append(k)
    return out


def action_json(act):
    channels = []
    for fc in act.fcurves:
        c = {"path": fc.data_path, "index": fc.array_index}
        c.update(fcurve_json(fc))
        channels.append(c)
    a = {"name": act.name, "channels": channels}
    if act.use_frame_range:
        a["frame_range"] = [act.frame_start, act.frame_end]
    return a


def object_json(ob):
    o = {"name": ob.name, "rotation_mode": ob.rotation_mode.lower(), "translation": list(ob.location), "scale": list(ob.scale)}
    if ob.rotation_mode == "QUATERNION":
        o["rotation"] = list(ob.rotation_quaternion)
    elif ob.rotation_mode == "AXIS_ANGLE":
        o["rotation_axis_angle"] = list(ob.rotation_axis_angle)
    else:
        o["rotation_euler"] = list(ob.rotation_euler)
    if ob.parent:
        o["parent"] = ob.parent.name
        pi = ob.matrix_parent_inverse
        o["parent_inverse"] = [[pi[r][c] for c in range(4)] for r in range(4)]
    ad = ob.animation_data
    if ad is None:
        return o
    an = {}
    if ad.action:
        an["action"] = ad.action.name
        an["action_blend"] = ad.action_blend_type.lower()
        an["action_influence"] = ad.action_influence
        an["action_extrapolation"] = ad.action_extrapolation.lower()
    an["nla"] = ad.use_nla
    tracks = []
    for tr in ad.nla_tracks:
        t = {"name": tr.name, "mute": tr.mute, "solo": tr.is_solo, "strips": []}
        for st in tr.strips:
            s = {"name": st.name, "action": st.action.name, "frame_start": st.frame_start, "frame_end": st.frame_end,
                 "action_frame_start": st.action_frame_start, "action_frame_end": st.action_frame_end,
                 "scale": st.scale, "repeat": st.repeat, "reverse": st.use_reverse, "blend": st.blend_type.lower(),
                 "extrapolation": st.extrapolation.lower(), "blend_in": st.blend_in, "blend_out": st.blend_out,
                 "auto_blend": st.use_auto_blend, "mute": st.mute}
            if st.use_animated_influence:
                curves = [fc for fc in st.fcurves if fc.data_path == "influence"]
                s["influence"] = fcurve_json(curves[0]) if curves and len(curves[0].keyframe_points) else st.influence
            if st.use_animated_time:
                curves = [fc for fc in st.fcurves if fc.data_path == "strip_time"]
                s["strip_time"] = fcurve_json(curves[0])
                s["strip_time_cyclic"] = st.use_animated_time_cyclic
            t["strips"].append(s)
        tracks.append(t)
    an["tracks"] = tracks
    o["animation"] = an
    return o


def record(case, objects):
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob)
    for act in list(bpy.data.actions):
        bpy.data.actions.remove(act)
    actions = {name: build_action(name, ch) for name, ch in ACTIONS.items()}
    built = [build_object(o, actions) for o in objects]
    scene = {"inbetween": 3, "fps": 24, "range": [FRAMES[0], FRAMES[-1]],
             "actions": [action_json(a) for a in actions.values()], "objects": [object_json(ob) for ob in built]}
    matrices = {ob.name: [] for ob in built}
    for f in FRAMES:
        whole = math.floor(f)
        bpy.context.scene.frame_set(int(whole), subframe=f - whole)
        for ob in built:
            m = ob.matrix_world  # float32 in Blender: its shortest float text loses nothing
            matrices[ob.name].append([float("%.9g" % m[r][c]) for r in range(3) for c in range(4)])
    return {"case": case, "scene": scene, "frames": FRAMES, "matrix_world": matrices}


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    out_path = argv[0] if argv else "nla_cases.json"
    bpy.context.preferences.edit.keyframe_new_interpolation_type = "BEZIER"
    bpy.context.preferences.edit.keyframe_new_handle_type = "AUTO_CLAMPED"
    results = [record(name, objects) for name, objects in cases().items()]
    with open(out_path, "w") as f:
        json.dump({"blender": bpy.app.version_string, "cases": results}, f, indent=None, separators=(",", ":"))
        f.write("\n")
    print("wrote", out_path, len(results), "cases")


main()
