// The runtime contract of the scene module (house rule 10): per-frame evaluation is noexcept and
// never allocates.  This file replaces the global operator new of the scene test program with a
// counting one (as tests/tracks/hot_path_test.cpp does for tracks); the count is switched on only
// around the calls under test.  Keep one such replacement per test program: add further scene
// hot-path checks here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <new>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "inbetween/curves/catmull_rom.hpp"
#include "inbetween/scene/camera_view.hpp"

namespace {
long g_allocations = 0;
bool g_counting = false;
}  // namespace

void* operator new(std::size_t size) {
  if (g_counting) ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc{};
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace inbetween {
namespace {

// Runs `f` with the allocation counter on and returns the number of allocations it made.
template <class F>
long allocations_in(F&& f) {
  g_allocations = 0;
  g_counting = true;
  f();
  g_counting = false;
  return g_allocations;
}

TEST(SceneHotPath, CounterSeesAnAllocation) {
  // The counter itself can fail: a vector of one element allocates once.
  EXPECT_EQ(allocations_in([] { std::vector<int> v(1); (void)v; }), 1);
}

template <class T>
class SceneHotPathTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SceneHotPathTyped, Scalars);

TYPED_TEST(SceneHotPathTyped, CameraViewEvaluationNeverAllocates) {
  using T = TypeParam;
  static_assert(noexcept(std::declval<const CameraView<T>&>().evaluate(CameraInputs<T>{})));
  const std::vector<Vec3<T>> pts{{-5, 0, 0}, {0, 3, 0}, {5, 0, 0}, {5, 4, 3}};
  const auto arc = make_arc_length(*build_catmull_rom(pts)).value();
  const std::vector<RawCameraView<T>> raws{
      {.coi = RawLookAt<T>{Vec3<T>{1, 2, 3}}},
      {.coi = RawLookAt<T>{std::string("o")}, .tilt_deg = T(10)},
      {.coi = RawLookAhead<T>{.distance = T(1), .count = 5, .spread = T(2)}},
      {.coi = RawCoiPath{"p"}, .up_path = "p"},
      {.coi = RawHoldThenMove<T>{{{.target = std::string("o"), .hold_until = T(3), .move_frames = T(4)},
                                  {.target = Vec3<T>{0, 0, -4}, .hold_until = T(9)}}}},
  };
  std::vector<CameraView<T>> views;
  for (const auto& raw : raws) views.push_back(build_camera_view(raw).value());
  const Vec3<T> targets[] = {Vec3<T>{1, 1, 1}};
  T checksum = T(0);
  const long n = allocations_in([&] {
    for (const auto& view : views) {
      for (int f = 0; f <= 12; ++f) {
        const T s = arc.length() * T(f) / T(10);
        const std::span<const Vec3<T>> tspan(targets, view.target_names().size());
        const CameraViewSample<T> v = view.evaluate({.frame = T(f), .eye = arc.point_at_length(s),
                                                     .camera_path = path_view(arc), .s = s,
                                                     .coi_path = path_view(arc), .up_path = path_view(arc),
                                                     .targets = tspan});
        checksum += v.pose.forward.x + v.target.y;
      }
    }
  });
  EXPECT_EQ(n, 0);
  EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
}  // namespace inbetween
