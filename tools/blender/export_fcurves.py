"""Export Blender F-curves to the inbetween scene format (docs/scene-format.md).

Run inside Blender:

    blender -b file.blend --python tools/blender/export_fcurves.py -- -o scene.json
    blender -b file.blend --python tools/blender/export_fcurves.py -- -o scene.json --action Walk

Without --action every object's active action is exported, each curve named
"<object>.<data path>.<component>" (e.g. "Cube.location.x"); actions not assigned to an object are
exported as "<action>.<data path>.<component>".  Handles are written as Blender stores them
(absolute frame/value); inbetween recomputes the automatic and vector ones exactly as Blender's
FCurve.update() does, so a curve whose handles are up to date evaluates to Blender's numbers.

Exported: keyframes, extrapolation, auto smoothing and every F-curve modifier of Blender 3.4 (Generator,
Built-in Function, Envelope, Cycles, Noise, Limits, Stepped) with its mute, influence and restricted
frame range.  Skipped with a warning on stderr: baked sample curves, drivers, and a Stepped modifier
with a restricted range (Blender's Python API cannot read that range).

The module can also be imported (the agreement test does): fcurve_to_track(fcurve, name) returns
one track as a dict, modifiers_to_list(fcurve) its modifier stack, export_scene(scene,
action_name=None) the whole document.
"""

import json
import sys

import bpy

COMPONENTS = {
    "location": "xyz", "rotation_euler": "xyz", "scale": "xyz", "delta_location": "xyz",
    "delta_rotation_euler": "xyz", "delta_scale": "xyz", "rotation_quaternion": "wxyz",
    "delta_rotation_quaternion": "wxyz", "rotation_axis_angle": "wxyz", "color": "rgba",
}


def _warn(message):
    sys.stderr.write("export_fcurves: " + message + "\n")


def curve_name(owner, fcurve):
    """Track name "<owner>.<data path>.<component>"."""
    letters = COMPONENTS.get(fcurve.data_path)
    index = fcurve.array_index
    comp = letters[index] if letters and index < len(letters) else str(index)
    return "%s.%s.%s" % (owner, fcurve.data_path, comp)


GENERATOR_MODES = {"POLYNOMIAL": "expanded", "POLYNOMIAL_FACTORISED": "factorised"}


def modifier_to_dict(m):
    """One F-curve modifier as the scene format's modifier object (docs/scene-format.md), every member
    written; raises ValueError for what the format cannot hold."""
    out = {}
    t = m.type
    if t == "GENERATOR":
        out = {"type": "generator", "mode": GENERATOR_MODES[m.mode], "additive": bool(m.use_additive),
               "coefficients": [float(c) for c in m.coefficients]}
    elif t == "FNGENERATOR":
        out = {"type": "function", "function": m.function_type.lower(), "amplitude": m.amplitude,
               "phase_multiplier": m.phase_multiplier, "phase_offset": m.phase_offset,
               "value_offset": m.value_offset, "additive": bool(m.use_additive)}
    elif t == "ENVELOPE":
        out = {"type": "envelope", "reference": m.reference_value, "default_min": m.default_min,
               "default_max": m.default_max,
               "points": [{"frame": p.frame, "min": p.min, "max": p.max} for p in m.control_points]}
    elif t == "CYCLES":
        out = {"type": "cycles", "before": m.mode_before.lower(), "after": m.mode_after.lower(),
               "count_before": int(m.cycles_before), "count_after": int(m.cycles_after)}
    elif t == "NOISE":
        out = {"type": "noise", "blend": m.blend_type.lower(), "scale": m.scale, "strength": m.strength,
               "phase": m.phase, "offset": m.offset, "depth": int(m.depth)}
    elif t == "LIMITS":
        out = {"type": "limits",
               "min_x": m.min_x if m.use_min_x else None, "max_x": m.max_x if m.use_max_x else None,
               "min_y": m.min_y if m.use_min_y else None, "max_y": m.max_y if m.use_max_y else None}
    elif t == "STEPPED":
        # Blender's Python API names the step range frame_start/frame_end, hiding the restricted range's
        # members of the same names: a restricted range on a Stepped modifier cannot be read.
        if m.use_restricted_range:
            raise ValueError("a Stepped modifier with a restricted frame range (Blender's Python API cannot read "
                             "that range: its frame_start/frame_end are the step range's)")
        out = {"type": "stepped", "step": m.frame_step, "offset": m.frame_offset,
               "start": m.frame_start if m.use_frame_start else None,
               "end": m.frame_end if m.use_frame_end else None}
    else:
        raise ValueError("a %s modifier (not a Blender 3.4 F-curve modifier inbetween knows)" % t)
    # A modifier Blender has disabled (a Cycles modifier once evaluated below the top) does nothing,
    # as a muted one.
    out["mute"] = bool(m.mute) or not m.is_valid
    if m.use_influence:
        out["influence"] = m.influence
    if m.use_restricted_range and t != "STEPPED":
        out["range"] = {"start": m.frame_start, "end": m.frame_end, "blend_in": m.blend_in,
                        "blend_out": m.blend_out}
    return out


def modifiers_to_list(fcurve):
    """The F-curve's modifier stack (top first) as a list of modifier objects."""
    return [modifier_to_dict(m) for m in fcurve.modifiers]


def fcurve_to_track(fcurve, name):
    """One F-curve as an inbetween scalar track (dict)."""
    if len(fcurve.keyframe_points) == 0:
        raise ValueError("no keyframes (baked sample curves are not supported)")
    keys = []
    for k in fcurve.keyframe_points:
        keys.append({
            "frame": k.co[0], "value": k.co[1],
            "interpolation": k.interpolation.lower(), "easing": k.easing.lower(),
            "handle_left_type": k.handle_left_type.lower(), "handle_right_type": k.handle_right_type.lower(),
            "handle_left": [k.handle_left[0], k.handle_left[1]],
            "handle_right": [k.handle_right[0], k.handle_right[1]],
            "back": k.back, "amplitude": k.amplitude, "period": k.period,
        })
    track = {
        "name": name, "keys": keys,
        "extrapolation": fcurve.extrapolation.lower(),
        "auto_smoothing": fcurve.auto_smoothing.lower(),
    }
    modifiers = modifiers_to_list(fcurve)
    if modifiers:
        track["modifiers"] = modifiers
    return track


def _tracks_of(owner, action, tracks):
    for fc in action.fcurves:
        name = curve_name(owner, fc)
        try:
            tracks.append(fcurve_to_track(fc, name))
        except ValueError as e:
            _warn("skipping %s: %s" % (name, e))


def export_scene(scene, action_name=None):
    """The scene document (dict) for `scene`, or for one named action."""
    tracks = []
    if action_name is not None:
        action = bpy.data.actions.get(action_name)
        if action is None:
            raise SystemExit("export_fcurves: no action named %r" % action_name)
        _tracks_of(action.name, action, tracks)
    else:
        used = set()
        for obj in scene.objects:
            ad = obj.animation_data
            if ad is not None and ad.action is not None:
                used.add(ad.action.name)
                _tracks_of(obj.name, ad.action, tracks)
        for action in bpy.data.actions:
            if action.name not in used:
                _tracks_of(action.name, action, tracks)
    return {
        "inbetween": 1,
        "fps": scene.render.fps / scene.render.fps_base,
        "range": [scene.frame_start, scene.frame_end],
        "tracks": tracks,
    }


def main(argv):
    import argparse
    parser = argparse.ArgumentParser(prog="export_fcurves.py")
    parser.add_argument("-o", "--output", required=True, help="scene JSON to write ('-' for stdout)")
    parser.add_argument("--action", help="export only this action")
    args = parser.parse_args(argv)
    doc = export_scene(bpy.context.scene, args.action)
    text = json.dumps(doc, indent=1)
    if args.output == "-":
        sys.stdout.write(text + "\n")
    else:
        with open(args.output, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
