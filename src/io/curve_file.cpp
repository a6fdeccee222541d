// Curve files: JSON → AnyCurve with errors that name the JSON pointer, and AnyCurve → JSON.
#include "inbetween/io/curve_file.hpp"

#include <nlohmann/json.hpp>

#include "curve_value.hpp"
#include "json_text.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace inbetween {
namespace {

using json = nlohmann::json;

// "file:/points/3", or just "file" for the document root (whose JSON pointer is empty).
std::string located(const std::string& source, const std::string& pointer) {
  return pointer.empty() ? source : source + ":" + pointer;
}

using Loc = std::vector<LocationStep>;

struct Reader {
  // The error at `loc`, structured (relative to the curve object); parse_curve_json() renders it
  // once with json_pointer(), a scene file prepends the curve's own place.
  Error fail(const Loc& loc, std::string message, ErrorCode code = ErrorCode::Parse) const {
    return Error{code, std::move(message), "", loc};
  }
};

Loc ptr(std::string_view field) { return Loc{std::string(field)}; }
Loc ptr(std::string_view field, std::size_t i) { return Loc{std::string(field), i}; }
Loc at(Loc loc, std::size_t i) {
  loc.emplace_back(i);
  return loc;
}

// Reads a number; an error names the pointer.
Expected<double> read_number(const Reader& r, const json& v, const Loc& pointer) {
  if (!v.is_number()) return r.fail(pointer, "expected a number, got " + std::string(v.type_name()));
  const double d = v.get<double>();
  if (!std::isfinite(d)) return r.fail(pointer, "number is not finite", ErrorCode::NotFinite);
  return d;
}

// Reads one point: a number or an array of 1 to 3 numbers, of dimension `dim` (fixed by this point when 0).
Expected<Vec3d> read_point(const Reader& r, const json& p, const Loc& where, int& dim) {
  std::vector<double> comps;
  if (p.is_number()) {
    auto d = read_number(r, p, where);
    if (!d) return d.error();
    comps.push_back(*d);
  } else if (p.is_array()) {
    for (std::size_t c = 0; c < p.size(); ++c) {
      auto d = read_number(r, p[c], at(where, c));
      if (!d) return d.error();
      comps.push_back(*d);
    }
  } else {
    return r.fail(where, "expected a point: a number or an array of 1 to 3 numbers");
  }
  if (comps.empty() || comps.size() > 3)
    return r.fail(where, "expected 1 to 3 numbers, got " + std::to_string(comps.size()), ErrorCode::WrongArity);
  if (dim == 0) dim = int(comps.size());
  if (int(comps.size()) != dim)
    return r.fail(where, "expected " + std::to_string(dim) + " number" + (dim == 1 ? "" : "s") +
                             " (the dimension of the first point), got " + std::to_string(comps.size()),
                  ErrorCode::WrongArity);
  Vec3d v{};
  for (int c = 0; c < dim; ++c) v[c] = comps[c];
  return v;
}

// Reads an array of points, all of the same dimension (`dim` fixed by the first point when 0).
Expected<std::vector<Vec3d>> read_points(const Reader& r, const json& doc, std::string_view field, int& dim,
                                         bool required = true) {
  std::vector<Vec3d> out;
  if (!doc.contains(field)) {
    if (required) return r.fail(ptr(field), "missing required field", ErrorCode::Parse);
    return out;
  }
  const json& arr = doc.at(std::string(field));
  if (!arr.is_array()) return r.fail(ptr(field), "expected an array of points");
  for (std::size_t i = 0; i < arr.size(); ++i) {
    auto v = read_point(r, arr[i], ptr(field, i), dim);
    if (!v) return v.error();
    out.push_back(*v);
  }
  return out;
}

Expected<std::vector<double>> read_numbers(const Reader& r, const json& doc, std::string_view field) {
  std::vector<double> out;
  const json& arr = doc.at(std::string(field));
  if (!arr.is_array()) return r.fail(ptr(field), "expected an array of numbers");
  for (std::size_t i = 0; i < arr.size(); ++i) {
    auto d = read_number(r, arr[i], ptr(field, i));
    if (!d) return d.error();
    out.push_back(*d);
  }
  return out;
}

Expected<std::optional<double>> read_optional_number(const Reader& r, const json& doc, std::string_view field) {
  if (!doc.contains(field)) return std::optional<double>{};
  auto d = read_number(r, doc.at(std::string(field)), ptr(field));
  if (!d) return d.error();
  return std::optional<double>{*d};
}

// A builder's error location names the builder's inputs by the curve file's member names
// ({"points", 3}, {"knots"}, {"alpha"}), so it is the JSON pointer of the offending value as it is.
Error relocate(const Reader&, const Error& e) { return e; }

template <class C>
Expected<AnyCurve> wrap(const Reader& r, CurveKind kind, int dim, Expected<C> built) {
  if (!built) return relocate(r, built.error());
  return AnyCurve{kind, dim, AnyCurveVariant{std::move(built).value()}};
}

// Kochanek–Bartels parameters: a number (shared) or an array with one number per point.
Expected<std::vector<double>> read_tcb(const Reader& r, const json& doc, std::string_view field, std::size_t n) {
  if (!doc.contains(field)) return std::vector<double>{0.0};
  const json& v = doc.at(std::string(field));
  if (v.is_number()) {
    auto d = read_number(r, v, ptr(field));
    if (!d) return d.error();
    return std::vector<double>{*d};
  }
  auto arr = read_numbers(r, doc, field);
  if (!arr) return arr.error();
  if (arr->size() != n)
    return r.fail(ptr(field), "expected a number or an array of " + std::to_string(n) + " numbers (one per point), got " +
                                  std::to_string(arr->size()),
                  ErrorCode::WrongArity);
  return arr;
}

}  // namespace

Expected<AnyCurve> parse_curve_json(std::string_view text, std::string_view source_name) {
  const std::string source(source_name);
  io_detail::JsonText parsed = io_detail::parse_json_text(text);
  switch (parsed.failure) {
    case io_detail::JsonFailure::none:
      break;
    case io_detail::JsonFailure::syntax:
      return Error{ErrorCode::Parse, "invalid JSON: " + parsed.detail, source};
    case io_detail::JsonFailure::number_out_of_range:
      return Error{ErrorCode::Parse,
                   "invalid JSON: the number " + parsed.detail + " at line " + std::to_string(parsed.line) + ", column " +
                       std::to_string(parsed.column) + " is beyond double precision's range",
                   source};
    case io_detail::JsonFailure::too_deep:
      return Error{ErrorCode::Parse,
                   "invalid JSON: " + parsed.detail + " at line " + std::to_string(parsed.line) + ", column " +
                       std::to_string(parsed.column),
                   source};
  }
  auto curve = io_detail::read_curve_value(parsed.value);
  if (curve) return curve;
  // The structured place rendered once: "path.json:/points/3".
  Error e = curve.error();
  e.where = located(source, json_pointer(e.location));
  e.location.clear();
  return e;
}

Expected<AnyCurve> io_detail::read_curve_value(const nlohmann::json& value) {
  const Reader r{};
  const json& doc = value;
  if (!doc.is_object()) return r.fail({}, "expected a JSON object with a \"type\" field");
  if (doc.contains("version")) {
    const json& v = doc["version"];
    if (!v.is_number_integer() || v.get<long long>() != curve_format_version)
      return r.fail(ptr("version"), "unsupported version " + io_detail::short_dump(v) + "; this reader knows version " +
                                    std::to_string(curve_format_version), ErrorCode::Unsupported);
  }
  if (!doc.contains("type") || !doc["type"].is_string()) return r.fail(ptr("type"), "missing or not a string");
  const std::string type = doc["type"].get<std::string>();
  const std::optional<CurveKind> kind = enum_from_string<CurveKind>(type);  // nullopt: refused below
  // Unknown fields are rejected, so a misspelt option ("tensoin") is not silently ignored.
  static const std::vector<std::pair<CurveKind, std::vector<std::string>>> fields = {
      {CurveKind::bezier, {}},
      {CurveKind::bezier_path, {}},
      {CurveKind::hermite, {"tangents", "params"}},
      {CurveKind::catmull_rom, {"alpha", "tension", "closed"}},
      {CurveKind::natural, {"start_tangent", "end_tangent", "params", "closed"}},
      {CurveKind::kochanek_bartels, {"tension", "continuity", "bias", "params"}},
      {CurveKind::parabolic, {"params"}},
      {CurveKind::bspline, {"degree", "knots", "periodic"}},
      {CurveKind::lagrange, {"params"}},
  };
  for (const auto& [k, extra] : fields) {
    if (k != kind) continue;
    for (const auto& item : doc.items()) {
      const std::string& key = item.key();
      if (key == "version" || key == "type" || key == "points") continue;
      if (std::find(extra.begin(), extra.end(), key) == extra.end())
        return r.fail(ptr(io_detail::truncated(key)), "unknown field for type \"" + type + "\"", ErrorCode::Parse);
    }
  }

  int dim = 0;
  auto points = read_points(r, doc, "points", dim);
  if (!points) return points.error();
  if (points->empty()) return r.fail(ptr("points"), "expected at least one point", ErrorCode::TooFewPoints);
  const std::vector<Vec3d>& pts = *points;

  // The optional "params" member (parameters t_i of the points) of the interpolating splines.
  std::vector<double> params;
  if (doc.contains("params") && kind != CurveKind::lagrange) {
    auto k = read_numbers(r, doc, "params");
    if (!k) return k.error();
    params = *k;
    if (params.empty()) return r.fail(ptr("params"), "expected params, got an empty array", ErrorCode::WrongArity);
  }

  if (kind == CurveKind::bezier) return wrap(r, CurveKind::bezier, dim, build_bezier(pts));
  if (kind == CurveKind::bezier_path) return wrap(r, CurveKind::bezier_path, dim, build_bezier_path(pts));
  if (kind == CurveKind::parabolic) return wrap(r, CurveKind::parabolic, dim, build_parabolic_blend(pts, params));
  if (kind == CurveKind::hermite) {
    auto tangents = read_points(r, doc, "tangents", dim);
    if (!tangents) return tangents.error();
    return wrap(r, CurveKind::hermite, dim, build_hermite_spline(pts, *tangents, params));
  }
  if (kind == CurveKind::catmull_rom) {
    CatmullRomOptions<double> o;
    for (const char* f : {"alpha", "tension"}) {
      auto v = read_optional_number(r, doc, f);
      if (!v) return v.error();
      if (v->has_value()) (std::string(f) == "alpha" ? o.alpha : o.tension) = **v;
    }
    if (doc.contains("closed")) {
      if (!doc["closed"].is_boolean()) return r.fail(ptr("closed"), "expected true or false");
      o.closed = doc["closed"].get<bool>();
    }
    return wrap(r, CurveKind::catmull_rom, dim, build_catmull_rom(pts, o));
  }
  if (kind == CurveKind::natural) {
    const bool has_start = doc.contains("start_tangent"), has_end = doc.contains("end_tangent");
    if (has_start != has_end)
      return r.fail(ptr(has_start ? "end_tangent" : "start_tangent"),
                    "a clamped spline needs both start_tangent and end_tangent");
    bool closed = false;
    if (doc.contains("closed")) {
      if (!doc["closed"].is_boolean()) return r.fail(ptr("closed"), "expected true or false");
      closed = doc["closed"].get<bool>();
    }
    if (closed) {
      if (has_start) return r.fail(ptr("start_tangent"), "a closed spline takes no end tangents");
      return wrap(r, CurveKind::natural, dim, build_closed_spline(pts, params));
    }
    if (!has_start) return wrap(r, CurveKind::natural, dim, build_natural_spline(pts, params));
    auto start = read_point(r, doc["start_tangent"], ptr("start_tangent"), dim);
    if (!start) return start.error();
    auto end = read_point(r, doc["end_tangent"], ptr("end_tangent"), dim);
    if (!end) return end.error();
    return wrap(r, CurveKind::natural, dim, build_clamped_spline(pts, *start, *end, params));
  }
  if (kind == CurveKind::kochanek_bartels) {
    auto tension = read_tcb(r, doc, "tension", pts.size());
    if (!tension) return tension.error();
    auto continuity = read_tcb(r, doc, "continuity", pts.size());
    if (!continuity) return continuity.error();
    auto bias = read_tcb(r, doc, "bias", pts.size());
    if (!bias) return bias.error();
    const std::size_t n = std::max({tension->size(), continuity->size(), bias->size()});
    std::vector<TcbParams<double>> keys(n);
    for (std::size_t i = 0; i < n; ++i) {
      keys[i].tension = (*tension)[tension->size() == 1 ? 0 : i];
      keys[i].continuity = (*continuity)[continuity->size() == 1 ? 0 : i];
      keys[i].bias = (*bias)[bias->size() == 1 ? 0 : i];
    }
    return wrap(r, CurveKind::kochanek_bartels, dim, build_kochanek_bartels(pts, keys, params));
  }
  if (kind == CurveKind::bspline) {
    if (!doc.contains("degree") || !doc["degree"].is_number_integer())
      return r.fail(ptr("degree"), "expected an integer degree");
    const long long degree = doc["degree"].get<long long>();
    if (degree < 1 || degree > BSpline<Vec3d>::max_degree)
      return r.fail(ptr("degree"), "degree must be between 1 and " + std::to_string(BSpline<Vec3d>::max_degree) +
                                   ", got " + std::to_string(degree), ErrorCode::InvalidArgument);
    bool periodic = false;
    if (doc.contains("periodic")) {
      if (!doc["periodic"].is_boolean()) return r.fail(ptr("periodic"), "expected true or false");
      periodic = doc["periodic"].get<bool>();
    }
    if (periodic) {
      if (doc.contains("knots")) return r.fail(ptr("knots"), "a periodic bspline takes no knots (they are uniform)");
      return wrap(r, CurveKind::bspline, dim, build_periodic_bspline(pts, int(degree)));
    }
    std::vector<double> knots;
    if (doc.contains("knots")) {
      auto k = read_numbers(r, doc, "knots");
      if (!k) return k.error();
      knots = *k;
      if (knots.empty()) return r.fail(ptr("knots"), "expected knots, got an empty array", ErrorCode::WrongArity);
    }
    return wrap(r, CurveKind::bspline, dim, build_bspline(pts, int(degree), knots));
  }
  if (kind == CurveKind::lagrange) {
    // The "params" read above skips lagrange (here an empty array means the default 0, 1, …), so
    // `params` is still empty: fill it from the member.
    if (doc.contains("params")) {
      auto k = read_numbers(r, doc, "params");
      if (!k) return k.error();
      params = *k;
    }
    return wrap(r, CurveKind::lagrange, dim, build_lagrange(pts, params));
  }
  std::string expected;
  for (const std::string_view name : enum_names<CurveKind>()) (expected += expected.empty() ? "" : ", ") += name;
  return r.fail(ptr("type"), "unknown curve type \"" + io_detail::truncated(type) + "\"; expected one of " + expected,
                ErrorCode::Unsupported);
}

namespace {

json point_json(const Vec3d& p, int dim) {
  if (dim == 1) return p.x;
  json a = json::array();
  for (int c = 0; c < dim; ++c) a.push_back(p[c]);
  return a;
}

json points_json(std::span<const Vec3d> pts, int dim) {
  json a = json::array();
  for (const auto& p : pts) a.push_back(point_json(p, dim));
  return a;
}

}  // namespace

std::string write_curve_json(const AnyCurve& any) {
  json doc;
  doc["version"] = curve_format_version;
  doc["type"] = std::string(curve_kind_name(any.kind));
  const int dim = any.dimension;
  std::visit(
      [&](const auto& c) {
        using C = std::decay_t<decltype(c)>;
        doc["points"] = points_json(c.control_points(), dim);
        // Non-default parameters t_i of the interpolating splines (default 0, 1, …).
        if constexpr (std::is_same_v<C, HermiteSpline<Vec3d>> || std::is_same_v<C, CubicSpline<Vec3d>> ||
                      std::is_same_v<C, KochanekBartelsSpline<Vec3d>> ||
                      std::is_same_v<C, ParabolicBlendSpline<Vec3d>>) {
          const auto t = c.breakpoints();
          bool uniform = true;
          for (std::size_t i = 0; i < t.size(); ++i) uniform = uniform && t[i] == double(i);
          if (!uniform) doc["params"] = std::vector<double>(t.begin(), t.end());
        }
        if constexpr (std::is_same_v<C, HermiteSpline<Vec3d>>) {
          doc["tangents"] = points_json(c.tangents(), dim);
        } else if constexpr (std::is_same_v<C, CatmullRomSpline<Vec3d>>) {
          doc["alpha"] = c.options().alpha;
          doc["tension"] = c.options().tension;
          doc["closed"] = c.options().closed;
        } else if constexpr (std::is_same_v<C, CubicSpline<Vec3d>>) {
          if (c.closed()) doc["closed"] = true;
          if (c.end_condition() == CubicSplineEnd::clamped) {
            doc["start_tangent"] = point_json(c.tangents().front(), dim);
            doc["end_tangent"] = point_json(c.tangents().back(), dim);
          }
        } else if constexpr (std::is_same_v<C, KochanekBartelsSpline<Vec3d>>) {
          json t = json::array(), co = json::array(), b = json::array();
          for (const auto& k : c.keys()) t.push_back(k.tension), co.push_back(k.continuity), b.push_back(k.bias);
          const bool shared = c.keys().size() == 1;
          doc["tension"] = shared ? t[0] : t;
          doc["continuity"] = shared ? co[0] : co;
          doc["bias"] = shared ? b[0] : b;
        } else if constexpr (std::is_same_v<C, BSpline<Vec3d>>) {
          doc["degree"] = c.degree();
          doc["knots"] = std::vector<double>(c.knots().begin(), c.knots().end());
        } else if constexpr (std::is_same_v<C, LagrangeCurve<Vec3d>>) {
          doc["params"] = std::vector<double>(c.params().begin(), c.params().end());
        }
      },
      any.curve);
  return doc.dump(2) + "\n";
}

}  // namespace inbetween
