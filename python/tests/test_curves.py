"""Curves, arc length, speed and tracks: against the inbetween tool (the C++ results), closed forms
and SciPy's quadrature (an independent arc length)."""
import csv
import io
import json

import numpy as np
import pytest

import inbetween
from tolerances import ARC_LENGTH_REL


def read_csv(text):
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


CURVES = ["bezier-path.json", "bezier-quintic.json", "bspline-cubic.json", "bspline-periodic-3d.json",
          "catmull-rom-centripetal.json", "catmull-rom-uniform-loop.json", "hermite.json", "kochanek-bartels.json",
          "lagrange-runge.json", "natural.json"]


@pytest.mark.parametrize("name", CURVES)
def test_curve_points_equal_the_tools_samples(name, source_dir, cli):
    path = source_dir / "examples" / "curves" / name
    curve = inbetween.Curve(json.loads(path.read_text()))
    header, table = read_csv(cli("curve", "sample", path, "-n", 57).stdout)
    assert header[1:] == ["x", "y", "z"][:curve.dimension]
    got = curve.point(table[:, 0])
    # The tool prints shortest round-trip text: the same doubles come back.
    np.testing.assert_array_equal(got, table[:, 1:])
    # By arc length too (the tool's `--by arclength` uses ArcLength::u_at, the Newton reference).
    header, table = read_csv(cli("curve", "sample", path, "-n", 33, "--by", "arclength").stdout)
    arc = inbetween.ArcLength(curve)
    s = table[:, header.index("s")]
    u_ref = table[:, 0]
    np.testing.assert_array_equal(arc.u_newton(s), u_ref)
    # The Chebyshev inverse answers within 1e-10 L in s (its own guarantee).
    assert np.max(np.abs(arc.s(arc.u(s)) - s)) <= 1e-10 * arc.length + 1e-15


@pytest.mark.parametrize("name", ["natural.json", "catmull-rom-centripetal.json", "bezier-path.json", "lagrange-runge.json"])
def test_arc_length_matches_scipy_quad(name, source_dir, rng):
    integrate = pytest.importorskip("scipy.integrate")
    curve = inbetween.Curve((source_dir / "examples" / "curves" / name).read_text())
    arc = inbetween.ArcLength(curve)
    lo, hi = curve.domain

    def speed(u):
        return float(np.linalg.norm(curve.derivative(np.array([u]))[0]))
    # Integrate piece by piece (joints are where the speed may kink).
    knots = sorted({lo, hi, *[j["u"] for j in curve.continuity() if lo < j["u"] < hi]})
    for u in np.sort(rng.uniform(lo, hi, 8)):
        ref = sum(integrate.quad(speed, a, min(b, u), epsabs=1e-13, epsrel=1e-13, limit=200)[0]
                  for a, b in zip(knots, knots[1:]) if a < u)
        assert abs(arc.s(np.array([u]))[0] - ref) <= ARC_LENGTH_REL * arc.length, (u, ref)


def test_derivatives_and_continuity():
    # Catmull-Rom: C1 at every joint, not C2 (the texts); the derivative equals a central difference.
    c = inbetween.Curve({"type": "catmull-rom", "points": [[0, 0, 0], [1, 2, 0], [3, 3, 1], [4, 0, 2], [6, 1, 0]]})
    joints = c.continuity()
    assert len(joints) == c.segment_count - 1
    assert all(j["c_order"] == 1 for j in joints)
    # Inside the pieces (at a joint the second derivative jumps and a central difference errs by h).
    u = (np.arange(c.segment_count)[:, None] + np.linspace(0.1, 0.9, 17)[None, :]).ravel()[:17]
    h = 1e-6
    central = (c.point(u + h) - c.point(u - h)) / (2 * h)
    np.testing.assert_allclose(c.derivative(u), central, atol=1e-6)  # O(h^2) ~ 1e-12 plus rounding 1e-10
    assert c.derivative(u, 0).shape == (17, 3)
    np.testing.assert_array_equal(c.derivative(u, 0), c.point(u))
    # Natural spline: C2.
    n = inbetween.Curve({"type": "natural", "points": [[0, 0], [1, 2], [3, 3], [4, 0]]})
    assert all(j["c_order"] >= 2 for j in n.continuity())
    # Round trip through the curve file.
    np.testing.assert_array_equal(inbetween.Curve(c.to_json()).point(u), c.point(u))


def test_speed_eases_match_closed_forms():
    t = np.linspace(0, 1, 101)
    # Texts 004 Eqs. 3.18 and 3.20.
    np.testing.assert_allclose(inbetween.ease({"kind": "sine"}, t), (1 - np.cos(np.pi * t)) / 2, atol=1e-15)
    np.testing.assert_allclose(inbetween.ease({"kind": "cubic"}, t), -2 * t**3 + 3 * t**2, atol=1e-15)
    np.testing.assert_allclose(inbetween.ease({"kind": "linear"}, t), t, atol=0)
    # Every ease starts at 0 and ends at 1 (eases that would run backwards, Penner's back, bounce and
    # elastic, are refused by the builder: tested in test_speed_errors_name_the_place_inside_the_spec).
    for spec in [{"kind": "sine_pieces", "k1": 0.2, "k2": 0.7}, {"kind": "constant_acceleration", "t1": 0.3, "t2": 0.6},
                 {"kind": "cubic_bezier", "x1": 0.42, "y1": 0, "x2": 0.58, "y2": 1},
                 {"kind": "penner", "curve": "circ", "direction": "out"},
                 {"kind": "penner", "curve": "expo", "direction": "in_out"},
                 {"kind": "penner", "curve": "quad", "direction": "in"}]:
        s = inbetween.ease(spec, np.array([0.0, 1.0]))
        np.testing.assert_allclose(s, [0, 1], atol=1e-12, err_msg=str(spec))
    # Frames map onto distances: an ease over frames 10..30 on a path of length 5.
    sp = inbetween.Speed({"kind": "ease", "start_frame": 10, "end_frame": 30, "ease": {"kind": "cubic"}}, length=5)
    f = np.array([0, 10, 20, 30, 40.0])
    np.testing.assert_allclose(sp.distance(f), [0, 0, 2.5, 5, 5], atol=1e-14)
    assert sp.frame_range == (10, 30)
    # ds/dframe of -2t^3 + 3t^2 with t = (f - 10)/20 at the middle: 1.5 * 5 / 20.
    np.testing.assert_allclose(sp.velocity(np.array([20.0])), [1.5 * 5 / 20], rtol=1e-14)
    # Distance-time keys, linear: straight lines between the keys.
    keys = inbetween.Speed({"kind": "distance_keys", "interpolation": "linear",
                            "keys": [{"frame": 0, "distance": 0}, {"frame": 10, "distance": 4}, {"frame": 20, "distance": 5}]},
                           length=5)
    np.testing.assert_allclose(keys.distance(np.array([5.0, 15.0])), [2, 4.5], atol=1e-14)


def test_speed_errors_name_the_place_inside_the_spec():
    with pytest.raises(inbetween.Error) as info:
        inbetween.Speed({"kind": "distance_keys", "keys": [{"frame": 1, "distance": 0}, {"frame": 0, "distance": 1}]})
    assert info.value.where.startswith("/keys/1")
    with pytest.raises(inbetween.Error, match="runs backwards") as info:
        inbetween.ease({"kind": "penner", "curve": "back", "direction": "in_out"}, [0.5])
    assert info.value.where == "/ease"
    with pytest.raises(inbetween.Error) as info:
        inbetween.Speed({"kind": "ease", "start_frame": 5, "end_frame": 5})
    assert "end_frame" in info.value.where or "start_frame" in info.value.where


def test_fcurve_track_matches_a_baked_scene(source_dir):
    # A scalar track sampled alone equals the same track's column in a scene's bake.
    scene = json.loads((source_dir / "examples" / "scenes" / "bouncing_cube.json").read_text())
    frames = np.linspace(scene["range"][0], scene["range"][1], 91)
    values, columns = inbetween.bake(scene, frames)
    for spec in scene["tracks"]:
        track = inbetween.Track(spec, fps=scene.get("fps", 24))
        got = track.sample(frames)
        if got.ndim == 1:
            got = got[:, None]
        idx = [columns.index(c) for c in track.columns]
        np.testing.assert_array_equal(got, values[:, idx], err_msg=spec["name"])


def test_fcurve_track_takes_modifiers():
    # Keys y = t (linear); a Generator 1 + 2t - 0.5t^2 replaces them (closed form, exact in float at
    # these frames), a Stepped modifier below it steps the frame first (time modifiers run last to first).
    keys = [{"frame": 0, "value": 0, "interpolation": "linear"}, {"frame": 10, "value": 10, "interpolation": "linear"}]
    gen = {"type": "generator", "coefficients": [1, 2, -0.5]}
    track = inbetween.Track({"keys": keys, "modifiers": [gen]})
    t = np.array([-4.0, 0.0, 2.5, 7.0])
    np.testing.assert_array_equal(track.sample(t), 1 + 2 * t - 0.5 * t * t)
    stepped = inbetween.Track({"keys": keys, "modifiers": [gen, {"type": "stepped", "step": 2}]})
    ts = np.trunc(t / 2) * 2
    np.testing.assert_array_equal(stepped.sample(t), 1 + 2 * ts - 0.5 * ts * ts)
    with pytest.raises(inbetween.Error) as info:
        inbetween.Track({"keys": keys, "modifiers": [{"type": "limits"}, {"type": "generator", "coefficients": [1]}]})
    assert info.value.where == "/modifiers/1/coefficients"
    with pytest.raises(inbetween.Error) as info:
        inbetween.Track({"keys": keys, "modifiers": [{"type": "wobble"}]})
    assert info.value.where == "/modifiers/0/type"


def test_arc_length_out_argument():
    c = inbetween.Curve({"type": "natural", "points": [[0, 0], [1, 2], [3, 3], [4, 0]]})
    arc = inbetween.ArcLength(c)
    s = np.linspace(0, arc.length, 50)
    out = np.empty(50)
    assert arc.u(s, out=out) is out or np.shares_memory(arc.u(s, out=out), out)
    np.testing.assert_array_equal(out, arc.u(s))
    with pytest.raises(ValueError, match="out"):
        arc.u(s, out=np.empty(49))
    with pytest.raises(ValueError, match="out"):
        arc.u(s, out=np.empty(50, dtype=np.float32))


def test_constraints_speed_that_overflows_is_refused_not_searched():
    # Issue 21: a constraints speed key of 1e308 on a path shorter than 1 never returned (the
    # backing-up search subdivided an infinite speed hull 2^40 times).  Now inbetween.Error naming the key.
    spec = {"kind": "constraints", "keys": [{"frame": 0, "distance": 0, "speed": 1e308}, {"frame": 24, "distance": 0.5}]}
    with pytest.raises(inbetween.Error, match="tuples 0 → 1: the distance curve between them overflows"):
        inbetween.Speed(spec, length=0.9)
