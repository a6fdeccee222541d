// load_clip(): any file inbetween reads (read_input_file: scene file, glTF; BVH and assimp once
// their readers are in) built into a Scene and sampled in local or world space into one NumPy array
// of frames × objects × 10 (tx, ty, tz, qw, qx, qy, qz, sx, sy, sz), with the objects' names and
// parent indices.  The loop is Scene::sample with a SceneCursor, as `inbetween bake --space` runs it.
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common.hpp"
#include "inbetween/io/input.hpp"
#include "inbetween/scene/scene.hpp"

namespace inbetween::python {
namespace {

/// What load_clip() returns.
struct Clip {
  std::vector<std::string> names;  // every object of the scene, in file order
  py::array_t<std::int64_t> parents;
  py::array_t<double> frames;
  py::array_t<double> transforms;
  std::vector<std::string> skins_names;
  std::vector<std::vector<std::int64_t>> skins_joints;
  double fps = 24;
  std::string space;
};

std::string number_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

Clip load_clip(const py::object& path_like, const std::string& space_name, const std::optional<Array>& frames_in,
               const std::optional<double>& fps_in, const std::optional<std::string>& animation) {
  const std::string path = py::str(py::module_::import("os").attr("fspath")(path_like)).cast<std::string>();
  const std::optional<Space> space = enum_from_string<Space>(space_name);
  if (!space) throw py::value_error("space: \"" + space_name + "\" is neither \"local\" nor \"world\"");
  if (fps_in && (!(*fps_in > 0) || !std::isfinite(*fps_in))) throw py::value_error("fps: must be finite and > 0");
  InputOptions options;
  options.animation = animation.value_or("");
  options.fps = fps_in.value_or(0);
  if (animation && input_format(path) == InputFormat::scene_json) {
    throw py::value_error("animation: only for glTF and assimp input");
  }
  auto raw = read_input_file(path, options);
  if (!raw) {
    throw BindingError(raw.error(), path);
  }
  auto built = build_scene(*raw);
  if (!built) {
    throw BindingError(built.error(), path, "/");
  }
  const Scene& scene = *built;
  const auto objects = scene.objects();
  if (objects.empty()) {
    throw BindingError(Error{ErrorCode::unsupported, "no objects (joints) in the file, only tracks: use inbetween.bake"}, path);
  }

  std::vector<double> frames;
  if (frames_in) {
    if (frames_in->ndim() > 1) throw py::value_error("frames: expected a 1-D array of frames");
    frames.assign(frames_in->data(), frames_in->data() + frames_in->size());
  } else {
    const double a = scene.range_start(), b = scene.range_end();
    const double count = std::floor(b - a + 1e-9) + 1;
    if (!(count <= 1e9)) throw py::value_error("frames: the scene's range has " + number_text(count) + " frames, too many for an array");
    for (std::size_t i = 0; i < std::size_t(count); ++i) frames.push_back(a + double(i));
  }

  // The first output column of each object (its translation.x).
  const auto columns = scene.columns();
  std::vector<std::size_t> first(objects.size());
  for (std::size_t i = 0, c = 0; i < objects.size(); ++i) {
    const std::string name = objects[i].name + ".translation.x";
    while (c < columns.size() && columns[c].name != name) ++c;
    first[i] = c;
  }

  Clip clip;
  clip.space = std::string(enum_name(*space));
  clip.fps = fps_in.value_or(scene.fps());
  const std::size_t n = frames.size(), m = objects.size();
  clip.transforms = py::array_t<double>(std::vector<py::ssize_t>{py::ssize_t(n), py::ssize_t(m), 10});
  clip.frames = py::array_t<double>(py::ssize_t(n));
  std::copy(frames.begin(), frames.end(), clip.frames.mutable_data());
  clip.parents = py::array_t<std::int64_t>(py::ssize_t(m));
  for (std::size_t i = 0; i < m; ++i) {
    clip.names.push_back(objects[i].name);
    clip.parents.mutable_data()[i] = objects[i].parent ? std::int64_t(*objects[i].parent) : -1;
  }
  for (const SceneSkin& skin : scene.skins()) {
    clip.skins_names.push_back(skin.name);
    clip.skins_joints.emplace_back(skin.joints.begin(), skin.joints.end());
  }
  double* out = clip.transforms.mutable_data();
  std::string failure;
  {
    py::gil_scoped_release release;
    SceneCursor cursor(scene);
    std::vector<double> row(columns.size());
    for (std::size_t f = 0; f < n && failure.empty(); ++f) {
      scene.sample(frames[f], row, cursor, *space);
      for (std::size_t i = 0; i < m && failure.empty(); ++i) {
        for (std::size_t k = 0; k < 10; ++k) {
          const double v = row[first[i] + k];
          if (!std::isfinite(v)) {
            failure = "frame " + number_text(frames[f]) + ": " + columns[first[i] + k].name + " is not finite";
            break;
          }
          out[(f * m + i) * 10 + k] = v;
        }
      }
    }
  }
  if (!failure.empty()) throw BindingError(Error{ErrorCode::not_finite, failure}, path);
  return clip;
}

}  // namespace

void bind_clip(py::module_& m) {
  py::class_<Clip>(m, "Clip",
                   "A skeletal clip (any scene's objects) sampled at frames: names, parents and transforms "
                   "(frames x objects x 10: tx, ty, tz, qw, qx, qy, qz, sx, sy, sz) in `space`.")
      .def_readonly("names", &Clip::names, "Object (joint) names, in the file's order.")
      .def_readonly("parents", &Clip::parents, "Index of each object's parent in `names`, -1 for a root (int64 array).")
      .def_readonly("frames", &Clip::frames, "The frames sampled (1-D array).")
      .def_readonly("fps", &Clip::fps, "Frames per second: time = frame / fps.")
      .def_readonly("space", &Clip::space, "\"local\" (relative to the parent) or \"world\".")
      .def_readonly("transforms", &Clip::transforms,
                    "Array (len(frames), len(names), 10): translation x y z, rotation w x y z (unit, sign-continuous "
                    "from frame to frame), scale x y z -- the columns of `inbetween bake --space`.")
      .def_property_readonly("times", [](const Clip& c) {
             py::array_t<double> t(c.frames.size());
             for (py::ssize_t i = 0; i < c.frames.size(); ++i) t.mutable_data()[i] = c.frames.data()[i] / c.fps;
             return t;
           }, "frames / fps, in seconds.")
      .def_property_readonly("skins", [](const Clip& c) {
             py::list out;
             for (std::size_t k = 0; k < c.skins_names.size(); ++k) out.append(py::make_tuple(c.skins_names[k], c.skins_joints[k]));
             return out;
           }, "The file's skins as (name, [joint indices into names]) (glTF skins; a BVH's one skin).")
      .def("__repr__", [](const Clip& c) {
        return "<inbetween.Clip " + std::to_string(c.names.size()) + " objects, " + std::to_string(c.frames.size()) +
               " frames, " + c.space + " space>";
      });

  m.def("load_clip", &load_clip, py::arg("path"), py::arg("space") = "local", py::arg("frames") = py::none(),
        py::arg("fps") = py::none(), py::arg("animation") = py::none(),
        "Reads any file inbetween reads (scene file, glTF; BVH and assimp formats when their readers are built in) "
        "and samples every object at `frames` (default: the file's range, step 1) in `space` (\"local\": relative "
        "to the parent, the default; \"world\").  `fps`: frames per second of keys given in seconds (glTF, BVH: "
        "frame = time * fps; default the format's own); `animation`: glTF/assimp animation name or index.  "
        "Returns an inbetween.Clip.  inbetween.Error names the file and the place (JSON pointer, line, node).");
}

}  // namespace inbetween::python
