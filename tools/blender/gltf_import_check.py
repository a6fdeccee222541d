# Loads a .glb/.gltf with Blender's own glTF importer and prints each object's world transform at
# the requested frames, converted back to glTF's axes (Blender is Z-up: glTF (x, y, z) is Blender
# (x, −z, y)).
# usage: blender -b --factory-startup --python gltf_import_check.py -- FILE FPS FRAME_OFFSET N
#   samples Blender frames FRAME_OFFSET + k for k = 0 … N−1; prints one JSON object on a line
#   starting with "RESULT ".
import json
import sys

import bpy
from mathutils import Matrix, Quaternion

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
out = {"frames": [], "objects": {}}
for k in range(count):
    frame = offset + k
    scene.frame_set(int(frame), subframe=frame - int(frame))
    out["frames"].append(frame)
    for o in scene.objects:
        m = blender_to_gltf @ o.matrix_world @ blender_to_gltf.inverted()
        t, q, s = m.decompose()
        out["objects"].setdefault(o.name, []).append([t.x, t.y, t.z, q.w, q.x, q.y, q.z, s.x, s.y, s.z])
print("RESULT " + json.dumps(out))
