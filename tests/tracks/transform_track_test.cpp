// Transform tracks and hierarchies.  Sources: closed forms (a quarter turn about z), and equality
// of TRS composition with the matrix product when no shear arises.
#include "inbetween/tracks/transform_track.hpp"

#include <gtest/gtest.h>

#include "support/random.hpp"
#include "support/tolerances.hpp"

namespace inbetween {
namespace {

const Vec3d kZ{0, 0, 1};
// A few products of unit-magnitude values.
constexpr double kTol = 1e-14;

Vec3d apply(const Mat4d& m, const Vec3d& p) {
  const Vec4d r = m * Vec4d{p.x, p.y, p.z, 1};
  return {r.x, r.y, r.z};
}

TEST(TransformTrackTrs, MatrixIsTranslationRotationScale) {
  const Transform<double> trs{.translation = {1, 2, 3}, .rotation = Quatd::from_axis_angle(kZ, pi_v<double> / 2),
                        .scale = {2, 1, 1}};
  // (1,0,0) scaled to (2,0,0), turned a quarter about z to (0,2,0), moved to (1,4,3).
  const Vec3d p = apply(trs.to_matrix(), {1, 0, 0});
  EXPECT_NEAR(p.x, 1, kTol);
  EXPECT_NEAR(p.y, 4, kTol);
  EXPECT_NEAR(p.z, 3, kTol);
}

TEST(TransformTrackTrs, ComposeEqualsMatrixProductWithUniformScale) {
  test::Random rng(test::seed_for(5040));
  SCOPED_TRACE(rng.trace());
  for (int i = 0; i < 100; ++i) {
    const double sp = rng.uniform(0.5, 2.0), sc = rng.uniform(0.5, 2.0);
    const Transform<double> parent{.translation = rng.vec3(), .rotation = rng.rotation(), .scale = {sp, sp, sp}};
    const Transform<double> child{.translation = rng.vec3(), .rotation = rng.rotation(),
                            .scale = {sc, rng.uniform(0.5, 2.0), sc}};  // child may be non-uniform
    EXPECT_LT(max_abs_diff(compose(parent, child).to_matrix(), parent.to_matrix() * child.to_matrix()), 1e-13);
  }
}

TEST(TransformHierarchy, ChildFollowsRotatingParent) {
  std::vector<HierarchyNode<double>> nodes(2);
  nodes[0].name = "arm";
  std::vector<QuatKey<double>> keys(2);
  keys[0].frame = 0;
  keys[1].frame = 10;
  keys[1].value = Quatd::from_axis_angle(kZ, pi_v<double> / 2);
  nodes[0].local.rotation = std::move(build_quat_track(keys)).value();
  nodes[1].name = "hand";
  nodes[1].parent = 0;
  nodes[1].local.rest.translation = {2, 0, 0};
  auto h = build_transform_hierarchy(nodes);
  ASSERT_TRUE(h.has_value());
  std::vector<Transform<double>> world(2);
  std::vector<Mat4d> mats(2);
  h->sample_world(10.0, std::span<Transform<double>>(world));
  h->sample_world(10.0, std::span<Mat4d>(mats));
  // After a quarter turn of the arm the hand at (2,0,0) is at (0,2,0).
  EXPECT_NEAR(world[1].translation.x, 0, kTol);
  EXPECT_NEAR(world[1].translation.y, 2, kTol);
  EXPECT_NEAR(mats[1].translation().y, 2, kTol);
  h->sample_world(5.0, std::span<Transform<double>>(world));
  EXPECT_NEAR(world[1].translation.x, 2 * std::cos(pi_v<double> / 4), kTol);  // slerp halfway: 45°
}

TEST(TransformHierarchy, ChildrenBeforeParentsInTheListAreFine) {
  std::vector<HierarchyNode<double>> nodes(3);
  nodes[0].parent = 1;
  nodes[1].parent = 2;
  nodes[2].local.rest.translation = {1, 0, 0};
  nodes[1].local.rest.translation = {0, 1, 0};
  nodes[0].local.rest.translation = {0, 0, 1};
  auto h = build_transform_hierarchy(nodes);
  ASSERT_TRUE(h.has_value());
  std::vector<Transform<double>> world(3);
  h->sample_world(0.0, std::span<Transform<double>>(world));
  EXPECT_EQ(world[0].translation, (Vec3d{1, 1, 1}));
}

TEST(TransformHierarchy, RejectsCyclesAndBadParents) {
  std::vector<HierarchyNode<double>> nodes(2);
  nodes[0].name = "a";
  nodes[1].name = "b";
  nodes[0].parent = 1;
  nodes[1].parent = 0;
  auto h = build_transform_hierarchy(nodes);
  ASSERT_FALSE(h.has_value());
  EXPECT_NE(h.error().message.find("own ancestor"), std::string::npos);
  nodes[1].parent = 7;
  h = build_transform_hierarchy(nodes);
  ASSERT_FALSE(h.has_value());
  EXPECT_EQ(json_pointer(h.error().location), "/1/parent");
}

}  // namespace
}  // namespace inbetween
