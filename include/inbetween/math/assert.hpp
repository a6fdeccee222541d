#pragma once
/// INBETWEEN_ASSERT: checks caller bugs (wrong span sizes, out-of-range indices), not user data.
/// Active unless NDEBUG is defined or INBETWEEN_DISABLE_ASSERTS is set; on failure it prints the
/// condition and location to stderr and aborts.

#include <cstdio>
#include <cstdlib>

#if defined(NDEBUG) || defined(INBETWEEN_DISABLE_ASSERTS)
#define INBETWEEN_ASSERT(cond) ((void)0)
#else
#define INBETWEEN_ASSERT(cond)                                                                   \
  ((cond) ? (void)0                                                                              \
          : (std::fprintf(stderr, "inbetween: assertion failed: %s (%s:%d)\n", #cond, __FILE__,   \
                          __LINE__),                                                             \
             std::abort()))
#endif
