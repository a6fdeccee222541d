"""Scenes and glTF from Python against the inbetween tool on the same files (the C++ results):
bake, convert, and the error text."""
import csv
import io
import json

import numpy as np
import pytest

import inbetween

SCENES = ["frame22.json", "bouncing_cube.json"]


def read_csv(text):
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


def assert_same_as_csv(values, table):
    """Double columns come back exactly from the tool's shortest round-trip text; single-precision
    (F-curve) columns are printed as the shortest float text, so they agree as float32."""
    assert values.shape == table.shape
    same = (values == table) | (values.astype(np.float32) == table.astype(np.float32))
    bad = np.argwhere(~same)
    assert bad.size == 0, f"first difference at row, column {bad[0]}: {values[tuple(bad[0])]} vs {table[tuple(bad[0])]}"


@pytest.mark.parametrize("name", SCENES)
def test_bake_equals_the_tools_csv(name, source_dir, cli):
    path = source_dir / "examples" / "scenes" / name
    header, table = read_csv(cli("bake", path).stdout)
    for source in (path, str(path), json.loads(path.read_text()), path.read_text()):
        values, columns = inbetween.bake(source)
        assert columns == header
        assert_same_as_csv(values, table)
    # A frame list with a step, as --frames A:B:STEP.
    header, table = read_csv(cli("bake", path, "--frames", "3:40:0.25").stdout)
    scene = inbetween.Scene(path)
    values, columns = scene.bake(np.arange(3, 40.0001, 0.25))
    assert_same_as_csv(values, table)


def test_gltf_bake_and_convert_equal_the_tool(source_dir, cli, tmp_path):
    scene = source_dir / "examples" / "scenes" / "bouncing_cube.json"
    ours, theirs = tmp_path / "ours.glb", tmp_path / "theirs.glb"
    report = inbetween.convert(scene, str(ours))
    cli("convert", scene, theirs, "-q")
    assert ours.read_bytes() == theirs.read_bytes()
    assert report and {"object", "path", "max_error", "refitted"} <= set(report[0])
    header, table = read_csv(cli("bake", ours, "--fps", 30).stdout)
    values, columns = inbetween.bake(str(ours), fps=30)
    assert columns == header
    assert_same_as_csv(values, table)
    # glTF back to a scene file, as `inbetween convert X.glb Y.json`.
    inbetween.convert(str(ours), str(tmp_path / "ours.json"))
    cli("convert", ours, tmp_path / "theirs.json")
    assert (tmp_path / "ours.json").read_text() == (tmp_path / "theirs.json").read_text()


def test_errors_carry_the_tools_message_and_place(cli, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"inbetween": 1, "tracks": [
        {"name": "a", "keys": [{"frame": 2, "value": 0}, {"frame": 1, "value": 0}]}]}))
    r = cli("bake", bad, check=False)
    assert r.returncode != 0
    with pytest.raises(inbetween.Error) as info:
        inbetween.bake(str(bad))
    e = info.value
    assert e.where == "/tracks/0/keys/1/frame"
    assert e.code == "KeysNotIncreasing"
    assert str(e) in r.stderr  # the tool prints "inbetween: <file>: <where>: <message>"
    # Syntax errors name the line and column, as the tool does.
    bad.write_text('{"inbetween": 1,\n "tracks": [}')
    r = cli("bake", bad, check=False)
    with pytest.raises(inbetween.Error) as info:
        inbetween.Scene(bad)
    assert info.value.where.startswith("line 2")
    assert str(info.value) in r.stderr


def test_scene_properties(source_dir):
    s = inbetween.Scene(source_dir / "examples" / "scenes" / "frame22.json")
    assert s.fps == 24 and s.range == (16, 86)
    assert s.columns[:2] == ["frame", "time"]
    values, _ = s.bake(step=2)
    np.testing.assert_array_equal(values[:, 0], np.arange(16, 87, 2.0))
    # Round trip of a version-1 scene through to_json.
    cube = inbetween.Scene(source_dir / "examples" / "scenes" / "bouncing_cube.json")
    again = inbetween.Scene(cube.to_json())
    np.testing.assert_array_equal(again.bake()[0], cube.bake()[0])


def test_bake_frames_must_be_one_dimensional(source_dir):
    s = inbetween.Scene(source_dir / "examples" / "scenes" / "bouncing_cube.json")
    with pytest.raises(ValueError, match="1-D"):
        s.bake(np.zeros((2, 3)))
    assert s.bake(5.0)[0].shape == (1, len(s.columns))  # one frame as a scalar


def test_a_device_is_refused_at_once(tmp_path):
    # Issue 21: a curve file /dev/zero was read to 4 GB; every reader now refuses non-regular files.
    scene = {"inbetween": 2, "paths": [{"name": "l", "file": "/dev/zero"}],
             "objects": [{"name": "o", "path": {"curve": "l", "speed": {"kind": "ease", "start_frame": 0, "end_frame": 1}}}]}
    with pytest.raises(inbetween.Error, match="not a regular file"):
        inbetween.Scene(scene)
    with pytest.raises(inbetween.Error, match="not a regular file"):
        inbetween.Scene("/dev/zero")


@pytest.mark.parametrize("reduce", [float("nan"), -1.0, float("inf")])
def test_convert_refuses_a_reduce_the_tool_refuses(reduce, source_dir, tmp_path):
    # Issue 21: reduce=nan or -1 was accepted (the CLI's --reduce refuses it); no file is written.
    out = tmp_path / "out.glb"
    with pytest.raises(inbetween.Error, match="reduce"):
        inbetween.convert(str(source_dir / "examples" / "scenes" / "bouncing_cube.json"), str(out), reduce=reduce)
    assert not out.exists()
