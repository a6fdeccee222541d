"""Blender 3.4's FBX importer as the reference for inbetween's assimp reader (docs/assimp.md).

Run inside Blender (Debian package blender, 3.4.1):

    blender -b --factory-startup --python-exit-code 1 --python tools/blender/record_assimp_fbx.py -- \\
        /usr/share/assimp/models/FBX/animation_with_skeleton.fbx \\
        tests/data/assimp/animation_with_skeleton-blender-3.4.1.json

Imports the FBX keeping the file's axes and units (use_manual_orientation with forward Y, up Z:
axis_conversion() from (Y, Z) to Blender's (Y, Z) is the identity; global_scale =
100 / UnitScaleFactor cancels the importer's unit factor UnitScaleFactor / 100; anim_offset 0 keeps FBX frame f
at Blender frame f), so world coordinates and frames are the file's, as assimp gives them.  Then
for every frame of the imported action (scene.frame_set(f), f from the action's first to its last
frame, at the file's frame rate, which the importer sets as the scene's fps) it records

  * every pose bone: its world matrix arm.matrix_world @ pose_bone.matrix, i.e. the joint's world
    position (the bone's head) and its world rotation.  With the importer's default bone axes
    (primary Y, secondary X) and automatic bone orientation off, Blender's bone correction matrix
    is the identity, so the bone's matrix is the FBX node's world transform and rotations are
    comparable; the test still checks that before comparing them (rest pose equal).
  * every other object (the armature object, meshes, camera, light): its world position only.
    Blender turns cameras and lights to its own view axis (they look down −Z, FBX's down +X), so
    their rotations are not the file's.

Output: one JSON object, numbers as Blender gives them (float32 storage, printed with repr of the
float64 Python value):

    {"blender_version": "3.4.1", "file": "animation_with_skeleton.fbx", "fps": 24,
     "frames": [f0, …], "import": {settings},
     "joints": {"Bone": {"position": [[x, y, z] per frame], "rotation": [[w, x, y, z] per frame]}, …},
     "objects": {"Armature": {"position": [[x, y, z] per frame]}, …}}

tests/io/assimp_blender_test.cpp compares inbetween's world transforms against it.
"""

import json
import os
import sys

import bpy

IMPORT_SETTINGS = {
    "use_manual_orientation": True,
    "axis_forward": "Y",
    "axis_up": "Z",
    "global_scale": 1.0,
    "bake_space_transform": False,
    "automatic_bone_orientation": False,
    "primary_bone_axis": "Y",
    "secondary_bone_axis": "X",
    "ignore_leaf_bones": False,
    "use_prepost_rot": True,
    "use_anim": True,
    "anim_offset": 0.0,
}


def fbx_unit_scale_factor(path):
    """GlobalSettings' UnitScaleFactor, read with the importer's own parser."""
    from io_scene_fbx import parse_fbx
    root, _ = parse_fbx.parse(path)
    for elem in root.elems:
        if elem.id != b"GlobalSettings":
            continue
        for props in elem.elems:
            if props.id != b"Properties70":
                continue
            for p in props.elems:
                if p.props and p.props[0] == b"UnitScaleFactor":
                    return float(p.props[4])
    return 1.0


def rounded(values):
    return [float(v) for v in values]


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 2:
        sys.exit("usage: blender -b --python record_assimp_fbx.py -- IN.fbx OUT.json")
    source, target = argv
    bpy.ops.wm.read_factory_settings(use_empty=True)
    # Blender 3.4's importer multiplies lengths by global_scale · UnitScaleFactor /
    # units_blender_to_fbx_factor(scene), the last 100 in a factory scene (fbx_utils.py: 100 with no
    # unit system, 100 · scale_length otherwise): global_scale = 100 / UnitScaleFactor keeps the
    # file's lengths.
    unit_scale = fbx_unit_scale_factor(source)
    settings = dict(IMPORT_SETTINGS, global_scale=100.0 / unit_scale)
    bpy.ops.import_scene.fbx(filepath=source, **settings)
    scene = bpy.context.scene
    actions = [a for a in bpy.data.actions]
    if not actions:
        sys.exit("no action imported")
    first = min(int(round(a.frame_range[0])) for a in actions)
    last = max(int(round(a.frame_range[1])) for a in actions)
    frames = list(range(first, last + 1))
    joints, objects = {}, {}
    for frame in frames:
        scene.frame_set(frame)
        for obj in scene.objects:
            objects.setdefault(obj.name, {"position": []})["position"].append(rounded(obj.matrix_world.translation))
            if obj.type != "ARMATURE":
                continue
            for bone in obj.pose.bones:
                world = obj.matrix_world @ bone.matrix
                entry = joints.setdefault(bone.name, {"position": [], "rotation": []})
                entry["position"].append(rounded(world.translation))
                q = world.to_quaternion()
                entry["rotation"].append(rounded((q.w, q.x, q.y, q.z)))
    out = {
        "blender_version": ".".join(str(v) for v in bpy.app.version),
        "file": os.path.basename(source),
        "fps": scene.render.fps / scene.render.fps_base,
        "frames": frames,
        "import": settings,
        "unit_scale_factor": unit_scale,
        "joints": joints,
        "objects": objects,
    }
    os.makedirs(os.path.dirname(os.path.abspath(target)), exist_ok=True)
    with open(target, "w") as f:
        f.write("{\n")
        head = {k: out[k] for k in ("blender_version", "file", "fps", "unit_scale_factor", "import", "frames")}
        for k, v in head.items():
            f.write(f"  {json.dumps(k)}: {json.dumps(v)},\n")
        for group in ("joints", "objects"):
            f.write(f"  {json.dumps(group)}: {{\n")
            names = list(out[group])
            for i, name in enumerate(names):
                sep = "," if i + 1 < len(names) else ""
                f.write(f"    {json.dumps(name)}: {json.dumps(out[group][name])}{sep}\n")
            f.write("  }" + (",\n" if group == "joints" else "\n"))
        f.write("}\n")
    print(f"wrote {target}: {len(joints)} joints, {len(objects)} objects, frames {first}..{last}")


main()
