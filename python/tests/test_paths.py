"""Path functions: B-spline fitting against scipy.interpolate.make_lsq_spline (an independent
least-squares B-spline on the same knots) and the tool's `path fit`; smoothing closed forms."""
import json

import numpy as np
import pytest

import inbetween
from tolerances import LSQ_REL


@pytest.mark.parametrize("degree, control_points", [(3, 8), (2, 6), (5, 12), (3, 0)])
def test_fit_bspline_matches_scipy(degree, control_points, rng):
    interpolate = pytest.importorskip("scipy.interpolate")
    n = 40 if control_points else 12
    t = np.sort(rng.uniform(0, 3, n))
    t[0], t[-1] = 0.0, 3.0
    if control_points == 0:
        t = np.linspace(0, 3, n)  # interpolation: evenly spaced data keep the collocation matrix well conditioned
    pts = np.column_stack([np.sin(2 * t), np.cos(3 * t), t**2]) + rng.normal(0, 0.05, (n, 3))
    curve, info = inbetween.fit_bspline(t, pts, degree=degree, control_points=control_points)
    assert curve.kind == "bspline" and curve.dimension == 3
    knots = np.array(info["knots"])
    if control_points == 0:
        # Interpolation (Eq. 3.26): through every data point.  (SciPy's normal equations are not
        # used here: with as many control points as data they are near-singular.)
        assert info["square"] and info["max_residual"] < 1e-9
        np.testing.assert_allclose(curve.point(t), pts, atol=1e-9)
        return
    spline = interpolate.make_lsq_spline(t, pts, knots, k=degree)
    scale = np.max(np.abs(pts))
    np.testing.assert_allclose(curve.control_points, spline.c, atol=LSQ_REL * scale * 1e2)  # coefficients: cond ~1e2
    u = np.linspace(0, 3, 301)
    np.testing.assert_allclose(curve.point(u), spline(u), atol=LSQ_REL * scale)
    residual = np.linalg.norm(curve.point(t) - pts, axis=1)
    np.testing.assert_allclose(info["max_residual"], residual.max(), rtol=1e-9)
    np.testing.assert_allclose(info["rms_residual"], np.sqrt(np.mean(residual**2)), rtol=1e-9)


def test_fit_bspline_equals_the_tools_path_fit(cli, tmp_path, rng):
    t = np.linspace(0, 2, 25)
    pts = np.column_stack([t, np.sin(t)])
    data = tmp_path / "data.csv"
    data.write_text("".join(f"{a!r},{b!r},{c!r}\n" for a, (b, c) in zip(t, pts)))
    curve, _ = inbetween.fit_bspline(t, pts, degree=3, control_points=7)
    theirs = json.loads(cli("path", "fit", data, "--degree", 3, "--control-points", 7).stdout)
    assert json.loads(curve.to_json()) == theirs


def test_fit_errors_are_located():
    with pytest.raises(inbetween.Error):
        inbetween.fit_bspline([0, 1, 1, 2], np.zeros((4, 2)), degree=2, control_points=3)
    with pytest.raises(ValueError):
        inbetween.fit_bspline([0, 1, 2], np.zeros((4, 2)))


def test_smoothing_closed_forms():
    # A straight, evenly spaced line is a fixed point of every smoother (each is an affine average).
    line = np.column_stack([np.arange(10.0), 2 * np.arange(10.0)])
    for method in ["linear", "cubic", "convolution"]:
        np.testing.assert_allclose(inbetween.smooth(line, method=method, fix_ends=True), line, atol=1e-13)
    # Linear smoothing (texts 004 Eq. 3.35): each inner point moves halfway to its neighbours'
    # midpoint, p_i' = (p_i + (p_{i-1} + p_{i+1})/2)/2, ends fixed: (4 + 0)/2 = 2, (0 + 4)/2 = 2.
    p = np.array([0.0, 4.0, 0.0, 4.0, 0.0])
    np.testing.assert_allclose(inbetween.smooth(p, method="linear"), [0, 2, 2, 2, 0])
    with pytest.raises(ValueError):
        inbetween.smooth(line, method="spline")


def test_find_path_equals_the_tools_path_find(source_dir, cli, tmp_path):
    env = source_dir / "examples" / "environments" / "hole_and_mover.json"
    curve, timing = inbetween.find_path(env)
    out = tmp_path / "path.json"
    theirs = json.loads(cli("path", "find", env, "-o", out).stdout)
    assert json.loads(curve.to_json()) == json.loads(out.read_text())
    assert timing["duration"] == theirs["duration"] and timing["wait"] == theirs["wait"]
    assert [list(k) for k in timing["keys"]] == theirs["keys"]
    # The same from a dictionary.
    curve2, _ = inbetween.find_path(json.loads(env.read_text()))
    assert curve2.to_json() == curve.to_json()


@pytest.mark.parametrize("method", ["plane", "greedy", "edges"])
def test_surface_path_equals_the_tools_path_surface(method, source_dir, cli):
    mesh = source_dir / "tests" / "data" / "obj" / "blender_torus.obj"
    pts = inbetween.surface_path(str(mesh), 0, 40, method=method)
    rows = cli("path", "surface", mesh, "--from", 0, "--to", 40, "--method", method).stdout.split()
    assert rows[0] == "x,y,z"
    theirs = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    np.testing.assert_array_equal(pts, theirs)  # shortest round-trip text: the same doubles
    with pytest.raises(inbetween.Error):
        inbetween.surface_path(str(mesh), 0, 10**6, method=method)


def test_downhill_path_equals_the_tools(source_dir, cli):
    mesh = source_dir / "tests" / "data" / "obj" / "blender_icosphere.obj"
    pts = inbetween.downhill_path(str(mesh), 3, up=[0, 0, 1])
    rows = cli("path", "surface", mesh, "--downhill", 3, "--up", 0, 0, 1).stdout.split()
    theirs = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    np.testing.assert_array_equal(pts, theirs)


def test_a_device_mesh_is_refused_at_once():
    # Issue 21: surface_path("/dev/zero") read the device until memory ran out.
    with pytest.raises(inbetween.Error, match="not a regular file"):
        inbetween.surface_path("/dev/zero", 0, 1)


def test_surface_uv_and_downhill_paths_equal_the_tools(source_dir, cli):
    # Named surfaces (docs/paths.md): the same doubles as `path surface SURFACE.json`.
    sphere = source_dir / "examples" / "surfaces" / "sphere.json"
    pts = inbetween.surface_uv_path(sphere, [0, 0.5], [1.5, 0.5], count=7)
    rows = cli("path", "surface", sphere, "--from", 0, 0.5, "--to", 1.5, 0.5, "--count", 7).stdout.split()
    assert rows[0] == "u,v,x,y,z"
    theirs = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    np.testing.assert_array_equal(pts, theirs[:, 2:])
    # A circle of latitude (closed form): distance 2 cos 0.5 from the axis, height 2 sin 0.5.
    np.testing.assert_allclose(np.hypot(pts[:, 0], pts[:, 2]), 2 * np.cos(0.5), rtol=0, atol=1e-14)
    bowl = source_dir / "examples" / "surfaces" / "bowl.json"
    down = inbetween.surface_downhill_path(bowl, [1.5, 1])
    rows = cli("path", "surface", bowl, "--downhill", 1.5, 1).stdout.split()
    np.testing.assert_array_equal(down, np.array([[float(x) for x in r.split(",")] for r in rows[1:]]))
    assert np.hypot(down[-1, 0], down[-1, 2]) <= 0.5 / 20  # the bottom of y = x² + z², within a step
    # From a dictionary, and the errors.
    assert inbetween.surface_uv_path(json.loads(sphere.read_text()), [0, 0], [1, 0], count=2).shape == (2, 3)
    with pytest.raises(inbetween.Error, match="radius"):
        inbetween.surface_uv_path({"inbetween_surface": 1, "sphere": {"radius": -1}}, [0, 0], [1, 0])


def test_find_path_gives_a_capsules_poses_as_the_tool(source_dir, cli, tmp_path):
    env = source_dir / "examples" / "environments" / "capsule_slot.json"
    _, timing = inbetween.find_path(env)
    poses = tmp_path / "poses.csv"
    cli("path", "find", env, "-o", tmp_path / "p.json", "--poses", poses)
    rows = poses.read_text().split()
    assert rows[0] == "t,x,y,z,qw,qx,qy,qz"
    theirs = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    np.testing.assert_array_equal(np.array(timing["poses"]), theirs)
