"""Rotations against SciPy's Rotation (an independent implementation): every conversion, all 24
Euler conventions, slerp; the Euler filter's properties.  Seeded random rotations."""
import numpy as np
import pytest

import inbetween
from tolerances import COMPONENT, ROTATION_RAD, SLERP_RAD

Rotation = pytest.importorskip("scipy.spatial.transform").Rotation
Slerp = pytest.importorskip("scipy.spatial.transform").Slerp

N = 2000


def wxyz(r):
    """SciPy's x, y, z, w quaternions as w, x, y, z with w >= 0."""
    q = r.as_quat()
    q = np.concatenate([q[:, 3:], q[:, :3]], axis=1)
    return q * np.where(q[:, :1] < 0, -1.0, 1.0)


def angle_between(qa, qb):
    """Rotation angle between quaternion arrays (sign-blind)."""
    d = np.abs(np.sum(qa * qb, axis=-1))
    return 2 * np.arctan2(np.linalg.norm(qa - np.sign(np.sum(qa * qb, axis=-1))[:, None] * qb, axis=-1),
                          np.linalg.norm(qa + np.sign(np.sum(qa * qb, axis=-1))[:, None] * qb, axis=-1)) * (d >= 0)


def test_the_24_conventions_are_scipys_names():
    names = inbetween.euler_sequences()
    assert len(names) == 24 and len(set(names)) == 24
    for n in names:
        Rotation.from_euler(n, [0.1, 0.2, 0.3])  # SciPy accepts every one of them


@pytest.mark.parametrize("seq", [s for s in ["XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ",
                                             "ZYZ"] for s in (s, s.lower())])
def test_euler_matches_scipy_in_every_convention(seq, rng):
    angles = rng.uniform(-np.pi, np.pi, size=(N, 3))
    ours = inbetween.quat_from_euler(seq, angles)
    theirs = wxyz(Rotation.from_euler(seq, angles))
    np.testing.assert_allclose(ours, theirs, atol=COMPONENT * 10)
    np.testing.assert_allclose(inbetween.matrix_from_euler(seq, angles),
                               Rotation.from_euler(seq, angles).as_matrix(), atol=COMPONENT * 10)
    # Extraction: SciPy's ranges, so the angles themselves agree away from gimbal lock.
    q = wxyz(Rotation.random(N, random_state=int(rng.integers(2**31))))
    got, lock = inbetween.euler_from_quat(seq, q, return_gimbal_lock=True)
    want = Rotation.from_quat(np.concatenate([q[:, 1:], q[:, :1]], axis=1)).as_euler(seq)
    ok = ~lock
    diff = np.angle(np.exp(1j * (got[ok] - want[ok])))  # wrapped difference
    assert np.max(np.abs(diff)) < ROTATION_RAD * 1e3, seq  # 1e-9: atan2 near the range ends
    # And the extracted angles rebuild the rotation everywhere (also at gimbal lock).
    rebuilt = inbetween.quat_from_euler(seq, got)
    assert np.max(np.abs(np.abs(np.sum(rebuilt * q, axis=1)) - 1)) < 1e-14
    got_m = inbetween.euler_from_matrix(seq, inbetween.matrix_from_quat(q))
    assert np.max(np.abs(np.angle(np.exp(1j * (got_m[ok] - got[ok]))))) < 1e-9


def test_gimbal_lock_matches_scipys_choice(rng):
    # Middle angle exactly singular: SciPy sets the third angle to 0 (with a warning).
    for seq in ["XYZ", "zyx", "ZXZ", "xyx"]:
        proper = seq[0].lower() == seq[2].lower()
        mid = 0.0 if proper else np.pi / 2
        angles = np.column_stack([rng.uniform(-3, 3, 50), np.full(50, mid), rng.uniform(-3, 3, 50)])
        q = inbetween.quat_from_euler(seq, angles)
        got, lock = inbetween.euler_from_quat(seq, q, return_gimbal_lock=True)
        assert lock.all()
        with pytest.warns(UserWarning):
            want = Rotation.from_quat(np.concatenate([q[:, 1:], q[:, :1]], axis=1)).as_euler(seq)
        np.testing.assert_allclose(got[:, 2], 0, atol=0)
        d = np.angle(np.exp(1j * (got - want)))
        np.testing.assert_allclose(d[:, [0, 2]], 0, atol=1e-9)
        # SciPy 1.10's middle angle at lock carries sqrt(eps) = 1.49e-8 (measured: 1.4901161e-8,
        # an acos of 1 - eps); ours is exact there (docs/conventions.md).
        np.testing.assert_allclose(d[:, 1], 0, atol=2 * np.sqrt(np.finfo(float).eps))
        np.testing.assert_allclose(got[:, 1], mid, atol=0)


def test_matrix_rotvec_axis_angle_match_scipy(rng):
    r = Rotation.random(N, random_state=int(rng.integers(2**31)))
    q = wxyz(r)
    np.testing.assert_allclose(inbetween.matrix_from_quat(q), r.as_matrix(), atol=COMPONENT * 10)
    np.testing.assert_allclose(inbetween.quat_from_matrix(r.as_matrix()), q, atol=COMPONENT * 10)
    np.testing.assert_allclose(inbetween.rotvec_from_quat(q), r.as_rotvec(), atol=ROTATION_RAD)
    np.testing.assert_allclose(inbetween.quat_from_rotvec(r.as_rotvec()), q, atol=COMPONENT * 10)
    np.testing.assert_allclose(inbetween.rotvec_from_matrix(r.as_matrix()), r.as_rotvec(), atol=ROTATION_RAD)
    np.testing.assert_allclose(inbetween.matrix_from_rotvec(r.as_rotvec()), r.as_matrix(), atol=COMPONENT * 10)
    axis, angle = inbetween.axis_angle_from_quat(q)
    np.testing.assert_allclose(axis * angle[:, None], r.as_rotvec(), atol=ROTATION_RAD)
    np.testing.assert_allclose(inbetween.quat_from_axis_angle(axis, angle), q, atol=COMPONENT * 10)
    axis_m, angle_m = inbetween.axis_angle_from_matrix(r.as_matrix())
    np.testing.assert_allclose(axis_m * angle_m[:, None], r.as_rotvec(), atol=ROTATION_RAD)
    np.testing.assert_allclose(inbetween.matrix_from_axis_angle(axis, angle), r.as_matrix(), atol=COMPONENT * 10)
    # Leading shapes are kept.
    assert inbetween.matrix_from_quat(q.reshape(40, 50, 4)).shape == (40, 50, 3, 3)


def test_slerp_matches_scipy(rng):
    for _ in range(20):
        ends = Rotation.random(2, random_state=int(rng.integers(2**31)))
        u = rng.uniform(0, 1, 200)
        q = wxyz(ends)
        ours = inbetween.slerp(q[0], q[1], u)
        theirs = wxyz(Slerp([0, 1], ends)(u))  # SciPy takes the shortest arc too
        err = np.abs(np.abs(np.sum(ours * theirs, axis=1)) - 1)
        assert np.max(err) < SLERP_RAD, np.max(err)
        np.testing.assert_allclose(np.abs(ours), np.abs(theirs), atol=SLERP_RAD)
    # Broadcasting: many pairs at one u.
    a, b = wxyz(Rotation.random(10, random_state=1)), wxyz(Rotation.random(10, random_state=2))
    assert inbetween.slerp(a, b, 0.5).shape == (10, 4)
    np.testing.assert_array_equal(inbetween.slerp(a, b, 0.0), a)


def test_euler_filter_keeps_rotations_and_removes_jumps(rng):
    # A smooth spin about a tilted axis sampled past +-pi: extracted angles jump by 2*pi, the filter
    # removes the jumps and every filtered triple is still the same rotation.
    for seq in ["XYZ", "zxz", "YXY", "zyx"]:
        t = np.linspace(0.1, 2 * np.pi - 0.1, 400)  # crosses pi; avoids the identity (proper Euler: gimbal lock)
        axis = np.tile([0.3, 0.5, 0.8], (t.size, 1))
        q = inbetween.quat_from_axis_angle(axis / np.linalg.norm(axis[0]), t)
        raw = inbetween.euler_from_quat(seq, q)
        filtered = inbetween.euler_filter(seq, raw)
        again = inbetween.quat_from_euler(seq, filtered)
        assert np.max(np.abs(np.abs(np.sum(again * q, axis=1)) - 1)) < 1e-13
        assert np.max(np.abs(np.diff(filtered, axis=0))) < 0.5, seq  # steps of 2pi/400 ~ 0.016 rad per frame
        np.testing.assert_array_equal(filtered[0], raw[0])
    with pytest.raises(ValueError):
        inbetween.euler_filter("XYZ", np.zeros((2, 3, 3)))


# Issue 21: a NaN or infinite input is refused (inbetween.Error naming the argument and the item)
# instead of quietly becoming the identity; each call below returned the identity before.
NAN_CALLS = [
    ("matrix_from_quat", lambda x: inbetween.matrix_from_quat(np.array([[1.0, 0, 0, 0], [x, 0, 0, 1]]))),
    ("rotvec_from_quat", lambda x: inbetween.rotvec_from_quat(np.array([1.0, x, 0, 0]))),
    ("euler_from_quat", lambda x: inbetween.euler_from_quat("XYZ", np.array([x, 0, 0, 1.0]))),
    ("quat_from_rotvec", lambda x: inbetween.quat_from_rotvec(np.array([0.1, x, 0]))),
    ("matrix_from_rotvec", lambda x: inbetween.matrix_from_rotvec(np.array([x, 0, 0]))),
    ("rotvec_from_matrix", lambda x: inbetween.rotvec_from_matrix(np.diag([1.0, 1, x]))),
    ("axis_angle_from_quat", lambda x: inbetween.axis_angle_from_quat(np.array([x, 1.0, 0, 0]))),
    ("axis_angle_from_matrix", lambda x: inbetween.axis_angle_from_matrix(np.diag([x, 1.0, 1]))),
    ("quat_from_axis_angle angle", lambda x: inbetween.quat_from_axis_angle(np.array([0, 0, 1.0]), np.array(x))),
    ("quat_from_axis_angle axis", lambda x: inbetween.quat_from_axis_angle(np.array([0, x, 1.0]), np.array(0.5))),
    ("matrix_from_axis_angle", lambda x: inbetween.matrix_from_axis_angle(np.array([0, 0, 1.0]), np.array(x))),
    ("quat_from_euler", lambda x: inbetween.quat_from_euler("xyz", np.array([x, 0, 0]))),
    ("matrix_from_euler", lambda x: inbetween.matrix_from_euler("ZYX", np.array([0, 0, x]))),
    ("euler_from_matrix", lambda x: inbetween.euler_from_matrix("XYZ", np.diag([1.0, x, 1]))),
    ("euler_filter", lambda x: inbetween.euler_filter("XYZ", np.array([[0, 0, 0], [x, 0, 0.0]]))),
    ("slerp a", lambda x: inbetween.slerp(np.array([x, 0, 0, 1.0]), np.array([1.0, 0, 0, 0]), np.array(0.5))),
    ("slerp u", lambda x: inbetween.slerp(np.array([1.0, 0, 0, 0]), np.array([0, 1.0, 0, 0]), np.array(x))),
    ("quat_from_matrix unchecked", lambda x: inbetween.quat_from_matrix(np.diag([x, 1.0, 1]), check=False)),
]


@pytest.mark.parametrize("name,call", NAN_CALLS, ids=[n for n, _ in NAN_CALLS])
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_input_is_refused(name, call, bad):
    with pytest.raises(inbetween.Error, match="not finite"):
        call(bad)


def test_non_finite_input_names_the_item():
    with pytest.raises(inbetween.Error) as e:
        inbetween.matrix_from_quat(np.array([[1.0, 0, 0, 0], [1.0, 0, 0, 0], [0, np.nan, 0, 1]]))
    assert e.value.where == "/2"


def test_slerp_of_huge_finite_quaternions_is_finite():
    # slerp is scale-free on its inputs: 1e308 times a unit quaternion interpolates as the unit one
    # (before: NaN, the plain norm overflowing).  Halfway between the identity and a half turn about
    # z is the quarter turn about z (closed form).
    a = np.array([1e308, 0, 0, 0])
    b = np.array([0, 0, 0, 1e308])
    q = inbetween.slerp(a, b, np.array(0.5))
    assert np.all(np.isfinite(q))
    np.testing.assert_allclose(q, [np.sqrt(0.5), 0, 0, np.sqrt(0.5)], atol=COMPONENT)
    big = inbetween.slerp(np.array([1e308, -1e308, 1e308, 1e308]), np.array([1e300, 0, 0, 0]), np.array(0.25))
    np.testing.assert_allclose(big, inbetween.slerp(np.array([0.5, -0.5, 0.5, 0.5]), np.array([1.0, 0, 0, 0]), np.array(0.25)),
                               atol=COMPONENT)


@pytest.mark.parametrize("tolerance", [np.nan, -1.0, np.inf])
def test_quat_from_matrix_refuses_a_tolerance_that_switches_the_check_off(tolerance):
    # Before: tolerance=nan made every comparison false, so a shear passed as a rotation.
    with pytest.raises(inbetween.Error, match="tolerance"):
        inbetween.quat_from_matrix(np.array([[1.0, 5, 0], [0, 1, 0], [0, 0, 1]]), tolerance=tolerance)
