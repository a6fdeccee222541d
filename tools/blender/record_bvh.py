"""Records Blender's world joint positions of a BVH clip for tests/io/bvh_reference_test.cpp.

Run inside Blender (Debian package blender, 3.4.1):

    blender -b --factory-startup --python-exit-code 1 --python tools/blender/record_bvh.py -- \\
        CLIP.bvh OUT.blender.bin [--rotations]

Imports CLIP with Blender's own BVH importer (io_anim_bvh) as a user would, with no axis conversion
(forward Y, up Z: the armature's matrix_world is the identity), rotate_mode QUATERNION (its Euler
modes are off by up to 1e-4 rad near gimbal lock), scale 1, one BVH frame per Blender frame from
frame 1 (use_fps_scale off), then for every frame and every joint records the world position of the
bone's head: armature matrix_world @ pose_bone.head, after scene.frame_set().

OUT: one line of JSON (the header), then little-endian float32 values, frame-major: for each frame
(MOTION line, from 0) and joint (the armature's bone order, which is the file's) tx ty tz.  Blender
keeps these in float32 (mathutils), so float32 storage loses nothing.

--rotations adds qw qx qy qz: the joint's world rotation, pose_bone.matrix @ bone.matrix_local⁻¹
(Blender's bones point along their length, so the rest orientation is divided out).  The test does
not hold these: the importer computes each key as rest⁻¹ · R · rest in float32 and Blender
recomposes it, which leaves about 1e-5 rad of rest-matrix error (tests/data/bvh/README.md has the
measured figure); positions are held to Blender, rotations to three.js.

Two things the recording works around:
- Debian's Blender 3.4 runs Python 3.11, where open(path, 'rU') raises ValueError ('U' mode was
  removed); the importer module's `open` is replaced by one that drops the 'U'.
- Blender reads every line after MOTION, even beyond the declared `Frames:` count (Boxing_Toes.bvh
  declares 3069 and has 3070): all of them are recorded; the header gives both counts.
"""

import builtins
import hashlib
import json
import os
import struct
import sys

import bpy
import mathutils


def _open_without_u(file, mode="r", *args, **kwargs):
    """open() as Python 2/3.10 read 'rU': universal newlines are the default of text mode."""
    return builtins.open(file, mode.replace("U", ""), *args, **kwargs)


def main(argv):
    if len(argv) < 2:
        sys.exit("usage: blender -b --python record_bvh.py -- CLIP.bvh OUT.blender.bin [--rotations]")
    clip, out = argv[0], argv[1]
    rotations = "--rotations" in argv[2:]

    import io_anim_bvh.import_bvh as importer  # enabled in the factory settings
    importer.open = _open_without_u

    bpy.ops.wm.read_factory_settings(use_empty=True)
    result = bpy.ops.import_anim.bvh(filepath=os.path.abspath(clip), axis_forward="Y", axis_up="Z",
                                     rotate_mode="QUATERNION", global_scale=1.0, frame_start=1,
                                     use_fps_scale=False, update_scene_fps=False,
                                     update_scene_duration=False, use_cyclic=False)
    if result != {"FINISHED"}:
        sys.exit(f"record_bvh: the import of {clip} returned {result}")
    arm = next(o for o in bpy.context.scene.objects if o.type == "ARMATURE")
    if arm.matrix_world != mathutils.Matrix.Identity(4):
        sys.exit(f"record_bvh: the armature's matrix_world is not the identity: {arm.matrix_world}")
    action = arm.animation_data.action
    first, last = (int(round(f)) for f in action.frame_range)
    frames = last - first + 1
    bones = list(arm.pose.bones)
    rest_inv = [b.bone.matrix_local.to_3x3().inverted() for b in bones]

    with open(clip, "rb") as f:
        source = f.read()
    text = source.decode("latin-1")
    declared = int(text.split("Frames:")[1].split()[0])
    frame_time = float(text.split("Frame Time:")[1].split()[0])

    scene = bpy.context.scene
    values = []
    for frame in range(first, last + 1):
        scene.frame_set(frame)
        for b, inv in zip(bones, rest_inv):
            head = arm.matrix_world @ b.head
            values.extend(head)
            if rotations:
                q = ((arm.matrix_world @ b.matrix).to_3x3() @ inv).to_quaternion()
                values.extend((q.w, q.x, q.y, q.z))

    header = {
        "format": "inbetween-bvh-reference-1",
        "tool": f"Blender {bpy.app.version_string} io_anim_bvh "
                + ".".join(str(v) for v in __import__("io_anim_bvh").bl_info["version"]),
        "source": os.path.basename(clip),
        "source_bytes": len(source),
        "source_sha256": hashlib.sha256(source).hexdigest(),
        "declared_frames": declared,
        "frames": frames,
        "frame_time": frame_time,
        "joints": [b.name for b in bones],
        "values": ["tx", "ty", "tz"] + (["qw", "qx", "qy", "qz"] if rotations else []),
        "dtype": "float32 little-endian",
        "layout": "frame, joint, value",
        "sampled_at": f"Blender frame {first} + i for MOTION line i (import frame_start 1, use_fps_scale off)",
    }
    tmp = out + ".tmp"
    with open(tmp, "wb") as f:
        f.write((json.dumps(header, separators=(",", ":")) + "\n").encode("utf-8"))
        f.write(struct.pack(f"<{len(values)}f", *values))
    os.replace(tmp, out)
    print(f"record_bvh: {out}: {frames} frames x {len(bones)} joints ({header['tool']})")


main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
