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
