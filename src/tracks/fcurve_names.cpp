// to_string for the F-curve enumerations: each reads its enum's one name table (fcurve.hpp).
#include "inbetween/tracks/fcurve.hpp"

namespace inbetween {

std::string_view to_string(Interpolation v) noexcept { return enum_name(v); }
std::string_view to_string(KeyEasing v) noexcept { return enum_name(v); }
std::string_view to_string(HandleType v) noexcept { return enum_name(v); }
std::string_view to_string(Extrapolation v) noexcept { return enum_name(v); }
std::string_view to_string(AutoSmoothing v) noexcept { return enum_name(v); }
std::string_view to_string(CycleMode v) noexcept { return enum_name(v); }

}  // namespace inbetween
