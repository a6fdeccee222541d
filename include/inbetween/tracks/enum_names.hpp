#pragma once
/// The name-table mechanism moved to math (every module's enums use it); this header stays so that
/// code including it keeps compiling.
#include "inbetween/math/enum_names.hpp"
