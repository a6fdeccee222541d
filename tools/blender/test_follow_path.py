"""Test of inbetween_follow_path.py inside Blender (ctest python.blender; skipped only where
`blender` is absent): keys an object along curves at several speeds and orientation modes, reads
back what Blender evaluates at every keyed frame (matrix_world), and compares it with
`inbetween bake` of the equivalent scene file written here, independently of the script, mapped
to Blender's axes (Blender (x, y, z) = scene (x, -z, y); docs/python.md).

    INBETWEEN_CLI=build/release/inbetween INBETWEEN_PYTHON_PATH=build/release/python \\
        /usr/bin/python3 tools/blender/test_follow_path.py
"""
import csv
import io
import json
import math
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
SOURCE = HERE.parents[1]
# Blender keeps keyframe values and evaluates matrix_world in float32: positions agree to a few
# float32 ulp of their size (2^-24 relative; 8 ulp allows the matrix_world round trip), rotations
# to the angle a few float32 ulp of the quaternion components make (measured 1.6e-7 rad at most).
POSITION_ULPS = 8
ROTATION_RAD = 2e-6

CASES = [
    {"name": "natural-sine-rmf", "curve": "examples/curves/natural.json",
     "speed": {"kind": "ease", "start_frame": 1, "end_frame": 40, "ease": {"kind": "sine"}},
     "orientation": "rotation_minimizing"},
    {"name": "catmull-keys-up", "curve": "examples/curves/catmull-rom-centripetal.json",
     "speed": {"kind": "distance_keys", "fraction": True,
               "keys": [{"frame": 1, "distance": 0}, {"frame": 12, "distance": 0.2},
                        {"frame": 30, "distance": 0.9}, {"frame": 36, "distance": 1}]},
     "orientation": "up"},
    {"name": "bezier-accel-frenet", "curve": "examples/curves/bezier-path.json",
     "speed": {"kind": "ease", "start_frame": 5, "end_frame": 50,
               "ease": {"kind": "constant_acceleration", "accel_frames": 10, "decel_frames": 15}},
     "orientation": "frenet"},
    {"name": "helix-bezier-none", "curve": "examples/curves/bspline-periodic-3d.json",
     "speed": {"kind": "ease", "start_frame": 0, "end_frame": 24, "ease": {"kind": "cubic_bezier",
                                                                        "x1": 0.42, "y1": 0, "x2": 0.58, "y2": 1}},
     "orientation": "none"},
]

DUMP = """
import bpy, json, os
obj = bpy.data.objects["Mover"]
out = []
for f in json.loads(os.environ["FOLLOW_FRAMES"]):
    bpy.context.scene.frame_set(int(f))
    m = obj.matrix_world
    q = m.to_quaternion()
    out.append([f, *m.translation, q.w, q.x, q.y, q.z])
open(os.environ["FOLLOW_DUMP"], "w").write(json.dumps(out))
"""


def skip(reason):
    # The marker ctest's SKIP_REGULAR_EXPRESSION and tools/report_skips.sh read.
    print(f"test_follow_path.py: Skipped\n{reason}\n[  SKIPPED ] python.blender")
    sys.exit(0)


def main():
    blender = shutil.which("blender")
    if blender is None:
        skip("blender is not installed (Debian package blender)")
    cli = os.environ.get("INBETWEEN_CLI") or str(SOURCE / "build" / "release" / "inbetween")
    module_dir = os.environ.get("INBETWEEN_PYTHON_PATH") or str(SOURCE / "build" / "release" / "python")
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for case in CASES:
            curve = json.loads((SOURCE / case["curve"]).read_text())
            speed = case["speed"]
            a = speed.get("start_frame", speed.get("keys", [{}])[0].get("frame"))
            b = speed.get("end_frame", speed.get("keys", [{}])[-1].get("frame"))
            frames = list(range(int(a), int(b) + 1))
            # The equivalent scene, written here (not by the script under test).
            leg = {"curve": "p", "speed": speed}
            if case["orientation"] != "none":
                leg["orientation"] = {"mode": case["orientation"]}
            scene = {"inbetween": 2, "fps": 24, "range": [a, b], "paths": [{"name": "p", "curve": curve}],
                     "objects": [{"name": "Mover", "path": [leg]}]}
            scene_file = tmp / f"{case['name']}.json"
            scene_file.write_text(json.dumps(scene))
            baked = subprocess.run([cli, "bake", scene_file], capture_output=True, text=True, check=True).stdout
            rows = list(csv.reader(io.StringIO(baked)))
            header, table = rows[0], [[float(x) for x in r] for r in rows[1:]]
            col = {n: i for i, n in enumerate(header)}
            dump = tmp / f"{case['name']}.dump.json"
            env = dict(os.environ, FOLLOW_FRAMES=json.dumps(frames), FOLLOW_DUMP=str(dump))
            r = subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1",
                                "--python", str(HERE / "inbetween_follow_path.py"), "--python-expr", DUMP, "--",
                                "--object", "Mover", "--path", str(SOURCE / case["curve"]),
                                "--speed", json.dumps(speed), "--orientation", case["orientation"],
                                "--fps", "24", "--module-dir", module_dir],
                               capture_output=True, text=True, env=env)
            if r.returncode != 0 or not dump.exists():
                print(f"FAIL {case['name']}: blender exited {r.returncode}\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}")
                failures += 1
                continue
            keyed = json.loads(dump.read_text())
            worst_p, worst_r = 0.0, 0.0
            for row, k in zip(table, keyed):
                assert row[0] == k[0], (row[0], k[0])
                p = [row[col[f"Mover.translation.{c}"]] for c in "xyz"]
                want = [p[0], -p[2], p[1]]  # scene -> Blender axes
                for w, g in zip(want, k[1:4]):
                    err = abs(w - g) / (max(1.0, abs(w)) * 2.0**-24)
                    worst_p = max(worst_p, err)
                if case["orientation"] != "none":
                    qw, qx, qy, qz = (row[col[f"Mover.rotation.{c}"]] for c in "wxyz")
                    want_q = [qw, qx, -qz, qy]
                    got_q = k[4:8]
                    sign = 1.0 if sum(x * y for x, y in zip(want_q, got_q)) >= 0 else -1.0
                    # Angle between the rotations, 2 atan2(|a - b|, |a + b|) (acos of the dot loses
                    # half the digits near 0).
                    diff = math.sqrt(sum((x - sign * y) ** 2 for x, y in zip(want_q, got_q)))
                    summ = math.sqrt(sum((x + sign * y) ** 2 for x, y in zip(want_q, got_q)))
                    worst_r = max(worst_r, 2 * math.atan2(diff, summ))
            ok = worst_p <= POSITION_ULPS and worst_r <= ROTATION_RAD and len(keyed) == len(table)
            print(f"{'ok  ' if ok else 'FAIL'} {case['name']}: {len(keyed)} frames, position {worst_p:.2f} float32 ulp "
                  f"(limit {POSITION_ULPS}), rotation {worst_r:.2e} rad (limit {ROTATION_RAD})")
            failures += not ok
        failures += blender_curve_case(blender, cli, module_dir, tmp)
    sys.exit(1 if failures else 0)


MAKE_CURVE = """
import bpy
cu = bpy.data.curves.new("TrackCurve", "CURVE")
cu.dimensions = "3D"
sp = cu.splines.new("BEZIER")
sp.bezier_points.add(2)
for b, co, hl, hr in zip(sp.bezier_points,
                         [(0, 0, 0), (4, 2, 1), (8, 0, 3)],
                         [(-1, -1, 0), (3, 1, 1), (7, 1, 2)],
                         [(1, 1, 0), (5, 3, 1), (9, -1, 4)]):
    b.co, b.handle_left, b.handle_right = co, hl, hr
    b.handle_left_type = b.handle_right_type = "FREE"
ob = bpy.data.objects.new("TrackCurve", cu)
ob.location = (1, 2, 3)
bpy.context.scene.collection.objects.link(ob)
"""


def blender_curve_case(blender, cli, module_dir, tmp):
    """The path taken from a Blender Bezier curve object (world space, moved by its location): the
    keyed positions equal `inbetween bake` of the scene the script wrote, and the first and last
    keyed positions are the curve's own end points (Blender coordinates, independent of the
    conversion)."""
    dump, scene_file = tmp / "blender-curve.dump.json", tmp / "blender-curve.json"
    frames = list(range(1, 31))
    env = dict(os.environ, FOLLOW_FRAMES=json.dumps(frames), FOLLOW_DUMP=str(dump))
    speed = {"kind": "ease", "start_frame": 1, "end_frame": 30, "ease": {"kind": "cubic"}}
    r = subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python-expr", MAKE_CURVE,
                        "--python", str(HERE / "inbetween_follow_path.py"), "--python-expr", DUMP, "--",
                        "--object", "Mover", "--path", "TrackCurve", "--speed", json.dumps(speed),
                        "--orientation", "rotation_minimizing", "--fps", "24", "--module-dir", module_dir,
                        "--write-scene", str(scene_file)], capture_output=True, text=True, env=env)
    if r.returncode != 0 or not dump.exists():
        print(f"FAIL blender-curve: blender exited {r.returncode}\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}")
        return 1
    keyed = json.loads(dump.read_text())
    rows = list(csv.reader(io.StringIO(subprocess.run([cli, "bake", scene_file], capture_output=True, text=True,
                                                      check=True).stdout)))
    col = {n: i for i, n in enumerate(rows[0])}
    worst = 0.0
    for row, k in zip(rows[1:], keyed):
        p = [float(row[col[f"Mover.translation.{c}"]]) for c in "xyz"]
        for w, g in zip([p[0], -p[2], p[1]], k[1:4]):
            worst = max(worst, abs(w - g) / (max(1.0, abs(w)) * 2.0**-24))
    # The curve's end points in Blender's world: (0, 0, 0) and (8, 0, 3) moved by (1, 2, 3).
    ends = max(abs(a - b) for a, b in zip(keyed[0][1:4] + keyed[-1][1:4], [1, 2, 3, 9, 2, 6]))
    ok = worst <= POSITION_ULPS and ends <= 1e-5 * 9  # float32 ulps of coordinates up to 9
    print(f"{'ok  ' if ok else 'FAIL'} blender-curve: {len(keyed)} frames, position {worst:.2f} float32 ulp, "
          f"end points off by {ends:.1e}")
    # The add-on's operator on the same selection (curve object selected, Mover active) keys the
    # same values as the script: the same doubles rounded to the same float32 keys.
    dump_op = tmp / "operator.dump.json"
    env = dict(env, FOLLOW_DUMP=str(dump_op))
    r = subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python-expr", MAKE_CURVE,
                        "--python-expr", OPERATOR, "--python-expr", DUMP],
                       capture_output=True, text=True, env=dict(env, INBETWEEN_PYTHON_PATH=module_dir,
                                                                 FOLLOW_SCRIPT=str(HERE / "inbetween_follow_path.py")))
    if r.returncode != 0 or not dump_op.exists():
        print(f"FAIL add-on operator: blender exited {r.returncode}\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}")
        return 1
    same = json.loads(dump_op.read_text()) == keyed
    print(f"{'ok  ' if same else 'FAIL'} add-on operator: keys {'equal' if same else 'differ from'} the script's")
    return 0 if ok and same else 1


OPERATOR = """
import bpy, importlib.util, os
spec = importlib.util.spec_from_file_location("inbetween_follow_path", os.environ["FOLLOW_SCRIPT"])
addon = importlib.util.module_from_spec(spec)
spec.loader.exec_module(addon)
addon.register()
mover = bpy.data.objects.new("Mover", None)
bpy.context.scene.collection.objects.link(mover)
for o in bpy.context.view_layer.objects:
    o.select_set(o.name in ("Mover", "TrackCurve"))
bpy.context.view_layer.objects.active = mover
bpy.context.scene.render.fps, bpy.context.scene.render.fps_base = 24, 1.0
result = bpy.ops.object.inbetween_follow_path(ease="cubic", start_frame=1, end_frame=30,
                                              orientation="rotation_minimizing")
assert result == {"FINISHED"}, result
"""


if __name__ == "__main__":
    main()
