"""Named tolerances of the Python suite, each with its source."""
# Rotation conversions in double: both sides are a few ulp accurate (docs/conventions.md; SciPy
# uses the same quaternion-method Euler extraction of Bernardes & Viollet): 1e-12 rad leaves room
# for ~4500 ulp of pi, far above either side's error, far below any real convention mix-up (~0.1).
ROTATION_RAD = 1e-12
# Matrix and quaternion components agree to 1e-14 (a few ulp of 1 over 3-term sums).
COMPONENT = 1e-14
# Euler angles close to gimbal lock are ill-conditioned: compared through the rebuilt rotation.
# Slerp: both formulas are ulp-accurate (ours: docs/orientation.md; SciPy's: rotvec composition).
SLERP_RAD = 1e-12
# Arc length: ArcLength guarantees 1e-9 * L on s(u) and u(s) (include/inbetween/arclength/arc_length.hpp);
# the inverse checks 1e-10 * L.  scipy.integrate.quad at epsabs 1e-13 is the independent reference.
ARC_LENGTH_REL = 1e-9
# B-spline least squares vs scipy.interpolate.make_lsq_spline on the same knots: both solve the
# same well-conditioned system (QR in SciPy, Eigen here); 1e-10 relative to the data's scale.
LSQ_REL = 1e-10
# load_clip: a child's world transform recomposed in NumPy from its parent's world and its local
# transform (t = tp + Rp(sp * tl), q = qp ql) against the library's world columns: a few roundings
# of O(1..10) values per level, 64 ulp of the scene's size is ample and far below any frame mix-up.
COMPOSE_REL = 64 * 2.220446049250313e-16
# glTF accessors are float32: values read back from a .glb agree with the double scene to float
# rounding of O(1) values (a few float ulp).
GLTF_FLOAT = 4 * 1.1920929e-07
# blend_poses in double against the NumPy formulas of docs/blending.md (sums of a few weighted
# terms divided by their weight sum, then a normalisation): 1e-12 of the O(1..5) values is far above
# both sides' rounding and far below any formula mix-up (a wrong sign or weight moves results by 0.1).
BLEND_ABS = 1e-12
# Root motion: motion composed with the character-space root gives the root back to 1e-6 of the
# clip's extent (issue 23's bound); double rounding is ~1e-15 of it.
ROOT_MOTION_REL = 1e-6
