// Pose along a path at an animation frame: p = P(U(S(t))) plus a frame field at the same u.
#include "inbetween/paths/path_pose.hpp"

#include <gtest/gtest.h>

#include "inbetween/paths/rotation_minimizing_frames.hpp"
#include "paths_test_curves.hpp"

namespace inbetween {
namespace {

TEST(PathPose, ComposesMotionAndFrames) {
  const Helix<double> h;
  auto arc = make_arc_length(h);
  auto rmf = build_rotation_minimizing_frames(h);
  ASSERT_TRUE(arc && rmf);
  const FrameRange<double> range{10, 50};
  const SineEase<double> ease;
  for (double f : {0.0, 10.0, 17.5, 30.0, 50.0, 60.0}) {
    SCOPED_TRACE(f);
    const PathPose<double> p = pose_at_frame(h, *arc, ease, *rmf, range, f);
    const auto m = motion_at_frame(h, *arc, ease, range, f);
    EXPECT_EQ(p.position, m.position);
    EXPECT_EQ(p.u, m.u);
    // The helix has constant speed √1.25, so u = s/√1.25 and s = L·ease(t) (Eq. 3.18).
    const double t = std::clamp((f - 10) / 40, 0.0, 1.0);
    EXPECT_NEAR(p.s, arc->length() * (1 - std::cos(pi_v<double> * t)) / 2, 1e-9);
    EXPECT_NEAR(p.u, p.s / std::sqrt(1.25), 1e-9);
    // The object's x axis is the tangent, y the RMF normal.
    const Transformd x = p.transform();
    const Vec3d along = x.apply_to_direction(Vec3d{1, 0, 0});
    EXPECT_NEAR(distance(along, rmf->frame_at(p.u).tangent), 0.0, 1e-14);
    EXPECT_NEAR(distance(x.apply_to_direction(Vec3d{0, 1, 0}), rmf->frame_at(p.u).normal), 0.0, 1e-14);
    EXPECT_EQ(x.translation, p.position);
  }
}

}  // namespace
}  // namespace inbetween
