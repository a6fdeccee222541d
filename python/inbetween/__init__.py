"""inbetween: keyframe animation from Python (docs/python.md).

NumPy-first bindings of the C++ library: arrays in, arrays out, the loops in C++.
Quaternions are (..., 4) arrays in w, x, y, z order; matrices (..., 3, 3) with v' = R v;
angles in radians.  Bad user data raises inbetween.Error (a ValueError) with .message,
.where (the JSON pointer or place, as the command-line tool prints it) and .code.
"""
from ._inbetween import *  # noqa: F401,F403
from ._inbetween import Error, __doc__ as _ext_doc  # noqa: F401
from . import _inbetween

__all__ = [name for name in dir(_inbetween) if not name.startswith("_")]


def ease(spec, t):
    """The normalised ease S(t) of an ease dictionary (a scene file's speed.ease, e.g.
    {"kind": "penner", "curve": "bounce", "direction": "out"}) at normalised times t
    (array, clamped to [0, 1]): S(0) = 0, S(1) = 1."""
    import numpy as np
    speed = _inbetween.Speed({"kind": "ease", "start_frame": 0, "end_frame": 1, "ease": spec}, length=1.0)
    return speed.distance(np.asarray(t, dtype=float))


__all__.append("ease")


def bake(scene, frames=None, step=1.0, animation="", fps=24.0):
    """Bakes a scene: `scene` is an inbetween.Scene, or a scene or glTF file path, a dictionary or
    JSON text (read with Scene(scene, animation, fps)).  Returns (values, columns): an
    (n, len(columns)) array, one row per frame (`frames`, or the scene's range at `step`), and the
    column names -- frame, time, then the scene's columns, as the CSV of `inbetween bake`."""
    if not isinstance(scene, _inbetween.Scene):
        scene = _inbetween.Scene(scene, animation=animation, fps=fps)
    return scene.bake(frames, step)


__all__.append("bake")
