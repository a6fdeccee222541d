"""inbetween.load_clip: any file the tool reads, sampled in local or world space, as one
(frames, objects, 10) array.  Checked against the tool's `bake --space` CSV on the same file,
local against world through a composition written here in NumPy (independent of the library),
through glTF, and errors."""
import csv
import io
import json
import pathlib

import numpy as np
import pytest

import inbetween
from tolerances import COMPOSE_REL, GLTF_FLOAT

# A small rig: a keyed root, a scaled and turned child with keys, a grandchild, a path object under
# the root and a camera looking at the hand (every kind of object).
RIG = {
    "inbetween": 2, "fps": 30, "range": [0, 12],
    "paths": [{"name": "arc", "curve": {"type": "bezier-path",
                                        "points": [[0, 0, 0], [1, 2, 0], [3, 2, 1], [4, 0, 0]]}}],
    "objects": [
        {"name": "hips", "translation": {"keys": [{"frame": 0, "value": [1, 0.9, -2]},
                                                  {"frame": 12, "value": [2, 1.0, -1]}]},
         "rotation": {"keys": [{"frame": 0, "value": [0.9238795, 0, 0.3826834, 0]},
                               {"frame": 12, "value": [0.8, 0.6, 0, 0]}]}},
        {"name": "arm", "parent": "hips", "translation": [0.2, 0.3, 0], "scale": [1.5, 1.5, 1.5],
         "rotation": {"keys": [{"frame": 0, "value": [1, 0, 0, 0]}, {"frame": 12, "value": [0, 0, 0, 1]}]}},
        {"name": "hand", "parent": "arm", "translation": {"keys": [{"frame": 0, "value": [0.3, 0, 0]},
                                                                    {"frame": 12, "value": [0.3, 0.1, 0.2]}]}},
        {"name": "ball", "parent": "hips",
         "path": {"curve": "arc", "speed": {"kind": "ease", "start_frame": 2, "end_frame": 10}}},
        {"name": "cam", "parent": "arm", "translation": [0, 1, 5], "camera": {"look_at": "hand"}},
    ],
    "skins": [{"name": "body", "joints": ["hips", "arm", "hand"]}],
}


def write_rig(tmp_path):
    p = tmp_path / "rig.json"
    p.write_text(json.dumps(RIG))
    return p


def read_csv(text):
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


def quat_mul(a, b):
    """Hamilton product of (..., 4) w, x, y, z arrays."""
    aw, ax, ay, az = np.moveaxis(a, -1, 0)
    bw, bx, by, bz = np.moveaxis(b, -1, 0)
    return np.stack([aw * bw - ax * bx - ay * by - az * bz,
                     aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw], axis=-1)


def rotate(q, v):
    """v rotated by unit quaternion q (..., 4) w first."""
    w, u = q[..., :1], q[..., 1:]
    t = 2 * np.cross(u, v)
    return v + w * t + np.cross(u, t)


def compose(parent, local):
    """The scene's world = parent ∘ local for (..., 10) TRS rows (docs/conventions.md, compose())."""
    t = parent[..., 0:3] + rotate(parent[..., 3:7], parent[..., 7:10] * local[..., 0:3])
    q = quat_mul(parent[..., 3:7], local[..., 3:7])
    s = parent[..., 7:10] * local[..., 7:10]
    return np.concatenate([t, q, s], axis=-1)


def check_local_composes_to_world(local, world):
    assert local.names == world.names
    np.testing.assert_array_equal(local.parents, world.parents)
    scale = 1 + np.abs(world.transforms[..., 0:3]).max()
    for j, p in enumerate(local.parents):
        if p < 0:
            np.testing.assert_array_equal(local.transforms[:, j], world.transforms[:, j])
            continue
        got = compose(world.transforms[:, p], local.transforms[:, j])
        want = world.transforms[:, j]
        np.testing.assert_allclose(got[:, 0:3], want[:, 0:3], rtol=0, atol=COMPOSE_REL * scale)
        # q and -q are the same rotation.
        dots = np.abs(np.sum(got[:, 3:7] * want[:, 3:7], axis=-1))
        np.testing.assert_allclose(dots, 1, rtol=0, atol=COMPOSE_REL)
        np.testing.assert_allclose(got[:, 7:10], want[:, 7:10], rtol=COMPOSE_REL)


def test_scene_file_local_and_world_equal_the_tools_bake(tmp_path, cli):
    path = write_rig(tmp_path)
    for space in ("local", "world"):
        clip = inbetween.load_clip(path, space=space)
        assert clip.space == space
        assert clip.names == ["hips", "arm", "hand", "ball", "cam"]
        assert clip.parents.tolist() == [-1, 0, 1, 0, 1]
        assert clip.transforms.shape == (13, 5, 10)
        np.testing.assert_array_equal(clip.frames, np.arange(13.0))
        assert clip.fps == 30
        assert clip.skins == [("body", [0, 1, 2])]
        header, table = read_csv(cli("bake", path, "--space", space).stdout)
        for j, name in enumerate(clip.names):
            first = header.index(name + ".translation.x")
            # The tool prints the shortest round-trip text: the doubles come back exactly.
            np.testing.assert_array_equal(clip.transforms[:, j], table[:, first:first + 10])


def test_local_composes_to_world(tmp_path):
    path = write_rig(tmp_path)
    frames = np.linspace(-2, 14, 33)
    local = inbetween.load_clip(path, frames=frames)  # local is the default
    world = inbetween.load_clip(path, space="world", frames=frames)
    assert local.space == "local"
    np.testing.assert_array_equal(local.frames, frames)
    check_local_composes_to_world(local, world)
    # A keyed child's local transform is its keys: hand at frame 0.
    hand = local.names.index("hand")
    np.testing.assert_array_equal(local.transforms[2, hand], [0.3, 0, 0, 1, 0, 0, 0, 1, 1, 1])


def test_gltf_input(tmp_path):
    # The rig without its path object and camera (glTF keeps keyed nodes as keys), through convert.
    rig = dict(RIG, objects=RIG["objects"][:3], paths=[])
    src = tmp_path / "rig.json"
    src.write_text(json.dumps(rig))
    glb = tmp_path / "rig.glb"
    inbetween.convert(str(src), str(glb))
    local = inbetween.load_clip(glb, fps=30)
    world = inbetween.load_clip(glb, space="world", fps=30)
    assert local.names == ["hips", "arm", "hand"]
    assert local.parents.tolist() == [-1, 0, 1]
    assert local.skins == [("body", [0, 1, 2])]
    check_local_composes_to_world(local, world)
    from_scene = inbetween.load_clip(src, frames=local.frames)
    np.testing.assert_allclose(local.transforms, from_scene.transforms, rtol=0, atol=GLTF_FLOAT * 4)


def test_errors_name_the_file_and_place(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"inbetween": 2, "objects": [{"name": "a", "parent": "nobody"}]}))
    with pytest.raises(inbetween.Error) as e:
        inbetween.load_clip(bad)
    assert e.value.where == "/objects/0/parent"
    assert str(bad) in str(e.value)
    with pytest.raises(inbetween.Error) as e:
        inbetween.load_clip(tmp_path / "missing.json")
    assert e.value.code == "Io"
    tracks = tmp_path / "tracks.json"
    tracks.write_text(json.dumps({"inbetween": 1, "tracks": [{"name": "w", "kind": "scalar",
                                                              "keys": [{"frame": 1, "value": 5}]}]}))
    with pytest.raises(inbetween.Error) as e:
        inbetween.load_clip(tracks)
    assert e.value.code == "Unsupported"
    with pytest.raises(ValueError, match="space"):
        inbetween.load_clip(write_rig(tmp_path), space="parent")
    with pytest.raises(ValueError, match="animation"):
        inbetween.load_clip(write_rig(tmp_path), animation="walk")


BVH = pathlib.Path("/usr/share/assimp/models/BVH/01_01.bvh")


def test_bvh_clip_when_the_reader_is_built_in():
    if not BVH.exists():
        pytest.skip(f"{BVH} missing (Debian's assimp-testmodels)")
    try:
        local = inbetween.load_clip(BVH)
    except inbetween.Error as e:
        if e.code == "Unsupported":
            pytest.skip(f"no BVH reader in this build: {e}")
        raise
    world = inbetween.load_clip(BVH, space="world", frames=local.frames[:50])
    assert len(local.names) == local.transforms.shape[1]
    assert (local.parents == -1).sum() >= 1
    check_local_composes_to_world(inbetween.load_clip(BVH, frames=world.frames), world)
