#pragma once
// A counting global operator new for the "never allocates" tests (house rule 10).  Include this
// header from exactly ONE source file of a test program (it defines the replacement operators);
// the count is switched on only inside allocations_in().
#include <cstddef>
#include <cstdlib>
#include <new>

namespace inbetween::test {
inline long g_allocations = 0;  ///< allocations seen while counting
inline bool g_counting = false;  ///< counting on or off

/// Runs `f` with the allocation counter on and returns the number of allocations it made.
template <class F>
long allocations_in(F&& f) {
  g_allocations = 0;
  g_counting = true;
  f();
  g_counting = false;
  return g_allocations;
}
}  // namespace inbetween::test

void* operator new(std::size_t size) {
  if (inbetween::test::g_counting) ++inbetween::test::g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc{};
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
// The nothrow and array forms too: std::stable_sort's temporary buffer uses nothrow new and frees
// with plain delete, so every form must come from the same malloc (AddressSanitizer reports an
// alloc-dealloc mismatch otherwise), and a sampling path must not hide an allocation in them.
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  if (inbetween::test::g_counting) ++inbetween::test::g_allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
  return operator new(size, tag);
}
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
