"""blend_poses, additive_delta and extract_root_motion (docs/blending.md) on NumPy arrays, against the
documented formulas written again in NumPy; seeded random poses (the seed is printed)."""
import numpy as np
import pytest

import inbetween
from tolerances import BLEND_ABS, ROOT_MOTION_REL

SEED = 2323


def qmul(a, b):
    w1, x1, y1, z1 = np.moveaxis(a, -1, 0)
    w2, x2, y2, z2 = np.moveaxis(b, -1, 0)
    return np.stack([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2], axis=-1)


def qrot(q, v):
    p = np.concatenate([np.zeros(v.shape[:-1] + (1,)), v], axis=-1)
    conj = q * np.array([1, -1, -1, -1])
    return qmul(qmul(q, p), conj)[..., 1:]


def random_poses(rng, shape):
    p = np.empty(shape + (10,))
    p[..., 0:3] = rng.uniform(-5, 5, shape + (3,))
    q = rng.normal(size=shape + (4,))
    p[..., 3:7] = q / np.linalg.norm(q, axis=-1, keepdims=True)
    p[..., 7:10] = rng.uniform(0.5, 2, shape + (3,))
    return p


def reference_blend(poses, weights, masks, rest, threshold):
    w = np.clip(np.nan_to_num(weights[:, None] * masks, nan=0.0), 0, None)  # (L, J)
    total = w.sum(axis=0)
    h = poses[0, :, 3:7]
    sign = np.where(np.einsum("ljk,jk->lj", poses[:, :, 3:7], h) < 0, -1.0, 1.0)
    rest_w = np.maximum(threshold - total, 0)
    rsign = np.where(np.einsum("jk,jk->j", rest[:, 3:7], h) < 0, -1.0, 1.0)
    t = np.einsum("lj,ljk->jk", w, poses[:, :, 0:3]) + rest_w[:, None] * rest[:, 0:3]
    s = np.einsum("lj,ljk->jk", w, poses[:, :, 7:10]) + rest_w[:, None] * rest[:, 7:10]
    q = np.einsum("lj,ljk->jk", w * sign, poses[:, :, 3:7]) + (rest_w * rsign)[:, None] * rest[:, 3:7]
    wsum = np.maximum(total, threshold)[:, None]
    return t / wsum, q / np.linalg.norm(q, axis=-1, keepdims=True), s / wsum


def test_blend_matches_the_formulas():
    rng = np.random.default_rng(SEED)
    print("seed", SEED)
    for _ in range(20):
        layers, joints = rng.integers(1, 5), rng.integers(1, 30)
        poses = random_poses(rng, (layers, joints))
        weights = rng.uniform(0, 1.5, layers)
        masks = rng.uniform(0, 1, (layers, joints))
        rest = random_poses(rng, (joints,))
        out = inbetween.blend_poses(poses, weights, masks=masks, rest=rest, threshold=0.2)
        t, q, s = reference_blend(poses, weights, masks, rest, 0.2)
        assert np.abs(out[:, 0:3] - t).max() <= BLEND_ABS * 5
        assert np.abs(out[:, 7:10] - s).max() <= BLEND_ABS * 5
        # Same rotation: |dot| = 1 (either sign).
        assert np.abs(np.abs(np.einsum("jk,jk->j", out[:, 3:7], q)) - 1).max() <= BLEND_ABS


def test_complementary_weights_and_identity_delta():
    rng = np.random.default_rng(SEED + 1)
    pose = random_poses(rng, (7,))
    out = inbetween.blend_poses(np.stack([pose, pose]), [0.3, 0.7])
    assert np.abs(out[:, 0:3] - pose[:, 0:3]).max() <= BLEND_ABS * 5
    delta = inbetween.additive_delta(pose, pose)
    assert np.abs(delta[:, 0:3]).max() == 0 and np.abs(delta[:, 7:10] - 1).max() == 0
    added = inbetween.blend_poses(pose[None], [1.0], additive=delta[None], additive_weights=[1.0])
    assert np.abs(added[:, 0:3] - pose[:, 0:3]).max() == 0


def test_root_motion_reproduces_the_root():
    rng = np.random.default_rng(SEED + 2)
    n = 50
    yaw = np.cumsum(rng.uniform(-0.05, 0.05, n))
    root = np.zeros((n, 10))
    root[:, 0] = np.cumsum(np.sin(yaw)) * 0.1
    root[:, 1] = 0.9
    root[:, 2] = np.cumsum(np.cos(yaw)) * 0.1
    root[:, 3] = np.cos(yaw / 2)
    root[:, 5] = np.sin(yaw / 2)
    root[:, 7:10] = 1
    motion, character = inbetween.extract_root_motion(root, loop=True)
    assert motion.shape == (n, 7) and character.shape == (n, 10)
    assert np.abs(motion[:, 1]).max() == 0  # horizontal only (Y up)
    world_t = motion[:, 0:3] + qrot(motion[:, 3:7], character[:, 0:3])
    world_q = qmul(motion[:, 3:7], character[:, 3:7])
    extent = np.abs(root[:, 0:3]).max()
    assert np.abs(world_t - root[:, 0:3]).max() <= ROOT_MOTION_REL * extent
    assert np.abs(np.abs(np.einsum("nk,nk->n", world_q, root[:, 3:7])) - 1).max() <= 1e-12
    assert np.abs(motion[-1, 0:3] - motion[0, 0:3]).max() <= ROOT_MOTION_REL * extent  # looped


def test_bad_shapes_and_names():
    with pytest.raises(ValueError, match="poses"):
        inbetween.blend_poses(np.zeros((2, 3, 9)), [1, 1])
    with pytest.raises(ValueError, match="weights"):
        inbetween.blend_poses(np.zeros((2, 3, 10)), [1])
    with pytest.raises(ValueError, match="position_reference"):
        inbetween.extract_root_motion(np.zeros((3, 10)), position_reference="nowhere")
    # NaN and negative weights count as 0: the other layer alone.
    rng = np.random.default_rng(SEED + 3)
    a, b = random_poses(rng, (4,)), random_poses(rng, (4,))
    for bad in (np.nan, -1.0):
        out = inbetween.blend_poses(np.stack([a, b]), [bad, 1.0])
        assert np.all(np.isfinite(out))
        assert np.abs(out[:, 0:3] - b[:, 0:3]).max() <= BLEND_ABS * 5
