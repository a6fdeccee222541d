#pragma once
/// Why a sampled scene value is not finite.  Finite keys can still give a world value beyond
/// double (a parent scale of 1e308 times a child's, linear extrapolation to frame 1e300): the
/// commands that sample a scene (bake, plot, view) refuse it, and this names the frame, the column
/// and the scene member that caused it, so that the message points into the file.

#include <cstddef>

#include "inbetween/math/expected.hpp"
#include "inbetween/scene/scene.hpp"

namespace inbetween {

/// The error for column `column` of `scene` holding `value` (NaN or ±inf) at `frame`: code
/// NotFinite, message "frame F: <column> is not a number" or "… overflows (inf)", followed by the
/// cause.  Location: for an object's column, the member of the object or ancestor whose local
/// value is not finite, else the one of largest magnitude among the translations and scales of
/// the object and its ancestors ({"objects", i, "scale"}: "parent's scale 1e+308 in the product");
/// {"objects", i} for a path object or camera whose own motion overflows; {"tracks", k} for a
/// track's column.  `column` < scene.columns().size().
[[nodiscard]] Error non_finite_value_error(const Scene& scene, double frame, std::size_t column, double value);

}  // namespace inbetween
