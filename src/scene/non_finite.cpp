// Naming the cause of a non-finite sampled value (inbetween/scene/non_finite.hpp).
#include "inbetween/scene/non_finite.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "inbetween/math/format.hpp"
#include "inbetween/math/quote.hpp"

namespace inbetween {
namespace {

// The object whose column `name` is ("<object>.translation.x" …): the longest object name that is
// followed by a channel suffix; npos when the column is a track's.
std::size_t object_of_column(const Scene& scene, const std::string& name) {
  const auto objects = scene.objects();
  std::size_t best = std::size_t(-1), best_len = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const std::string& o = objects[i].name;
    if (name.size() <= o.size() + 1 || name.compare(0, o.size(), o) != 0 || name[o.size()] != '.') continue;
    const std::string rest = name.substr(o.size() + 1);
    const bool channel = rest.rfind("translation.", 0) == 0 || rest.rfind("rotation.", 0) == 0 || rest.rfind("scale.", 0) == 0;
    if (channel && (best == std::size_t(-1) || o.size() > best_len)) {
      best = i;
      best_len = o.size();
    }
  }
  return best;
}

// The track whose column `name` is, npos when none.
std::size_t track_of_column(const Scene& scene, const std::string& name) {
  const auto tracks = scene.tracks();
  for (std::size_t k = 0; k < tracks.size(); ++k) {
    const std::string t = std::visit([](const auto& tr) { return tr.name; }, tracks[k]);
    if (name == t || (name.size() > t.size() && name.compare(0, t.size(), t) == 0 && name[t.size()] == '.')) return k;
  }
  return std::size_t(-1);
}

double largest(const Vec3d& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

}  // namespace

Error non_finite_value_error(const Scene& scene, double frame, std::size_t column, double value) {
  const std::string& name = scene.columns()[column].name;
  Error e{ErrorCode::not_finite,
          "frame " + shortest_text(frame) + ": " + name +
              (std::isnan(value) ? " is not a number"
                                 : " overflows (" + shortest_text(value) +
                                       (scene.columns()[column].single_precision ? ", single precision" : "") + ")")};
  const std::size_t object = object_of_column(scene, name);
  if (object == std::size_t(-1)) {
    const std::size_t track = track_of_column(scene, name);
    if (track != std::size_t(-1)) e.location = {std::string("tracks"), track};
    return e;
  }
  const auto objects = scene.objects();
  // The chain from the object up to its root: a member that is not finite itself, else the
  // largest translation or scale factor in the product.
  std::size_t cause = object;
  const char* member = nullptr;
  double biggest = -1;
  for (std::optional<std::size_t> j = object; j; j = objects[*j].parent) {
    const Transform<double> local = objects[*j].local.sample(frame);
    const std::pair<const char*, double> parts[] = {
        {"translation", largest(local.translation)}, {"scale", largest(local.scale)},
        {"rotation", std::isfinite(local.rotation.w + local.rotation.x + local.rotation.y + local.rotation.z) ? 0.0 : INFINITY}};
    for (const auto& [what, size] : parts) {
      const double s = std::isnan(size) ? INFINITY : size;
      if (s > biggest) {
        biggest = s;
        cause = *j;
        member = what;
      }
    }
  }
  const bool own_motion = !scene.path_legs(object).empty() || scene.camera(object) != nullptr;
  if (member == nullptr || (own_motion && std::isfinite(biggest) && biggest <= 1e150)) {
    e.location = {std::string("objects"), object};
    e.message += " (the object's own motion overflows)";
    return e;
  }
  e.location = {std::string("objects"), cause, std::string(member)};
  e.message += std::isfinite(biggest) ? " (its world transform overflows: " + quote_excerpt(objects[cause].name) + "'s " + member +
                                            " has a component of " + shortest_text(biggest) + ")"
                                      : " (" + quote_excerpt(objects[cause].name) + "'s " + member + " is not finite here)";
  return e;
}

}  // namespace inbetween
