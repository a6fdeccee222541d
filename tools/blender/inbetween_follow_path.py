"""Put the active Blender object on a curve at a chosen speed, with the inbetween Python module.

An add-on (Object > Animation > "inbetween: Follow Path") and a command-line script.  The path is
a Blender curve object (its first Bezier or poly spline, world space) or a curve file
(docs/curve-format.md); the speed is a scene file's "speed" dictionary (an ease over a frame span,
distance-time keys, velocity keys; docs/scene-paths.md); the orientation one of the scene's modes
(rotation_minimizing, frenet, up, look_at) or "none" (position only).  The motion is baked by
inbetween (the same numbers as `inbetween bake` of the equivalent scene, which the script can
write) and written as one LINEAR key per frame on location and rotation_quaternion.

Axes.  inbetween scenes are Y-up with an object's front +Z and up +Y (glTF's convention); Blender
is Z-up.  The script uses the mapping of Blender's glTF importer:
    Blender (x, y, z) = scene (x, -z, y),    scene (x, y, z) = Blender (x, z, -y)
for points, and R_blender = C R_scene C^T for rotations (C the matrix of that map), so in Blender
the object's front is -Y and its up +Z (a scene "up" of [0, 1, 0] is Blender's +Z).

Making the module importable in Blender (Debian's blender 3.4 runs /usr/bin/python3 3.11, the
interpreter the module is built for): build it (`make`, or `cmake --build build/release --target
inbetween_python`), then either set INBETWEEN_PYTHON_PATH=/path/to/build/release/python, pass
--module-dir, or leave both out when this file is used from the source tree (build/release/python
next to it is found).  See docs/python.md.

Command line:
    blender -b scene.blend --python tools/blender/inbetween_follow_path.py -- \
        --object Cube --path examples/curves/natural.json \
        --speed '{"kind": "ease", "start_frame": 1, "end_frame": 48, "ease": {"kind": "sine"}}' \
        --orientation rotation_minimizing [--frames 1:60] [--write-scene out.json] [--save out.blend]
"""
import argparse
import json
import os
import pathlib
import sys

bl_info = {
    "name": "inbetween: Follow Path",
    "author": "inbetween",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Object > Animation > inbetween: Follow Path",
    "description": "Key the active object along a curve at a chosen speed (ease or distance-time keys) with an orientation mode",
    "category": "Animation",
}

ORIENTATIONS = ["rotation_minimizing", "frenet", "up", "look_at", "none"]


def import_inbetween(module_dir=None):
    """Imports the inbetween module: module_dir, $INBETWEEN_PYTHON_PATH, or the source tree's build."""
    candidates = [module_dir, os.environ.get("INBETWEEN_PYTHON_PATH")]
    here = pathlib.Path(__file__).resolve().parent
    candidates += [str(here.parents[1] / "build" / "release" / "python")]
    for c in candidates:
        if c and c not in sys.path and pathlib.Path(c, "inbetween").is_dir():
            sys.path.insert(0, c)
            break
    import inbetween  # noqa: E402
    return inbetween


# ------------------------------------------------------------------------------ axes
def to_scene(p):
    """A Blender point (x, y, z) in scene axes (x, z, -y)."""
    return [p[0], p[2], -p[1]]


def to_blender(p):
    """A scene point (x, y, z) in Blender axes (x, -z, y)."""
    return [p[0], -p[2], p[1]]


def quat_to_blender(w, x, y, z):
    """R_blender = C R_scene C^T: the rotation axis maps like a point, the angle stays."""
    bx, by, bz = to_blender([x, y, z])
    return [w, bx, by, bz]


# ------------------------------------------------------------------------------ the path
def curve_dict_from_blender(curve_object):
    """A curve-file dictionary (scene axes) of the first spline of a Blender curve object, in world
    space: a Bezier spline becomes "bezier-path" (points and handles), a poly spline "catmull-rom"."""
    import bpy
    bpy.context.view_layer.update()  # matrix_world of an object moved by a script is stale until then
    m = curve_object.matrix_world
    spline = curve_object.data.splines[0]
    if spline.type == "BEZIER":
        pts = []
        bp = spline.bezier_points
        for i, b in enumerate(bp):
            if i > 0:
                pts.append(to_scene(m @ b.handle_left))
            pts.append(to_scene(m @ b.co))
            if i + 1 < len(bp):
                pts.append(to_scene(m @ b.handle_right))
        return {"type": "bezier-path", "points": [list(map(float, p)) for p in pts]}
    pts = [to_scene(m @ p.co.xyz) for p in spline.points]
    return {"type": "catmull-rom", "points": [list(map(float, p)) for p in pts]}


def scene_dict(object_name, curve, speed, orientation, fps, frame_range, look_at=None):
    """The version-2 scene with the object on the path: what `inbetween bake` evaluates."""
    leg = {"curve": "path", "speed": speed}
    if orientation != "none":
        leg["orientation"] = {"mode": orientation}
        if orientation == "look_at":
            leg["orientation"]["look_at"] = list(look_at or [0.0, 0.0, 0.0])
    return {"inbetween": 2, "fps": fps, "range": list(frame_range),
            "paths": [{"name": "path", "curve": curve}],
            "objects": [{"name": object_name, "path": [leg]}]}


def key_object(ib, obj, scene, frames):
    """Bakes `scene` at `frames` and keys obj's location (and rotation unless none) per frame."""
    import numpy as np
    values, columns = ib.bake(scene, np.asarray(frames, dtype=float))
    name = scene["objects"][0]["name"]
    tx = [columns.index(f"{name}.translation.{c}") for c in "xyz"]
    rq = [columns.index(f"{name}.rotation.{c}") for c in "wxyz"]
    orient = "orientation" in scene["objects"][0]["path"][0]
    if orient:
        obj.rotation_mode = "QUATERNION"
    for row in values:
        f = float(row[0])
        obj.location = to_blender(row[tx])
        obj.keyframe_insert("location", frame=f)
        if orient:
            obj.rotation_quaternion = quat_to_blender(*row[rq])
            obj.keyframe_insert("rotation_quaternion", frame=f)
    if obj.animation_data and obj.animation_data.action:
        for fc in obj.animation_data.action.fcurves:
            for k in fc.keyframe_points:
                k.interpolation = "LINEAR"
    return values, columns


def speed_frame_range(speed, default):
    """The frames over which a speed dictionary moves: an ease's span, the first and last key."""
    kind = speed.get("kind", "ease")
    if kind == "ease":
        return speed.get("start_frame", 0), speed.get("end_frame", 1)
    keys = speed.get("keys") if kind == "distance_keys" else speed.get("velocities")
    if keys:
        return keys[0]["frame"], keys[-1]["frame"]
    return default


# ------------------------------------------------------------------------------ add-on
def _register_operator():
    import bpy

    class INBETWEEN_OT_follow_path(bpy.types.Operator):
        """Key the active object along a curve (the other selected curve object, or a curve file)"""
        bl_idname = "object.inbetween_follow_path"
        bl_label = "inbetween: Follow Path"
        bl_options = {"REGISTER", "UNDO"}

        curve_file: bpy.props.StringProperty(name="Curve file", subtype="FILE_PATH",
                                             description="Curve file (JSON); empty: the other selected curve object")
        ease: bpy.props.EnumProperty(name="Ease", items=[(k, k, "") for k in
                                     ["linear", "sine", "cubic", "sine_pieces", "constant_acceleration"]], default="sine")
        speed_json: bpy.props.StringProperty(name="Speed JSON", default="",
                                             description="A scene file's speed dictionary; overrides Ease")
        start_frame: bpy.props.IntProperty(name="Start", default=1)
        end_frame: bpy.props.IntProperty(name="End", default=48)
        orientation: bpy.props.EnumProperty(name="Orientation", items=[(k, k, "") for k in ORIENTATIONS],
                                            default="rotation_minimizing")

        def execute(self, context):
            ib = import_inbetween()
            obj = context.active_object
            if self.curve_file:
                curve = json.loads(pathlib.Path(bpy.path.abspath(self.curve_file)).read_text())
            else:
                others = [o for o in context.selected_objects if o is not obj and o.type == "CURVE"]
                if not others:
                    self.report({"ERROR"}, "select a curve object (or give a curve file) and the object to move")
                    return {"CANCELLED"}
                curve = curve_dict_from_blender(others[0])
            speed = json.loads(self.speed_json) if self.speed_json else {
                "kind": "ease", "start_frame": self.start_frame, "end_frame": self.end_frame, "ease": {"kind": self.ease}}
            fps = context.scene.render.fps / context.scene.render.fps_base
            scene = scene_dict(obj.name, curve, speed, self.orientation, fps, (self.start_frame, self.end_frame))
            try:
                key_object(ib, obj, scene, range(self.start_frame, self.end_frame + 1))
            except ib.Error as e:
                self.report({"ERROR"}, str(e))
                return {"CANCELLED"}
            return {"FINISHED"}

    def menu(self, context):
        self.layout.operator(INBETWEEN_OT_follow_path.bl_idname)

    bpy.utils.register_class(INBETWEEN_OT_follow_path)
    bpy.types.VIEW3D_MT_object_animation.append(menu)
    return INBETWEEN_OT_follow_path, menu


_registered = []


def register():
    _registered.extend(_register_operator())


def unregister():
    import bpy
    if _registered:
        cls, menu = _registered
        bpy.types.VIEW3D_MT_object_animation.remove(menu)
        bpy.utils.unregister_class(cls)
        _registered.clear()


# ------------------------------------------------------------------------------ command line
def main(argv):
    import bpy
    ap = argparse.ArgumentParser(prog="inbetween_follow_path.py", description=__doc__.split("\n")[0])
    ap.add_argument("--object", help="object to move (default: the active object, else a new empty)")
    ap.add_argument("--path", required=True, help="curve file (JSON), or the name of a Blender curve object")
    ap.add_argument("--speed", required=True, help="speed dictionary (JSON text or file)")
    ap.add_argument("--orientation", default="rotation_minimizing", choices=ORIENTATIONS)
    ap.add_argument("--look-at", type=float, nargs=3, help="look_at target (scene axes)")
    ap.add_argument("--frames", help="A:B frames to key (default: the speed's frame range)")
    ap.add_argument("--fps", type=float, help="frames per second (default: the Blender scene's)")
    ap.add_argument("--module-dir", help="folder holding the inbetween package (build/release/python)")
    ap.add_argument("--write-scene", help="also write the equivalent inbetween scene file here")
    ap.add_argument("--save", help="save the .blend file here")
    args = ap.parse_args(argv)
    ib = import_inbetween(args.module_dir)

    if args.path in bpy.data.objects and bpy.data.objects[args.path].type == "CURVE":
        curve = curve_dict_from_blender(bpy.data.objects[args.path])
    else:
        curve = json.loads(pathlib.Path(args.path).read_text())
    speed_text = args.speed if args.speed.lstrip().startswith("{") else pathlib.Path(args.speed).read_text()
    speed = json.loads(speed_text)
    if args.object:
        obj = bpy.data.objects.get(args.object) or bpy.data.objects.new(args.object, None)
    else:
        obj = bpy.context.active_object or bpy.data.objects.new("Mover", None)
    if obj.name not in bpy.context.scene.collection.all_objects:
        bpy.context.scene.collection.objects.link(obj)
    render = bpy.context.scene.render
    fps = args.fps or render.fps / render.fps_base
    if args.frames:
        a, b = (float(x) for x in args.frames.split(":"))
    else:
        a, b = speed_frame_range(speed, (bpy.context.scene.frame_start, bpy.context.scene.frame_end))
    frames = [a + i for i in range(int(b - a) + 1)]
    scene = scene_dict(obj.name, curve, speed, args.orientation, fps, (a, b), args.look_at)
    if args.write_scene:
        pathlib.Path(args.write_scene).write_text(json.dumps(scene, indent=1) + "\n")
    key_object(ib, obj, scene, frames)
    bpy.context.scene.frame_start, bpy.context.scene.frame_end = int(a), int(b)
    if args.save:
        bpy.ops.wm.save_as_mainfile(filepath=str(pathlib.Path(args.save).resolve()))
    print(f"inbetween_follow_path: keyed {obj.name} on {len(frames)} frames ({args.orientation})")


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    try:
        import bpy  # noqa: F401
    except ImportError:
        sys.exit("run inside Blender: blender -b --python tools/blender/inbetween_follow_path.py -- ...")
    main(argv)
