// A downstream program that only knows the installed headers and find_package(inbetween).
#include <inbetween/inbetween.hpp>

#include <cmath>
#include <cstdio>

int main() {
  using namespace inbetween;
  const Quatd q = Quatd::from_axis_angle(Vec3d{0, 0, 1}, pi_v<double> / 2);
  const Vec3d p = rotate(q, Vec3d{1, 0, 0});
  const bool ok = std::abs(p.x) < 1e-12 && std::abs(p.y - 1.0) < 1e-12;
  std::printf("%s\n", ok ? "consumer ok" : "consumer wrong");
  return ok ? 0 : 1;
}
