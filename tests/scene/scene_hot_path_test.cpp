// Scene::sample() never allocates, at any object count (house rule 10; the scene used to fall back
// to a std::vector beyond 64 objects).  As in tests/tracks/hot_path_test.cpp, this program's global
// operator new counts allocations while the counter is switched on.
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "inbetween/scene/scene.hpp"

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

template <class F>
long allocations_in(F&& f) {
  g_allocations = 0;
  g_counting = true;
  f();
  g_counting = false;
  return g_allocations;
}

TEST(SceneHotPath, CounterSeesAnAllocation) {
  EXPECT_EQ(allocations_in([] { std::vector<int> v(1); (void)v; }), 1);
}

// Every track kind and a hierarchy of `objects` objects (each the child of the previous one).
RawScene scene_with(std::size_t objects) {
  RawScene raw;
  RawScalarTrack s;
  s.name = "s";
  s.curve.keys = {FCurveKey{.frame = 0, .value = 0}, FCurveKey{.frame = 10, .value = 1}};
  raw.tracks.push_back(s);
  RawVectorTrack v;
  v.name = "v";
  v.kind = VectorKind::color;
  v.keys = {TrackKey<Vec4d>{.frame = 0}, TrackKey<Vec4d>{.frame = 10, .value = Vec4d{1, 1, 1, 1}}};
  raw.tracks.push_back(v);
  RawQuatTrack q;
  q.name = "q";
  q.keys = {QuatKey<double>{.frame = 0}, QuatKey<double>{.frame = 10, .value = Quatd::from_wxyz(0, 1, 0, 0),
                                                        .interpolation = QuatInterpolation::bezier}};
  raw.tracks.push_back(q);
  RawEulerTrack e;
  e.name = "e";
  e.convention = "ZXZ";
  e.keys = {RawEulerKey{.frame = 0}, RawEulerKey{.frame = 10, .value = Vec3d{1, 2, 3}}};
  raw.tracks.push_back(e);
  for (std::size_t i = 0; i < objects; ++i) {
    RawObject o;
    o.name = "o" + std::to_string(i);
    if (i > 0) o.parent = "o" + std::to_string(i - 1);
    RawVec3Channel t;
    t.keys = {TrackKey<Vec3d>{.frame = 0}, TrackKey<Vec3d>{.frame = 10, .value = Vec3d{1, 0, 0}}};
    o.translation = t;
    raw.objects.push_back(o);
  }
  return raw;
}

TEST(SceneHotPath, SampleNeverAllocatesAtAnyObjectCount) {
  for (std::size_t objects : {std::size_t{0}, std::size_t{1}, std::size_t{64}, std::size_t{65}, std::size_t{1000}}) {
    SCOPED_TRACE(objects);
    auto scene = build_scene(scene_with(objects));
    ASSERT_TRUE(scene.has_value()) << scene.error().describe();
    std::vector<double> out(scene->columns().size());
    const long n = allocations_in([&] {
      for (double frame = -2; frame <= 12; frame += 0.25) scene->sample(frame, out);
    });
    EXPECT_EQ(n, 0);
  }
}

}  // namespace
}  // namespace inbetween
