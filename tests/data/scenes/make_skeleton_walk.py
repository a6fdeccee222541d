#!/usr/bin/env python3
"""Writes skeleton_walk.json: a character-sized hierarchy for the plot and preview tests.

The 31 joints of the CMU skeleton (names, parents and rest offsets shaped like
/usr/share/assimp/models/BVH/01_01.bvh), the root walking along +x and bobbing, every joint turning
about its own axis; keys every 8 frames over frames 0-96 at 120 fps (quaternion keys, slerp).
Regenerate: /usr/bin/python3 tests/data/scenes/make_skeleton_walk.py > tests/data/scenes/skeleton_walk.json
A longer clip for measuring (docs/preview.md): make_skeleton_walk.py LAST_FRAME KEY_STEP, e.g. 4510 1
(01_03.bvh's 4 511 frames, a key on every frame).
"""
import json
import math
import sys

JOINTS = [("Hips", None, (0, 0, 0)), ("LHipJoint", "Hips", (0, 0, 0)), ("LeftUpLeg", "LHipJoint", (1.6, -1.9, 0.8)),
          ("LeftLeg", "LeftUpLeg", (2.4, -6.7, 0)), ("LeftFoot", "LeftLeg", (2.5, -6.9, 0)),
          ("LeftToeBase", "LeftFoot", (0.1, -0.4, 2.2)), ("RHipJoint", "Hips", (0, 0, 0)),
          ("RightUpLeg", "RHipJoint", (-1.6, -1.9, 0.8)), ("RightLeg", "RightUpLeg", (-2.4, -6.7, 0)),
          ("RightFoot", "RightLeg", (-2.5, -6.9, 0)), ("RightToeBase", "RightFoot", (-0.1, -0.4, 2.2)),
          ("LowerBack", "Hips", (0, 0, 0)), ("Spine", "LowerBack", (0, 2.0, -0.1)), ("Spine1", "Spine", (0, 2.0, 0)),
          ("Neck", "Spine1", (0, 2.0, 0)), ("Neck1", "Neck", (0, 1.6, 0.1)), ("Head", "Neck1", (0, 1.6, 0.1)),
          ("LeftShoulder", "Spine1", (0, 0, 0)), ("LeftArm", "LeftShoulder", (3.4, 1.8, 0.5)),
          ("LeftForeArm", "LeftArm", (5.3, 0, 0)), ("LeftHand", "LeftForeArm", (3.6, 0, 0)),
          ("LeftFingerBase", "LeftHand", (0, 0, 0)), ("LeftHandIndex1", "LeftFingerBase", (0.7, 0, 0)),
          ("LThumb", "LeftHand", (0, 0, 0)), ("RightShoulder", "Spine1", (0, 0, 0)),
          ("RightArm", "RightShoulder", (-3.4, 1.8, 0.5)), ("RightForeArm", "RightArm", (-5.3, 0, 0)),
          ("RightHand", "RightForeArm", (-3.6, 0, 0)), ("RightFingerBase", "RightHand", (0, 0, 0)),
          ("RightHandIndex1", "RightFingerBase", (-0.7, 0, 0)), ("RThumb", "RightHand", (0, 0, 0))]


def r6(v):
    return round(v, 6)


def main():
    last = int(sys.argv[1]) if len(sys.argv) > 1 else 96
    every = int(sys.argv[2]) if len(sys.argv) > 2 else 8
    objects = []
    for j, (name, parent, offset) in enumerate(JOINTS):
        rotation, translation = [], []
        for f in range(0, last + 1, every):
            t = f / 120
            phase = 2 * math.pi * 0.8 * t + 0.7 * j
            angle = (0.35 if ("Leg" in name or "Arm" in name) else 0.12) * math.sin(phase)
            axis = (1, 0.2 * math.sin(j), 0.1)
            n = math.sqrt(sum(a * a for a in axis))
            s = math.sin(angle / 2) / n
            rotation.append({"frame": f, "value": [r6(math.cos(angle / 2))] + [r6(a * s) for a in axis]})
            translation.append({"frame": f, "value": [r6(10 * t), r6(17 + 0.5 * math.sin(2 * phase)), 0]})
        o = {"name": name}
        if parent:
            o["parent"] = parent
            o["translation"] = list(offset)
        else:
            o["translation"] = {"keys": translation}
        o["rotation"] = {"keys": rotation}
        objects.append(o)
    print(json.dumps({"inbetween": 1, "fps": 120, "range": [0, last], "objects": objects}, separators=(",", ":")))


if __name__ == "__main__":
    main()
