// The scene file (docs/scene-format.md): the document — "inbetween" (the version), "fps",
// "range" and the order of the parts — read into a RawScene and written from one.  Each concept
// (tracks, objects and skins, paths, cameras) is read and written in its own part, listed in
// src/io/scene_file.hpp.  The reader checks shape only (syntax, member types, unknown members,
// names of enumerations, the version); build_scene() does every other check.  Errors carry the
// JSON pointer as structured location steps; parse_scene() renders it once.
#include "inbetween/io/scene.hpp"
#include "inbetween/io/scene_write.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene_file.hpp"

namespace inbetween {

namespace {

using namespace io_detail;

// ------------------------------------------------------------------ reading
Expected<RawScene> read_scene(const json& root, Context cx) {
  const Loc doc;
  if (!root.is_object()) return error_at(ErrorCode::invalid_argument, "a scene must be a JSON object", doc);
  if (auto ok = only_members(root, doc, {"inbetween", "fps", "range", "tracks", "paths", "objects", "skins", "actions"}); !ok) return ok.error();
  RawScene scene;
  auto version = root.find("inbetween");
  if (version == root.end()) {
    return error_at(ErrorCode::invalid_argument, "missing \"inbetween\": 1 (the format version)", {"inbetween"});
  }
  if (!version->is_number_integer() || version->get<long long>() < scene_format_version_min ||
      version->get<long long>() > scene_format_version_max) {
    return error_at(ErrorCode::unsupported,
                    "unsupported format version " + io_detail::short_dump(*version) + " (this reader knows 1, 2 and 3)",
                    {"inbetween"});
  }
  cx.version = int(version->get<long long>());
  for (std::string_view member : {"paths", "skins"}) {
    if (auto ok = needs_version_2(root, doc, cx, member); !ok) return ok.error();
  }
  auto fps = number_member(root, doc, "fps", 24.0);
  if (!fps) return fps.error();
  scene.fps = *fps;
  if (auto r = root.find("range"); r != root.end()) {
    if (!r->is_array() || r->size() != 2) {
      return error_at(ErrorCode::wrong_arity, "\"range\" must be [first_frame, last_frame]", {"range"});
    }
    for (std::size_t i = 0; i < 2; ++i) {
      auto v = get_number((*r)[i], {"range", i});
      if (!v) return v.error();
      scene.range[i] = *v;
    }
  }
  if (auto t = root.find("tracks"); t != root.end()) {
    if (!t->is_array()) return error_at(ErrorCode::invalid_argument, "\"tracks\" must be an array", {"tracks"});
    for (std::size_t i = 0; i < t->size(); ++i) {
      auto track = read_track((*t)[i], {"tracks", i});
      if (!track) return track.error();
      scene.tracks.push_back(std::move(*track));
    }
  }
  if (auto ok = read_paths(root, cx, scene); !ok) return ok.error();
  if (auto ok = read_actions(root, cx, scene); !ok) return ok.error();
  if (auto o = root.find("objects"); o != root.end()) {
    if (!o->is_array()) return error_at(ErrorCode::invalid_argument, "\"objects\" must be an array", {"objects"});
    for (std::size_t i = 0; i < o->size(); ++i) {
      auto object = read_object((*o)[i], {"objects", i}, cx);
      if (!object) return object.error();
      scene.objects.push_back(std::move(*object));
    }
  }
  if (auto ok = read_skins(root, scene); !ok) return ok.error();
  return scene;
}

// ------------------------------------------------------------------ writing
// Indented JSON in which every array or object that fits in kOneLine characters stays on one line
// (a key, a vector, a constant channel), so a scene with thousands of keys reads as one key a line.
constexpr std::size_t kOneLine = 100;

std::string scalar_text(const ojson& j) { return j.dump(-1, ' ', false, ojson::error_handler_t::replace); }

// One line with a space after each ':' and ',': {"frame": 0, "value": [1, 2, 3]}.
std::string one_line(const ojson& j) {
  if (!j.is_structured()) return scalar_text(j);
  std::string out = j.is_object() ? "{" : "[";
  bool first = true;
  for (auto it = j.begin(); it != j.end(); ++it) {
    out += first ? "" : ", ";
    first = false;
    if (j.is_object()) out += scalar_text(ojson(it.key())) + ": ";
    out += one_line(it.value());
  }
  return out + (j.is_object() ? "}" : "]");
}

void pretty(const ojson& j, int indent, int depth, std::string& out) {
  std::string flat = one_line(j);
  if (!j.is_structured() || j.empty() || flat.size() <= kOneLine) {
    out += flat;
    return;
  }
  const std::string pad(std::size_t(indent * (depth + 1)), ' '), end_pad(std::size_t(indent * depth), ' ');
  out += j.is_object() ? "{\n" : "[\n";
  bool first = true;
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      out += first ? "" : ",\n";
      first = false;
      out += pad + scalar_text(ojson(it.key())) + ": ";
      pretty(it.value(), indent, depth + 1, out);
    }
  } else {
    for (const ojson& item : j) {
      out += first ? "" : ",\n";
      first = false;
      out += pad;
      pretty(item, indent, depth + 1, out);
    }
  }
  out += "\n" + end_pad + (j.is_object() ? "}" : "]");
}

}  // namespace

Expected<RawScene> read_scene_json(std::string_view json_text, std::string_view source_path) {
  io_detail::JsonText parsed = io_detail::parse_json_text(json_text);
  const std::vector<LocationStep> place{TextLine{std::size_t(parsed.line), std::size_t(parsed.column)}};
  switch (parsed.failure) {
    case io_detail::JsonFailure::none:
      return read_scene(parsed.value, Context{1, source_path.empty() || source_path == "-"
                                                    ? std::filesystem::path()
                                                    : std::filesystem::path(source_path).parent_path()});
    case io_detail::JsonFailure::syntax:
      return Error{ErrorCode::parse, "not valid JSON", place};
    case io_detail::JsonFailure::number_out_of_range:
      return Error{ErrorCode::parse, "the number " + parsed.detail + " is beyond double precision's range", place};
    case io_detail::JsonFailure::too_deep:
      return Error{ErrorCode::parse, "JSON " + parsed.detail + " (not accepted)", place};
  }
  return Error{ErrorCode::parse, "not valid JSON", place};
}

Expected<Scene> parse_scene(std::string_view json_text, std::string_view source_path) {
  auto raw = read_scene_json(json_text, source_path);
  Expected<Scene> scene = raw ? build_scene(*raw) : Expected<Scene>(raw.error());
  if (scene) return scene;
  return scene.error();  // an empty location is the whole document
}

Expected<std::string> write_scene_json(const RawScene& scene, const SceneWriteOptions& options) {
  io_detail::SceneWriter w;
  ojson root = ojson::object();
  const bool version_3 = !scene.actions.empty() ||
                         std::any_of(scene.objects.begin(), scene.objects.end(), [](const RawObject& o) { return o.blender; });
  root["inbetween"] = version_3 ? 3 : 2;
  root["fps"] = w.number(scene.fps, {"fps"});
  root["range"] = w.numbers({scene.range[0], scene.range[1]}, {"range"});
  if (!scene.paths.empty()) {
    ojson paths = ojson::array();
    for (const RawScenePath& p : scene.paths) paths.push_back(w.path(p));
    root["paths"] = std::move(paths);
  }
  if (!scene.actions.empty()) {
    ojson actions = ojson::array();
    for (std::size_t i = 0; i < scene.actions.size(); ++i) actions.push_back(w.action(scene.actions[i], {"actions", i}));
    root["actions"] = std::move(actions);
  }
  if (!scene.tracks.empty()) {
    ojson tracks = ojson::array();
    for (std::size_t i = 0; i < scene.tracks.size(); ++i)
      tracks.push_back(std::visit([&](const auto& t) { return w.track(t, {"tracks", i}); }, scene.tracks[i]));
    root["tracks"] = std::move(tracks);
  }
  if (!scene.objects.empty()) {
    ojson objects = ojson::array();
    for (std::size_t i = 0; i < scene.objects.size(); ++i) objects.push_back(w.object(scene.objects[i], {"objects", i}));
    root["objects"] = std::move(objects);
  }
  if (!scene.skins.empty()) {
    ojson skins = ojson::array();
    for (const RawSkin& skin : scene.skins) skins.push_back(w.skin(skin));
    root["skins"] = std::move(skins);
  }
  if (w.failure) return *w.failure;
  // Names are arbitrary bytes in a RawScene: invalid UTF-8 is replaced rather than thrown on.
  if (options.indent < 0) return root.dump(-1, ' ', false, ojson::error_handler_t::replace) + "\n";
  std::string out;
  pretty(root, options.indent, 0, out);
  return out + "\n";
}

}  // namespace inbetween
