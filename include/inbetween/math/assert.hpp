#pragma once
/// INBETWEEN_ASSERT: checks caller bugs (wrong span sizes, out-of-range indices), not user data.
/// Active unless NDEBUG is defined or INBETWEEN_DISABLE_ASSERTS is set; INBETWEEN_ENABLE_ASSERTS
/// turns it on despite NDEBUG (the asan preset: the libraries it uses keep NDEBUG, the project's
/// own checks run), and INBETWEEN_DISABLE_ASSERTS wins over both.  On failure it prints the
/// condition and location to stderr and aborts.

#include <cstdio>
#include <cstdlib>

/// 1 where INBETWEEN_ASSERT checks its condition, 0 where it compiles to nothing.
#if defined(INBETWEEN_DISABLE_ASSERTS)
#define INBETWEEN_ASSERTS_ACTIVE 0
#elif defined(INBETWEEN_ENABLE_ASSERTS) || !defined(NDEBUG)
#define INBETWEEN_ASSERTS_ACTIVE 1
#else
#define INBETWEEN_ASSERTS_ACTIVE 0
#endif

#if !INBETWEEN_ASSERTS_ACTIVE
#define INBETWEEN_ASSERT(cond) ((void)0)
#else
#define INBETWEEN_ASSERT(cond)                                                                   \
  ((cond) ? (void)0                                                                              \
          : (std::fprintf(stderr, "inbetween: assertion failed: %s (%s:%d)\n", #cond, __FILE__,   \
                          __LINE__),                                                             \
             std::abort()))
#endif
