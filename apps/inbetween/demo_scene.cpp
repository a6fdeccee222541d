// `inbetween demo`, section "scene": the texts' frame-22 scenario (000 §2.2–2.4, 004 §3.2–3.4) as
// the scene file examples/scenes/frame22.json (built into the tool), read and sampled by the
// library exactly as `inbetween bake examples/scenes/frame22.json` does: the ball's position,
// distance travelled and speed at the key frames, and where the two cameras look.
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "command.hpp"
#include "frame22_scene.hpp"
#include "inbetween/io/scene.hpp"

namespace inbetween::cli {
namespace {

std::string fixed(double v, int digits = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v == 0 ? 0.0 : v);  // no "-0.000"
  return buf;
}

std::string pad(std::string s, std::size_t width) {
  if (s.size() < width) s.insert(0, width - s.size(), ' ');
  return s;
}

void run(std::ostream& out) {
  auto scene = parse_scene(kFrame22SceneJson);
  if (!scene) {
    out << "  the built-in scene does not read: " << scene.error().describe() << "\n";
    return;
  }
  const auto columns = scene->columns();
  auto column = [&](const std::string& name) {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c].name == name) return c;
    return columns.size();
  };
  const std::size_t x = column("ball.translation.x"), d = column("ball.distance"), v = column("ball.speed"),
                    ft = column("follow_cam.target.x"), ht = column("hold_cam.target.x");
  if (ht == columns.size()) return;
  out << "examples/scenes/frame22.json: the ball rests at (-5, 0, 0) on frame 22, accelerates until 34,\n"
         "cruises until 50, comes to rest at (5, 0, 0) on 67 along an arc through (0, 3, 0), then climbs\n"
         "along a second (banked) curve to rest at (5, 10, 0) on 80; follow_cam rides the same legs lifted\n"
         "by (0, 2, 8), looking 3 ahead; hold_cam holds on the ball until 60, then pans to (5, 10, 0).\n"
         "(the same numbers as: inbetween bake examples/scenes/frame22.json)\n";
  out << "  frame   ball position               distance  speed/s   follow_cam looks at       hold_cam looks at\n";
  std::vector<double> row(columns.size());
  SceneCursor cursor(*scene);
  for (double f : {16.0, 22.0, 28.0, 34.0, 42.0, 50.0, 60.0, 67.0, 72.0, 76.0, 80.0, 86.0}) {
    scene->sample(f, row, cursor);
    auto point = [&](std::size_t c) {
      return "(" + fixed(row[c]) + ", " + fixed(row[c + 1]) + ", " + fixed(row[c + 2]) + ")";
    };
    out << pad(fixed(f, 0), 7) << "   " << point(x) << std::string(26 - std::min<std::size_t>(26, point(x).size()), ' ')
        << pad(fixed(row[d]), 8) << pad(fixed(row[v]), 9) << "   " << point(ft)
        << std::string(26 - std::min<std::size_t>(26, point(ft).size()), ' ') << point(ht) << "\n";
  }
}

const RegisterDemo kDemo{{"scene: the frame-22 scenario", 60, run}};

}  // namespace
}  // namespace inbetween::cli
