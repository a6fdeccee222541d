// Camera orientation (texts 004 §3.4.2 "Camera path following", Eqs. 3.33–3.34).
#include "inbetween/paths/camera.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "inbetween/curves/catmull_rom.hpp"
#include "paths_test_curves.hpp"
#include "support/museum_paths.hpp"
#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

template <class T>
void expect_vec_near(const Vec3<T>& a, const Vec3<T>& b, T tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

template <class T>
void expect_camera_axes(const CameraPose<T>& c, T tol) {
  ASSERT_TRUE(is_finite(c.right) && is_finite(c.up) && is_finite(c.forward));
  EXPECT_NEAR(norm(c.right), T(1), tol);
  EXPECT_NEAR(norm(c.up), T(1), tol);
  EXPECT_NEAR(norm(c.forward), T(1), tol);
  // Right-handed camera: x × y = z = −forward.
  expect_vec_near(cross(c.right, c.up), -c.forward, tol);
  EXPECT_NEAR(determinant(c.rotation_matrix()), T(1), tol);
}

TEST(Camera, DefaultViewIsTheIdentity) {
  // Eye on +z looking at the origin with y up: the camera frame is the world frame (OpenGL default).
  const CameraPosed c = look_at(Vec3d{0, 0, 5}, Vec3d{0, 0, 0});
  expect_vec_near(c.right, Vec3d{1, 0, 0}, 0.0);
  expect_vec_near(c.up, Vec3d{0, 1, 0}, 0.0);
  expect_vec_near(c.forward, Vec3d{0, 0, -1}, 0.0);
  const Mat4d v = c.view_matrix();
  EXPECT_EQ(v.translation(), (Vec3d{0, 0, -5}));
  EXPECT_EQ(max_abs_diff(v.linear(), Mat3d::identity()), 0.0);
}

TEST(Camera, ViewMatrixMapsEyeToOriginAndTargetDownMinusZ) {
  test::Random rng(test::seed_for(3));
  SCOPED_TRACE(rng.trace());
  for (int k = 0; k < 100; ++k) {
    const Vec3d eye = rng.vec3(-10.0, 10.0), target = rng.vec3(-10.0, 10.0);
    const CameraPosed c = look_at(eye, target, Vec3d{0, 1, 0});
    expect_camera_axes(c, 1e-14);
    const Mat4d v = c.view_matrix();
    expect_vec_near(transform_point(v, eye), Vec3d{}, 1e-13);
    expect_vec_near(transform_point(v, target), Vec3d{0, 0, -distance(eye, target)}, 1e-13);
    // Eq. 3.33: u = w × (0, 1, 0) normalised, v = u × w; the camera up lies in the plane of w and y.
    const Vec3d u = normalized(cross(c.forward, Vec3d{0, 1, 0}), Vec3d{});
    expect_vec_near(c.right, u, 1e-14);
    expect_vec_near(c.up, cross(u, c.forward), 1e-14);
    EXPECT_GE(c.up.y, 0.0);
    // The transform and the matrix agree.
    expect_vec_near(c.world_from_camera().apply_to_point(Vec3d{0, 0, -1}), eye + c.forward, 1e-13);
  }
}

TEST(Camera, Equation334UsesAnUpPath) {
  // P = (0, 0, 0), C = (1, 0, 0), U = (0, 0, 2): w = (1, 0, 0), up direction U − P = (0, 0, 2):
  // u = w × (0, 0, 2) ∝ (0, −1, 0), v = u × w = (0, 0, 1).
  const CameraPosed c = look_at(Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{0, 0, 2} - Vec3d{0, 0, 0});
  expect_vec_near(c.right, Vec3d{0, -1, 0}, 0.0);
  expect_vec_near(c.up, Vec3d{0, 0, 1}, 0.0);
}

TEST(Camera, TiltTurnsUpTowardsRight) {
  const CameraPosed c = look_at(Vec3d{0, 0, 5}, Vec3d{}, Vec3d{0, 1, 0}, {.tilt_rad = pi_v<double> / 2});
  expect_vec_near(c.up, Vec3d{1, 0, 0}, 1e-15);   // old right
  expect_vec_near(c.right, Vec3d{0, -1, 0}, 1e-15);
}

TYPED_TEST_SUITE_P(CameraMuseum);
template <class T>
class CameraMuseum : public ::testing::Test {};
TYPED_TEST_P(CameraMuseum, DegenerateSetUpsUseTheFallbacks) {
  using T = TypeParam;
  for (const auto& ex : test::museum_cameras<T>()) {
    SCOPED_TRACE(ex.name);
    const CameraPose<T> c = look_at(ex.eye, ex.target, ex.up);
    expect_camera_axes(c, T(8) * test::roundtrip_tol<T>);
  }
  // Up parallel to view: fallback_up (0, 0, 1) gives right = (0,1,0) × (0,0,1) = (1, 0, 0), up = +z.
  const CameraPose<T> c = look_at(Vec3<T>{}, Vec3<T>{0, 5, 0}, Vec3<T>{0, 1, 0});
  expect_vec_near(c.right, Vec3<T>{1, 0, 0}, T(0));
  expect_vec_near(c.up, Vec3<T>{0, 0, 1}, T(0));
  // Target at the eye: fallback_forward (0, 0, −1).
  const CameraPose<T> d = look_at(Vec3<T>{1, 2, 3}, Vec3<T>{1, 2, 3});
  expect_vec_near(d.forward, Vec3<T>{0, 0, -1}, T(0));
}
REGISTER_TYPED_TEST_SUITE_P(CameraMuseum, DegenerateSetUpsUseTheFallbacks);
using Scalars = ::testing::Types<float, double>;
INSTANTIATE_TYPED_TEST_SUITE_P(Scalar, CameraMuseum, Scalars);

TEST(LookAhead, StraightPieceLooksAlongThePathAndTheEndLooksAlongTheEndTangent) {
  auto arc = make_arc_length(test::ArcLineArc<double>{});
  ASSERT_TRUE(arc);
  const double w = pi_v<double> / 2;  // length of each piece (speed π/2 over a unit of u)
  EXPECT_NEAR(arc->length(), 3 * w, 1e-12);
  // Inside the straight piece with the look-ahead still on it: the view is +x.
  const CameraPosed c = look_ahead_camera(*arc, w + 0.2, {.ahead = 0.5});
  expect_vec_near(c.forward, Vec3d{1, 0, 0}, 1e-12);
  expect_camera_axes(c, 1e-14);
  // At the end the COI is continued along the end tangent (0, 0, −1) (φ = π/2 on the second arc).
  const CameraPosed e = look_ahead_camera(*arc, arc->length(), {.ahead = 0.5, .average_count = 4});
  expect_vec_near(e.forward, Vec3d{0, 0, -1}, 1e-12);
  // Δs = 0 looks along the tangent: on the first arc at u = 0.5 it is (cos φ, sin φ, 0), φ = −π/4.
  const CameraPosed t = look_ahead_camera(*arc, arc->s_at(0.5));
  const double r = std::sqrt(0.5);
  expect_vec_near(t.forward, Vec3d{r, -r, 0}, 1e-12);
  // Looking ahead on the first arc: the view is the chord to P(s + Δs).
  const double s = arc->s_at(0.25);
  const CameraPosed q = look_ahead_camera(*arc, s, {.ahead = 0.3});
  expect_vec_near(q.forward, normalized(Vec3d(arc->point_at_length(s + 0.3) - arc->point_at_length(s)), Vec3d{}), 1e-12);
}

TEST(LookAhead, MuseumPathsGiveFiniteCameras) {
  for (const auto& ex : test::museum_paths<double>()) {
    SCOPED_TRACE(ex.name);
    auto curve = build_catmull_rom(ex.points);
    if (!curve) {
      EXPECT_LT(ex.points.size(), 2u) << curve.error().describe();  // only the single point has no curve
      continue;
    }
    auto arc = make_arc_length(*curve);
    ASSERT_TRUE(arc);
    for (double f : {0.0, 0.3, 0.5, 1.0}) {
      const CameraPosed c = look_ahead_camera(*arc, f * arc->length(), {.ahead = 0.4, .average_count = 3});
      expect_camera_axes(c, 1e-13);
    }
  }
}

TEST(CameraBetweenPaths, EyeOnOneLineLooksAtAPointOnAnother) {
  // Eye on the line (0,0,0) → (10,0,0), centre of interest on (0,0,−5) → (20,0,−5): at fraction
  // 0.5 the eye is (5, 0, 0) and the COI (10, 0, −5); view (5, 0, −5)/√50.  Up path
  // (0,10,0) → (10,10,0): U − P = (0, 10, 0), so the camera up is the y-ward perpendicular.
  const std::vector<Vec3d> a{{0, 0, 0}, {10, 0, 0}}, b{{0, 0, -5}, {20, 0, -5}}, c{{0, 10, 0}, {10, 10, 0}};
  auto pa = make_arc_length(*build_catmull_rom(a));
  auto pb = make_arc_length(*build_catmull_rom(b));
  auto pc = make_arc_length(*build_catmull_rom(c));
  ASSERT_TRUE(pa && pb && pc);
  const double r = std::sqrt(0.5);
  const CameraPosed cam = camera_between_paths(*pa, *pb, 0.5);
  expect_vec_near(cam.eye, Vec3d{5, 0, 0}, 1e-12);
  expect_vec_near(cam.forward, Vec3d{r, 0, -r}, 1e-12);
  expect_vec_near(cam.up, Vec3d{0, 1, 0}, 1e-12);
  const CameraPosed up = camera_between_paths(*pa, *pb, *pc, 0.5);
  expect_vec_near(up.up, Vec3d{0, 1, 0}, 1e-12);
  expect_vec_near(up.right, Vec3d{r, 0, r}, 1e-12);  // forward × up = (r,0,−r) × (0,1,0)
  const CameraPosed end = camera_between_paths(*pa, *pb, 7.0);  // clamped to 1
  expect_vec_near(end.eye, Vec3d{10, 0, 0}, 1e-12);
}

}  // namespace
}  // namespace inbetween
