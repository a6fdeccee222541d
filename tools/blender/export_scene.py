"""Export a .blend file's objects, actions and NLA to the inbetween scene format, version 3.

Run inside Blender:

    blender -b FILE.blend --python tools/blender/export_scene.py -- -o SCENE.json

Writes every object of the scene (name, parent, matrix_parent_inverse, rotation mode, base
location / rotation / scale), every action an object uses (as its active action or in an NLA
strip) with its location, rotation_euler, rotation_quaternion, rotation_axis_angle and scale
F-curves, and each object's NLA tracks, strips and active action: the shape of docs/scene-format.md
("Blender objects, actions and NLA").  `inbetween bake SCENE.json --space world` then gives
Blender's matrix_world of every object (tests/io/blender_nla_agreement_test.cpp measures it on the
scenes tools/blender/random_nla_scenes.py records).

What the format cannot hold is refused with one message naming the object, action, track or strip,
exit status 1 and nothing written: bone (pose) animation, drivers, F-curves on other properties,
muted or disabled F-curves (or in a muted group), meta / transition / sound strips, NLA strip modifiers, tweak mode,
non-zero delta transforms, constraints, parents other than an object.

The F-curve members (keys, extrapolation, auto smoothing, modifiers) come from
export_fcurves.fcurve_to_track.

The module can be imported (random_nla_scenes.py does): export_scene_doc(scene) returns the document
as a dict and raises ExportError for what the format cannot hold.
"""

import json
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import export_fcurves  # noqa: E402  (tools/blender/export_fcurves.py)

CHANNEL_PATHS = ("location", "rotation_euler", "rotation_quaternion", "rotation_axis_angle", "scale")
ROTATION_MODES = {
    "QUATERNION": "quaternion", "AXIS_ANGLE": "axis_angle", "XYZ": "xyz", "XZY": "xzy",
    "YXZ": "yxz", "YZX": "yzx", "ZXY": "zxy", "ZYX": "zyx",
}


class ExportError(Exception):
    """Something the scene format cannot hold; the message names the object / action / strip."""


# ---------------------------------------------------------------------------------------------
# F-curves


def fcurve_members(fcurve, where):
    """The F-curve members of the format (keys, extrapolation, auto_smoothing, modifiers) as a dict."""
    if fcurve.mute:
        raise ExportError("%s: the F-curve is muted (unmute or delete it)" % where)
    if fcurve.group is not None and fcurve.group.mute:
        raise ExportError('%s: its group "%s" is muted (unmute or delete it)' % (where, fcurve.group.name))
    if not fcurve.is_valid:
        raise ExportError("%s: the F-curve is disabled (its path does not resolve)" % where)
    if len(fcurve.keyframe_points) == 0:
        raise ExportError("%s: the F-curve has no keyframes (baked samples or a modifier-only curve)" % where)
    try:
        members = export_fcurves.fcurve_to_track(fcurve, "")  # keys, extrapolation, smoothing, modifiers
        members.pop("name", None)
    except ValueError as e:
        raise ExportError("%s: %s" % (where, e))
    return members


# ---------------------------------------------------------------------------------------------
# Actions


def _action_doc(action):
    channels = []
    for fc in action.fcurves:
        where = 'action "%s", F-curve %s[%d]' % (action.name, fc.data_path, fc.array_index)
        if fc.data_path.startswith("pose.bones"):
            raise ExportError("%s: bone animation is not in the scene format" % where)
        if fc.data_path not in CHANNEL_PATHS:
            raise ExportError("%s: only %s are exported" % (where, ", ".join(CHANNEL_PATHS)))
        channel = {"path": fc.data_path, "index": fc.array_index}
        channel.update(fcurve_members(fc, where))
        channels.append(channel)
    doc = {"name": action.name}
    if action.use_frame_range:
        doc["frame_range"] = [action.frame_start, action.frame_end]
    doc["channels"] = channels
    return doc


# ---------------------------------------------------------------------------------------------
# Objects and NLA


def _strip_doc(obj, track, strip, used_actions):
    where = 'object "%s", NLA track "%s", strip "%s"' % (obj.name, track.name, strip.name)
    if strip.type != "CLIP":
        raise ExportError("%s: %s strips are not in the scene format (only action strips)" % (where, strip.type.lower()))
    if strip.action is None:
        raise ExportError("%s: the strip has no action" % where)
    if len(strip.modifiers):
        raise ExportError("%s: NLA strip modifiers are not in the scene format" % where)
    used_actions[strip.action.name] = strip.action
    _warn_combine_negative_scale(obj, strip.blend_type, strip.action, 'strip "%s"' % strip.name)
    doc = {
        "name": strip.name, "action": strip.action.name,
        "frame_start": strip.frame_start, "frame_end": strip.frame_end,
        "action_frame_start": strip.action_frame_start, "action_frame_end": strip.action_frame_end,
        "scale": strip.scale, "repeat": strip.repeat, "reverse": bool(strip.use_reverse),
        "blend": strip.blend_type.lower(), "extrapolation": strip.extrapolation.lower(),
        "blend_in": strip.blend_in, "blend_out": strip.blend_out, "auto_blend": bool(strip.use_auto_blend),
    }
    curves = {fc.data_path: fc for fc in strip.fcurves}
    for fc in strip.fcurves:
        if fc.data_path not in ("influence", "strip_time"):
            raise ExportError("%s: F-curve %s on the strip is not in the scene format" % (where, fc.data_path))
    if strip.use_animated_influence:
        fc = curves.get("influence")
        doc["influence"] = fcurve_members(fc, where + ", influence") if fc is not None else strip.influence
    if strip.use_animated_time:
        fc = curves.get("strip_time")
        if fc is not None:
            doc["strip_time"] = fcurve_members(fc, where + ", strip_time")
        else:  # no curve: the constant strip_time, as a one-key curve
            doc["strip_time"] = {"keys": [{"frame": strip.frame_start, "value": strip.strip_time, "interpolation": "constant"}]}
        if strip.use_animated_time_cyclic:
            doc["strip_time_cyclic"] = True
    if strip.mute:
        doc["mute"] = True
    return doc


def _warn_combine_negative_scale(obj, blend, action, what):
    """Blender 3.4's COMBINE blend of a negative scale is NaN (docs/blender-nla-observations.md)."""
    if blend != "COMBINE" or action is None:
        return
    for fc in action.fcurves:
        if fc.data_path == "scale" and any(k.co[1] < 0 for k in fc.keyframe_points):
            sys.stderr.write('export_scene: warning: object "%s", %s: COMBINE over action "%s" whose scale[%d] is keyed '
                             "negative; Blender evaluates that to NaN (docs/blender-nla-observations.md)\n"
                             % (obj.name, what, action.name, fc.array_index))


def _animation_doc(obj, used_actions):
    ad = obj.animation_data
    if ad is None:
        return None
    where = 'object "%s"' % obj.name
    if len(ad.drivers):
        raise ExportError("%s: drivers are not in the scene format (%s)" % (where, ad.drivers[0].data_path))
    if ad.use_tweak_mode:
        raise ExportError("%s: the NLA is in tweak mode (leave it first)" % where)
    if ad.action is None and len(ad.nla_tracks) == 0:
        return None
    doc = {}
    if ad.action is not None:
        used_actions[ad.action.name] = ad.action
        doc["action"] = ad.action.name
        _warn_combine_negative_scale(obj, ad.action_blend_type, ad.action, "active action")
    doc["action_blend"] = ad.action_blend_type.lower()
    doc["action_influence"] = ad.action_influence
    doc["action_extrapolation"] = ad.action_extrapolation.lower()
    doc["nla"] = bool(ad.use_nla)
    tracks = []
    for track in ad.nla_tracks:
        strips = [_strip_doc(obj, track, s, used_actions) for s in track.strips]
        t = {"name": track.name, "strips": strips}
        if track.mute:
            t["mute"] = True
        if track.is_solo:
            t["solo"] = True
        tracks.append(t)
    doc["tracks"] = tracks
    return doc


def _is_identity(m):
    return all(m[r][c] == (1.0 if r == c else 0.0) for r in range(4) for c in range(4))


def _object_doc(obj, used_actions):
    where = 'object "%s"' % obj.name
    if len(obj.constraints):
        raise ExportError("%s: constraints are not in the scene format (%s)" % (where, obj.constraints[0].name))
    if any(v != 0 for v in obj.delta_location) or any(v != 0 for v in obj.delta_rotation_euler) \
            or tuple(obj.delta_rotation_quaternion) != (1, 0, 0, 0) or any(v != 1 for v in obj.delta_scale):
        raise ExportError("%s: delta transforms are not in the scene format (apply or clear them)" % where)
    if obj.type == "ARMATURE" and obj.pose is not None and obj.animation_data is not None:
        for action in [obj.animation_data.action] + [s.action for t in obj.animation_data.nla_tracks for s in t.strips]:
            if action is not None and any(fc.data_path.startswith("pose.bones") for fc in action.fcurves):
                raise ExportError('%s: bone animation (action "%s") is not in the scene format' % (where, action.name))
    doc = {"name": obj.name}
    if obj.parent is not None:
        if obj.parent_type != "OBJECT":
            raise ExportError("%s: parent type %s is not in the scene format (only object parents)" % (where, obj.parent_type))
        doc["parent"] = obj.parent.name
        if not _is_identity(obj.matrix_parent_inverse):
            doc["parent_inverse"] = [[obj.matrix_parent_inverse[r][c] for c in range(4)] for r in range(4)]
    mode = ROTATION_MODES[obj.rotation_mode]
    doc["rotation_mode"] = mode
    doc["translation"] = list(obj.location)
    if mode == "quaternion":
        doc["rotation"] = list(obj.rotation_quaternion)
    elif mode == "axis_angle":
        doc["rotation_axis_angle"] = list(obj.rotation_axis_angle)
    else:
        doc["rotation_euler"] = list(obj.rotation_euler)
    doc["scale"] = list(obj.scale)
    animation = _animation_doc(obj, used_actions)
    if animation is not None:
        doc["animation"] = animation
    return doc


def _check_finite(value, where):
    if isinstance(value, float) and not math.isfinite(value):
        raise ExportError("%s: non-finite number %r" % (where, value))
    if isinstance(value, dict):
        for k, v in value.items():
            _check_finite(v, where + "/" + str(k))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            _check_finite(v, where + "/" + str(i))


def export_scene_doc(scene):
    """The version-3 scene document (dict) of `scene`; raises ExportError."""
    used_actions = {}
    objects = [_object_doc(obj, used_actions) for obj in scene.objects]
    actions = [_action_doc(used_actions[name]) for name in sorted(used_actions)]
    doc = {
        "inbetween": 3,
        "fps": scene.render.fps / scene.render.fps_base,
        "range": [scene.frame_start, scene.frame_end],
        "actions": actions,
        "objects": objects,
    }
    _check_finite(doc, "")
    return doc


def write_json(doc, path, compact=False):
    """Writes `doc` to `path` whole or not at all (a temporary file renamed into place)."""
    text = json.dumps(doc, separators=(",", ":")) if compact else json.dumps(doc, indent=1)
    tmp = path + ".tmp%d" % os.getpid()
    with open(tmp, "w") as f:
        f.write(text + "\n")
    os.replace(tmp, path)


def main(argv):
    import argparse
    parser = argparse.ArgumentParser(prog="export_scene.py")
    parser.add_argument("-o", "--output", required=True, help="scene JSON to write ('-' for stdout)")
    args = parser.parse_args(argv)
    try:
        doc = export_scene_doc(bpy.context.scene)
    except ExportError as e:
        sys.stderr.write("export_scene: %s: %s\n" % (bpy.data.filepath or "<unsaved>", e))
        sys.stderr.flush()
        os._exit(1)  # Blender's own exit would report success
    if args.output == "-":
        sys.stdout.write(json.dumps(doc, indent=1) + "\n")
    else:
        write_json(doc, args.output)


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
