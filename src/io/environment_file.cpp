// Environment files: JSON → EnvironmentFile with errors that name the JSON pointer.
#include "inbetween/io/environment_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <initializer_list>

#include "json_read.hpp"

namespace inbetween {
namespace {

using io_detail::json;
using io_detail::located;
using io_detail::read_number;
using io_detail::Reader;

// Longest member name quoted in an error place or message (a file's odd keys stay bounded).
constexpr std::size_t kMaxQuotedKey = 40;

// `base` + "/" + the member name, escaped as RFC 6901 asks ('~' → "~0", '/' → "~1") and cut to
// kMaxQuotedKey characters with "..." when longer.
std::string join(const std::string& base, std::string_view field) {
  std::string s(base);
  s.append("/");
  const std::size_t n = std::min(field.size(), kMaxQuotedKey);
  for (std::size_t i = 0; i < n; ++i) {
    if (field[i] == '~') s.append("~0");
    else if (field[i] == '/') s.append("~1");
    else s.push_back(field[i]);
  }
  if (field.size() > kMaxQuotedKey) s.append("...");
  return s;
}

// Rejects fields other than `known` (so a misspelt "raduis" is not silently ignored).
Expected<void> only_fields(const Reader& r, const json& obj, const std::string& pointer,
                           std::initializer_list<std::string_view> known) {
  for (const auto& item : obj.items())
    if (std::find(known.begin(), known.end(), item.key()) == known.end())
      return r.fail(join(pointer, item.key()), "unknown field");
  return {};
}

Expected<const json*> field(const Reader& r, const json& obj, const std::string& pointer, std::string_view name) {
  const auto it = obj.find(std::string(name));
  if (it == obj.end()) return r.fail(join(pointer, name), "missing required field");
  return &*it;
}

Expected<Vec3d> read_vec3(const Reader& r, const json& v, const std::string& pointer) {
  if (!v.is_array()) return r.fail(pointer, "expected an array of 3 numbers, got " + std::string(v.type_name()));
  if (v.size() != 3)
    return r.fail(pointer, "expected 3 numbers, got " + std::to_string(v.size()), ErrorCode::WrongArity);
  Vec3d out{};
  for (std::size_t c = 0; c < 3; ++c) {
    auto d = read_number(r, v[c], join(pointer, std::to_string(c)));
    if (!d) return d.error();
    out[int(c)] = *d;
  }
  return out;
}

Expected<Vec3d> read_vec3_field(const Reader& r, const json& obj, const std::string& pointer, std::string_view name) {
  auto f = field(r, obj, pointer, name);
  if (!f) return f.error();
  return read_vec3(r, **f, join(pointer, name));
}

Expected<double> read_number_field(const Reader& r, const json& obj, const std::string& pointer, std::string_view name) {
  auto f = field(r, obj, pointer, name);
  if (!f) return f.error();
  return read_number(r, **f, join(pointer, name));
}

Expected<RawObstacle> read_obstacle(const Reader& r, const json& o, const std::string& pointer) {
  if (!o.is_object() || o.size() != 1)
    return r.fail(pointer, "expected an object with one key: sphere, box, obb or moving_sphere");
  const std::string kind = o.begin().key();
  const json& v = o.begin().value();
  const std::string at = join(pointer, kind);
  if (!v.is_object()) return r.fail(at, "expected an object");
  if (kind == "sphere") {
    if (auto ok = only_fields(r, v, at, {"center", "radius"}); !ok) return ok.error();
    auto c = read_vec3_field(r, v, at, "center");
    if (!c) return c.error();
    auto rad = read_number_field(r, v, at, "radius");
    if (!rad) return rad.error();
    return RawObstacle{SphereObstacle{*c, *rad}};
  }
  if (kind == "box") {
    if (auto ok = only_fields(r, v, at, {"min", "max"}); !ok) return ok.error();
    auto lo = read_vec3_field(r, v, at, "min");
    if (!lo) return lo.error();
    auto hi = read_vec3_field(r, v, at, "max");
    if (!hi) return hi.error();
    return RawObstacle{BoxObstacle{*lo, *hi}};
  }
  if (kind == "obb") {
    if (auto ok = only_fields(r, v, at, {"center", "half_size", "rotation"}); !ok) return ok.error();
    auto c = read_vec3_field(r, v, at, "center");
    if (!c) return c.error();
    auto h = read_vec3_field(r, v, at, "half_size");
    if (!h) return h.error();
    Quatd q{};
    if (v.contains("rotation")) {
      const json& qa = v["rotation"];
      const std::string qp = join(at, "rotation");
      if (!qa.is_array() || qa.size() != 4)
        return r.fail(qp, "expected 4 numbers [w, x, y, z]", qa.is_array() ? ErrorCode::WrongArity : ErrorCode::Parse);
      double wxyz[4];
      for (std::size_t k = 0; k < 4; ++k) {
        auto d = read_number(r, qa[k], join(qp, std::to_string(k)));
        if (!d) return d.error();
        wxyz[k] = *d;
      }
      q = Quatd::from_wxyz(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    }
    return RawObstacle{OrientedBoxObstacle{*c, *h, q}};
  }
  if (kind == "moving_sphere") {
    if (auto ok = only_fields(r, v, at, {"center", "velocity", "radius", "t0"}); !ok) return ok.error();
    auto c = read_vec3_field(r, v, at, "center");
    if (!c) return c.error();
    auto vel = read_vec3_field(r, v, at, "velocity");
    if (!vel) return vel.error();
    auto rad = read_number_field(r, v, at, "radius");
    if (!rad) return rad.error();
    double t0 = 0;
    if (v.contains("t0")) {
      auto d = read_number(r, v["t0"], join(at, "t0"));
      if (!d) return d.error();
      t0 = *d;
    }
    return RawObstacle{MovingSphereObstacle{*c, *vel, *rad, t0}};
  }
  return r.fail(at, "unknown obstacle kind; expected sphere, box, obb or moving_sphere",
                ErrorCode::Unsupported);
}

}  // namespace

Expected<EnvironmentFile> parse_environment_json(std::string_view text, std::string_view source_name) {
  const Reader r{std::string(source_name)};
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    // nlohmann quotes the token it stopped in ("last read: '…'"), which can be the rest of the
    // file: keep the position and the description, cut the quote.
    constexpr std::size_t kMaxParseMessage = 200;
    std::string what = e.what();
    if (what.size() > kMaxParseMessage) what = what.substr(0, kMaxParseMessage) + "...";
    return Error{ErrorCode::Parse, "invalid JSON: " + what, r.source};
  }
  if (!doc.is_object()) return r.fail("", "expected a JSON object with \"inbetween_env\": 1");
  if (!doc.contains("inbetween_env")) return r.fail("/inbetween_env", "missing required field (the format version, 1)");
  {
    const json& v = doc["inbetween_env"];
    if (!v.is_number_integer() || v.get<long long>() != environment_format_version)
      return r.fail("/inbetween_env", "unsupported version " + (v.is_number() ? v.dump() : std::string(v.type_name())) +
                                          "; this reader knows version " +
                                          std::to_string(environment_format_version), ErrorCode::Unsupported);
  }
  if (auto ok = only_fields(r, doc, "", {"inbetween_env", "radius", "start", "goal", "via", "bounds", "obstacles",
                                         "speed", "fps", "cell_size", "margin"});
      !ok)
    return ok.error();
  EnvironmentFile out;
  auto radius = read_number_field(r, doc, "", "radius");
  if (!radius) return radius.error();
  out.environment.radius = *radius;
  auto bounds = field(r, doc, "", "bounds");
  if (!bounds) return bounds.error();
  if (!(*bounds)->is_object()) return r.fail("/bounds", "expected an object with min and max");
  if (auto ok = only_fields(r, **bounds, "/bounds", {"min", "max"}); !ok) return ok.error();
  auto lo = read_vec3_field(r, **bounds, "/bounds", "min");
  if (!lo) return lo.error();
  auto hi = read_vec3_field(r, **bounds, "/bounds", "max");
  if (!hi) return hi.error();
  out.environment.bounds_min = *lo;
  out.environment.bounds_max = *hi;
  auto start = read_vec3_field(r, doc, "", "start");
  if (!start) return start.error();
  auto goal = read_vec3_field(r, doc, "", "goal");
  if (!goal) return goal.error();
  out.ends.start = *start;
  out.ends.goal = *goal;
  if (doc.contains("via")) {
    const json& via = doc["via"];
    if (!via.is_array()) return r.fail("/via", "expected an array of points [x, y, z]");
    for (std::size_t i = 0; i < via.size(); ++i) {
      auto p = read_vec3(r, via[i], io_detail::ptr("via", i));
      if (!p) return p.error();
      out.ends.via.push_back(*p);
    }
  }
  auto obstacles = field(r, doc, "", "obstacles");
  if (!obstacles) return obstacles.error();
  if (!(*obstacles)->is_array()) return r.fail("/obstacles", "expected an array of obstacles");
  for (std::size_t i = 0; i < (*obstacles)->size(); ++i) {
    auto o = read_obstacle(r, (**obstacles)[i], io_detail::ptr("obstacles", i));
    if (!o) return o.error();
    out.environment.obstacles.push_back(*o);
  }
  for (const char* name : {"speed", "fps", "cell_size", "margin"}) {
    if (!doc.contains(name)) continue;
    auto d = read_number(r, doc[name], io_detail::ptr(name));
    if (!d) return d.error();
    const std::string n = name;
    (n == "speed" ? out.timing.speed : n == "fps" ? out.timing.fps : n == "cell_size" ? out.planner.cell_size
                                                                                     : out.planner.margin) = *d;
  }
  return out;
}

Error locate_environment_error(const Error& error, std::string_view source_name) {
  Error e = error;
  e.where = located(std::string(source_name), error.where.rfind('/', 0) == 0 ? error.where : std::string());
  return e;
}

}  // namespace inbetween
