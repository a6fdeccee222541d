"""A reference NLA evaluator in Python, written from Blender 3.4's anim_sys.cc and nla.c, to show that
a document written by tools/blender/export_scene.py holds everything Blender's NLA uses.

    blender -b --factory-startup --python tools/blender/nla_reference.py -- --data tests/data/blender_nla

It rebuilds the random scenes of random_nla_scenes.py (same --seed, --count, --frames), checks that
the exported documents are the recorded sceneK.json, and evaluates every object's world matrix at
the recorded frames from the document alone — strip choice, extrapolation, influence, strip time,
blending, the action strip, channel defaults, parents — taking only F-curve values from Blender
(FCurve.evaluate, modifiers included).  It compares with the recorded matrix_world (sceneK.world.json)
with the agreement test's tolerances and prints the worst sample per scene; exit status 1 if any
sample is over.  The semantics are quoted in docs/blender-nla-observations.md; _Reference is a
readable statement of them for the C++ evaluator.
"""

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
from random_nla_scenes import build_saved_scene, record, rotation_angle, sample_frames, shorten  # noqa: E402

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


def check_reference(seed, count, frames_per_scene, data):
    """Compares the reference with Blender: the recorded files in `data` if given (the exported
    document must then be the recorded one), else a fresh recording."""
    worst_all = 0.0
    over = total = 0
    tmp = tempfile.mkdtemp(prefix="nla_")
    for k in range(count):
        rng = random.Random(seed * 1000 + k)
        scene = build_saved_scene(rng, k >= count // 2, k, tmp)
        doc = export_scene.export_scene_doc(scene)
        frames = sample_frames(rng, doc, frames_per_scene)
        if data:
            with open(os.path.join(data, "scene%d.json" % k)) as f:
                if json.load(f) != json.loads(json.dumps(shorten(doc))):
                    print("check-reference: scene %d: the exported document is not the recorded scene%d.json" % (k, k))
                    over += 1
                    continue
            with open(os.path.join(data, "scene%d.world.json" % k)) as f:
                world = json.load(f)
            frames, recorded = world["frames"], world["objects"]
        else:
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
                over += not ratio <= 1
                if not ratio <= worst:
                    worst, where = ratio, "%s at frame %r (translation %.3g, scale %.3g, rotation %.3g x tolerance)" % (name, f, dt, ds, dr)
        worst_all = max(worst_all, worst)
        print("check-reference: scene %d: worst %.3g x tolerance, %s" % (k, worst, where))
    print("check-reference: %d of %d object samples over the tolerances, worst %.3g x" % (over, total, worst_all))
    return over


def main(argv):
    import argparse
    parser = argparse.ArgumentParser(prog="nla_reference.py")
    parser.add_argument("--seed", type=int, default=23)
    parser.add_argument("--count", type=int, default=12)
    parser.add_argument("--frames", type=int, default=170)
    parser.add_argument("--data", help="the recorded folder (tests/data/blender_nla); without it, record afresh")
    args = parser.parse_args(argv)
    sys.stdout.flush()
    failures = check_reference(args.seed, args.count, args.frames, args.data)
    sys.stdout.flush()
    os._exit(1 if failures else 0)


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
