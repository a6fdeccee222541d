#pragma once
/// Umbrella header: every public header of the core library (math → curves → arclength → timing →
/// tracks → paths).  Include single headers instead where compile time matters.

// math
#include "inbetween/math/assert.hpp"
#include "inbetween/math/expected.hpp"
#include "inbetween/math/mat.hpp"
#include "inbetween/math/quat.hpp"
#include "inbetween/math/scalar.hpp"
#include "inbetween/math/vec.hpp"

// curves
#include "inbetween/curves/curve.hpp"

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
