// AnyCurve: the curve families' names (their table, enum_names<CurveKind>(), is in any_curve.hpp).
#include "inbetween/curves/any_curve.hpp"

namespace inbetween {

std::string_view curve_kind_name(CurveKind kind) noexcept { return enum_name(kind); }

}  // namespace inbetween
