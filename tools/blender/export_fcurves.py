"""Export Blender F-curves to the inbetween scene format (docs/scene-format.md).

Run inside Blender:

    blender -b file.blend --python tools/blender/export_fcurves.py -- -o scene.json
    blender -b file.blend --python tools/blender/export_fcurves.py -- -o scene.json --action Walk

Without --action every object's active action is exported, each curve named
"<object>.<data path>.<component>" (e.g. "Cube.location.x"); actions not assigned to an object are
exported as "<action>.<data path>.<component>".  Handles are written as Blender stores them
(absolute frame/value); inbetween recomputes the automatic and vector ones exactly as Blender's
FCurve.update() does, so a curve whose handles are up to date evaluates to Blender's numbers.

Only what inbetween reproduces is exported: keyframes, extrapolation, auto smoothing and a Cycles
modifier that is the first modifier at full influence without a frame range.  Curves with other
modifiers, baked samples or drivers are skipped with a warning on stderr.

The module can also be imported (the agreement test does): fcurve_to_track(fcurve, name) returns
one track as a dict, export_scene(scene, action_name=None) the whole document.
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


def _cycles(fcurve):
    """The Cycles modifier as a dict, None when absent; raises ValueError when not exportable."""
    mods = list(fcurve.modifiers)
    if not mods:
        return None
    first = mods[0]
    if len(mods) > 1 or first.type != "CYCLES":
        raise ValueError("modifiers other than a single Cycles modifier are not supported")
    if first.mute:
        return None
    if first.use_restricted_range or first.use_influence:
        raise ValueError("a Cycles modifier with a frame range or influence is not supported")
    return {
        "before": first.mode_before.lower(), "after": first.mode_after.lower(),
        "count_before": int(first.cycles_before), "count_after": int(first.cycles_after),
    }


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
    cycles = _cycles(fcurve)
    if cycles is not None:
        track["cycles"] = cycles
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
