#pragma once
/// Umbrella header: every public header of the core library (math → curves → arclength → timing →
/// tracks → paths → scene).  Include single headers instead where compile time matters.

// math
#include "inbetween/math/assert.hpp"
#include "inbetween/math/euler.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/orientation_interp.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/rotation.hpp"
#include "inbetween/math/scalar.hpp"
#include "inbetween/math/transform.hpp"
#include "inbetween/math/vec.hpp"

// curves
#include "inbetween/curves/any_curve.hpp"
#include "inbetween/curves/bezier.hpp"
#include "inbetween/curves/bezier_path.hpp"
#include "inbetween/curves/bspline.hpp"
#include "inbetween/curves/bspline_basis.hpp"
#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/curves/continuity.hpp"
#include "inbetween/curves/cubic_basis.hpp"
#include "inbetween/curves/cubic_spline.hpp"
#include "inbetween/curves/curve.hpp"
#include "inbetween/curves/helix.hpp"
#include "inbetween/curves/hermite_spline.hpp"
#include "inbetween/curves/kochanek_bartels.hpp"
#include "inbetween/curves/lagrange.hpp"
#include "inbetween/curves/parabolic_blend.hpp"
#include "inbetween/curves/piecewise_cubic.hpp"
#include "inbetween/curves/segment_index.hpp"

// arclength
#include "inbetween/arclength/accuracy.hpp"
#include "inbetween/arclength/arc_length.hpp"
#include "inbetween/arclength/arc_length_table.hpp"
#include "inbetween/arclength/cubic_speed.hpp"
#include "inbetween/arclength/gauss_legendre.hpp"
#include "inbetween/arclength/quadrature_length.hpp"

// timing
#include "inbetween/timing/bspline_fit.hpp"  // implemented in inbetween_eigen (link inbetween::eigen)
#include "inbetween/timing/cubic_bezier_timing.hpp"
#include "inbetween/timing/distance_time.hpp"
#include "inbetween/timing/ease.hpp"
#include "inbetween/timing/motion.hpp"
#include "inbetween/timing/penner.hpp"
#include "inbetween/timing/piecewise_distance.hpp"

// tracks
#include "inbetween/tracks/euler_track.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"
#include "inbetween/tracks/transform_track.hpp"

// paths
#include "inbetween/paths/banking.hpp"
#include "inbetween/paths/camera.hpp"
#include "inbetween/paths/frenet_frames.hpp"
#include "inbetween/paths/graph_path.hpp"
#include "inbetween/paths/mesh_path.hpp"
#include "inbetween/paths/path_finding.hpp"
#include "inbetween/paths/path_frame.hpp"
#include "inbetween/paths/path_pose.hpp"
#include "inbetween/paths/rotation_minimizing_frames.hpp"
#include "inbetween/paths/smooth_bspline.hpp"  // uses fit_bspline from inbetween_eigen (link inbetween::eigen)
#include "inbetween/paths/smoothing.hpp"
#include "inbetween/paths/surface_path.hpp"
#include "inbetween/paths/triangle_mesh.hpp"

// scene
#include "inbetween/scene/camera_view.hpp"
#include "inbetween/scene/path_motion.hpp"
