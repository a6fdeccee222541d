// enum_from_string for the tracks enums: each reads its enum's one name table (enum_names<Enum>()).
#include "inbetween/tracks/enum_names.hpp"

#include "inbetween/tracks/euler_track.hpp"
#include "inbetween/tracks/fcurve.hpp"
#include "inbetween/tracks/quat_track.hpp"
#include "inbetween/tracks/track.hpp"

namespace inbetween {

#define INBETWEEN_ENUM_FROM_STRING(Enum)                                              \
  template <>                                                                         \
  std::optional<Enum> enum_from_string<Enum>(std::string_view name) noexcept {        \
    return find_enum_name<Enum>(enum_names<Enum>(), name);                            \
  }

INBETWEEN_ENUM_FROM_STRING(Interpolation)
INBETWEEN_ENUM_FROM_STRING(KeyEasing)
INBETWEEN_ENUM_FROM_STRING(HandleType)
INBETWEEN_ENUM_FROM_STRING(Extrapolation)
INBETWEEN_ENUM_FROM_STRING(AutoSmoothing)
INBETWEEN_ENUM_FROM_STRING(CycleMode)
INBETWEEN_ENUM_FROM_STRING(TangentKind)
INBETWEEN_ENUM_FROM_STRING(TrackExtend)
INBETWEEN_ENUM_FROM_STRING(QuatInterpolation)
INBETWEEN_ENUM_FROM_STRING(EulerTrackMode)

#undef INBETWEEN_ENUM_FROM_STRING

}  // namespace inbetween
