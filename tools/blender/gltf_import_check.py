# Loads a .glb/.gltf with Blender's own glTF importer and prints each object's world transform at
# the requested frames, converted back to glTF's axes (Blender is Z-up: glTF (x, y, z) is Blender
# (x, −z, y)).  For a camera object also its view direction (Blender cameras look down their local
# −Z) and up direction (local +Y) in glTF's axes, and its vertical field of view (angle_y, radians).
# usage: blender -b --factory-startup --python gltf_import_check.py -- FILE FPS FRAME_OFFSET N
#   samples Blender frames FRAME_OFFSET + k for k = 0 … N−1; prints one JSON object on a line
#   starting with "RESULT ": {"frames": [...], "objects": {name: [[t, q(wxyz), s] per frame]},
#   "cameras": {name: {"yfov": rad, "view": [[x, y, z] per frame], "up": [[x, y, z] per frame]}}}.
import json
import sys

import bpy
from mathutils import Matrix, Quaternion, Vector

argv = sys.argv[sys.argv.index("--") + 1:]
path, fps, offset, count = argv[0], float(argv[1]), float(argv[2]), int(argv[3])
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o, do_unlink=True)
scene = bpy.context.scene
scene.render.fps = int(round(fps))
scene.render.fps_base = scene.render.fps / fps
bpy.ops.import_scene.gltf(filepath=path)
# Blender (Z-up) → glTF (Y-up): the importer applied glTF_from... the inverse of this rotation.
blender_to_gltf = Matrix(((1, 0, 0, 0), (0, 0, 1, 0), (0, -1, 0, 0), (0, 0, 0, 1)))
out = {"frames": [], "objects": {}, "cameras": {}}
for o in scene.objects:
    if o.type == "CAMERA":
        out["cameras"][o.name] = {"yfov": o.data.angle_y, "sensor_fit": o.data.sensor_fit, "view": [], "up": []}
for k in range(count):
    frame = offset + k
    scene.frame_set(int(frame), subframe=frame - int(frame))
    out["frames"].append(frame)
    for o in scene.objects:
        m = blender_to_gltf @ o.matrix_world @ blender_to_gltf.inverted()
        t, q, s = m.decompose()
        out["objects"].setdefault(o.name, []).append([t.x, t.y, t.z, q.w, q.x, q.y, q.z, s.x, s.y, s.z])
        if o.type == "CAMERA":
            r = blender_to_gltf.to_3x3() @ o.matrix_world.to_3x3()
            view, up = r @ Vector((0, 0, -1)), r @ Vector((0, 1, 0))
            out["cameras"][o.name]["view"].append([view.x, view.y, view.z])
            out["cameras"][o.name]["up"].append([up.x, up.y, up.z])
print("RESULT " + json.dumps(out))
