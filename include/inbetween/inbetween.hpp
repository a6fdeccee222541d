#pragma once
/// Umbrella header: every public header of the core library (math → curves → arclength → timing →
/// tracks → paths).  Include single headers instead where compile time matters.

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
#include "inbetween/curves/curve.hpp"

// timing
#include "inbetween/timing/penner.hpp"

// tracks
#include "inbetween/tracks/euler_track.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"
#include "inbetween/tracks/transform_track.hpp"
