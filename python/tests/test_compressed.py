"""Compressed clips (.ibc, docs/compression.md) in Python: load_compressed() samples in place with
the runtime's float sampler, and agrees with load_clip() of the same file (the decompressed clip,
keyed at every frame) within the float sampler's tolerance; a corrupt file raises inbetween.Error
naming the byte."""
import math

import numpy as np
import pytest

import inbetween

# compressed_sample_tolerance (tracks/runtime/compressed_clip.hpp) relative to |value| + 1: float
# evaluation of the spline basis and of the range.
FLOAT_SAMPLER_TOLERANCE = 1e-5


def small_bvh(path):
    lines = ["HIERARCHY", "ROOT hip", "{", " OFFSET 0 0 0",
             " CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation",
             " JOINT arm", " {", "  OFFSET 0 5 0", "  CHANNELS 3 Zrotation Yrotation Xrotation",
             "  End Site", "  {", "   OFFSET 0 1 0", "  }", " }", "}", "MOTION", "Frames: 30", "Frame Time: 0.0333333"]
    for f in range(30):
        t = f / 30
        lines.append(f"{t} 10 {math.sin(3 * t)} {20 * math.sin(2 * t)} 5 0 {40 * math.sin(4 * t)} {10 * t} 0")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_sample_in_place_agrees_with_the_decompressed_clip(tmp_path, cli):
    bvh = small_bvh(tmp_path / "wave.bvh")
    ibc = tmp_path / "wave.ibc"
    cli("compress", bvh, "-o", ibc, "--error", "0.001")
    c = inbetween.load_compressed(ibc)
    assert c.names == ["hip", "arm"]
    assert list(c.parents) == [-1, 0]
    assert c.frame_count == 30 and c.first_frame == 0
    assert 0 <= c.measured_error <= c.error_bound
    assert c.nbytes == ibc.stat().st_size
    frames = np.arange(30.0)
    local = c.sample(frames)
    assert local.shape == (30, 2, 10) and local.dtype == np.float32
    assert c.sample(3.0).shape == (2, 10)
    ref = inbetween.load_clip(ibc, space="local", frames=frames).transforms
    scale = np.abs(ref).max() + 1
    # q and -q are the same rotation: compare the rotation columns up to sign.
    sign = np.sign(np.sum(ref[..., 3:7] * local[..., 3:7], axis=-1, keepdims=True))
    assert np.allclose(local[..., :3], ref[..., :3], atol=FLOAT_SAMPLER_TOLERANCE * scale)
    assert np.allclose(local[..., 3:7] * sign, ref[..., 3:7], atol=FLOAT_SAMPLER_TOLERANCE)
    assert np.allclose(local[..., 7:], ref[..., 7:], atol=FLOAT_SAMPLER_TOLERANCE)
    # outside the clip: clamped
    assert np.array_equal(c.sample(-100.0), c.sample(0.0))


def test_a_truncated_file_names_the_byte(tmp_path, cli):
    bvh = small_bvh(tmp_path / "wave.bvh")
    ibc = tmp_path / "wave.ibc"
    cli("compress", bvh, "-o", ibc)
    data = ibc.read_bytes()
    cut = tmp_path / "cut.ibc"
    cut.write_bytes(data[: len(data) // 2])
    with pytest.raises(inbetween.Error) as info:
        inbetween.load_compressed(cut)
    assert info.value.where == "byte 8"
    assert "truncated" in info.value.message
