// Scenes and glTF: a scene file (path, dictionary or JSON text) or a glTF file read and built
// once; bake() evaluates every column at every frame into a NumPy array (the loop in C++, the
// same numbers as `inbetween bake`); convert() is `inbetween convert`.
#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "common.hpp"
#include "inbetween/io/gltf.hpp"
#include "inbetween/io/gltf_write.hpp"
#include "inbetween/io/read_file.hpp"
#include "inbetween/io/scene.hpp"
#include "inbetween/io/scene_write.hpp"
#include "inbetween/math/format.hpp"

namespace inbetween::python {
namespace {

/// A read and built scene; `raw` is kept for convert().
struct PyScene {
  std::shared_ptr<const RawScene> raw;
  std::shared_ptr<const Scene> scene;
  std::string source;  // the file name, or "scene" for a dictionary or text
  double fps = 24;     // of the time column: the scene's, or the glTF reading rate
};

bool is_gltf_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".gltf" || ext == ".glb") return true;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;  // a FIFO would block the open
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  return bool(in.read(magic, 4)) && std::string(magic, 4) == "glTF";
}

std::string read_file(const std::string& path) {
  auto text = read_file_bytes(path);
  if (!text) throw BindingError(text.error());
  return std::move(*text);
}

/// Reads a scene from a path (scene file or glTF), a dict, or JSON text (a str starting with '{').
PyScene load(const py::object& source, const std::string& animation, double fps) {
  PyScene out;
  RawScene raw;
  bool text = py::isinstance<py::dict>(source);
  std::string path;
  if (!text) {
    if (py::isinstance<py::str>(source)) {
      const std::string s = source.cast<std::string>();
      const auto first = s.find_first_not_of(" \t\r\n");
      text = first != std::string::npos && s[first] == '{';
    }
    if (!text) path = py::str(py::module_::import("os").attr("fspath")(source)).cast<std::string>();
  }
  if (!path.empty() && is_gltf_path(path)) {
    if (!(fps > 0) || !std::isfinite(fps)) throw py::value_error("fps: must be finite and > 0 for glTF input");
    GltfReadOptions options;
    options.animation = animation;
    options.fps = fps;
    auto r = read_gltf_file(path, options);
    if (!r) {
      throw BindingError(r.error(), path);
    }
    raw = std::move(*r);
    out.source = path;
  } else {
    if (!animation.empty()) throw py::value_error("animation: only for glTF input (.gltf, .glb)");
    std::string json = text ? json_text(source) : read_file(path);
    out.source = text ? "scene" : path;
    auto r = read_scene_json(json, path);  // curve files relative to the scene's folder
    if (!r) {
      throw BindingError(r.error(), out.source, "/");
    }
    raw = std::move(*r);
  }
  auto built = build_scene(raw);
  if (!built) throw BindingError(built.error(), out.source);
  out.raw = std::make_shared<const RawScene>(std::move(raw));
  out.scene = std::make_shared<const Scene>(std::move(*built));
  out.fps = fps > 0 && !path.empty() && is_gltf_path(path) ? fps : out.scene->fps();
  return out;
}

std::string number_text(double v) {
  std::ostringstream ss;
  ss.precision(17);
  ss << v;
  return ss.str();
}

/// The frames of `inbetween bake --frames A:B:STEP` (default: the scene's range, step 1).
std::vector<double> frame_range(double a, double b, double step) {
  if (!(step > 0) || !std::isfinite(step)) throw py::value_error("step: must be finite and > 0");
  if (!std::isfinite(a) || !std::isfinite(b) || b < a) throw py::value_error("frames: end is before start or not finite");
  const double count_d = std::floor((b - a) / step * (1 + 1e-12) + 1e-9) + 1;
  if (!(count_d <= 1e9)) throw py::value_error("frames: " + number_text(count_d) + " frames is too many for an array");
  std::vector<double> f(static_cast<std::size_t>(count_d));
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = a + double(i) * step;
  return f;
}

py::tuple bake(const PyScene& s, const std::optional<Array>& frames_in, double step) {
  const Scene& scene = *s.scene;
  std::vector<double> frames;
  if (frames_in) {
    if (frames_in->ndim() > 1) {
      throw py::value_error("frames: expected a 1-D array of frames (one row each), got " + std::to_string(frames_in->ndim()) +
                            " dimensions");
    }
    frames.assign(frames_in->data(), frames_in->data() + frames_in->size());
  } else {
    frames = frame_range(scene.range_start(), scene.range_end(), step);
  }
  const auto columns = scene.columns();
  const std::size_t nc = columns.size() + 2, n = frames.size();
  Array out(std::vector<py::ssize_t>{py::ssize_t(n), py::ssize_t(nc)});
  double* o = out.mutable_data();
  std::string failure;
  {
    py::gil_scoped_release release;
    SceneCursor cursor(scene);
    std::vector<double> row(columns.size());
    for (std::size_t i = 0; i < n && failure.empty(); ++i) {
      const double f = frames[i];
      double* r = o + i * nc;
      r[0] = f;
      r[1] = f / s.fps;
      if (!std::isfinite(r[1])) {
        failure = "frame " + number_text(f) + ": time = frame / fps " + number_text(s.fps) + " overflows";
        break;
      }
      scene.sample(f, row, cursor);
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const double v = columns[c].single_precision ? double(float(row[c])) : row[c];
        if (!std::isfinite(v)) {
          failure = "frame " + number_text(f) + ": " + columns[c].name + (std::isnan(v) ? " is not a number" : " overflows");
          break;
        }
        r[c + 2] = v;
      }
    }
  }
  if (!failure.empty()) throw BindingError(Error{ErrorCode::not_finite, failure}, s.source);
  std::vector<std::string> names{"frame", "time"};
  for (const auto& c : columns) names.push_back(c.name);
  return py::make_tuple(out, names);
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<PyScene>(m, "Scene", "A scene read and built once: a scene file (docs/scene-format.md, versions 1 and 2) given "
                                  "as a path, a dictionary or JSON text, or a glTF 2.0 file (.gltf, .glb; docs/gltf.md).")
      .def(py::init(&load), py::arg("source"), py::arg("animation") = "", py::arg("fps") = 24.0,
           "Reads and builds.  glTF: `animation` (name or index; default the first) at `fps` (frame = time * fps).  "
           "inbetween.Error with the file name and the JSON pointer, as `inbetween bake` prints them.")
      .def_property_readonly("fps", [](const PyScene& s) { return s.fps; }, "Frames per second of the time column.")
      .def_property_readonly("range", [](const PyScene& s) { return py::make_tuple(s.scene->range_start(), s.scene->range_end()); },
                             "(first, last): the default bake range in frames.")
      .def_property_readonly("columns", [](const PyScene& s) {
             std::vector<std::string> names{"frame", "time"};
             for (const auto& c : s.scene->columns()) names.push_back(c.name);
             return names;
           }, "Column names of bake(): frame, time, then the scene's columns (the CSV header of `inbetween bake`).")
      .def("bake", &bake, py::arg("frames") = py::none(), py::arg("step") = 1.0,
           "(values, columns): values is an (n, len(columns)) array with one row per frame -- `frames` (array), or "
           "the scene's range at `step` -- the same numbers as `inbetween bake` (F-curve columns in single precision, "
           "rotations sign-continuous from row to row).  inbetween.Error naming the frame and column where a value "
           "is not finite.")
      .def("to_json", [](const PyScene& s) { return take(write_scene_json(*s.raw), s.source); },
           "The scene as a scene file (JSON text; for glTF input: the converted scene).");

  m.def("convert", [](const py::object& input, const std::string& output, const std::string& animation, double fps,
                      double tolerance, double reduce, int substeps, bool cubic) {
    // reduce: 0 keeps exact keys, > 0 is a tolerance; NaN or < 0 is refused as the CLI's --reduce is.
    if (!(reduce >= 0) || !std::isfinite(reduce)) {
      throw BindingError(Error{ErrorCode::invalid_argument, "reduce must be 0 (keep exact keys) or finite and > 0, got " +
                                                               shortest_text(reduce), {"reduce"}});
    }
    const PyScene s = load(input, animation, fps);
    const auto ends = [&](const char* ext) {
      const std::string e(ext);
      return output.size() >= e.size() && output.compare(output.size() - e.size(), e.size(), e) == 0;
    };
    std::string bytes;
    py::list report;
    if (ends(".json")) {
      bytes = take(write_scene_json(*s.raw), s.source);
    } else if (ends(".glb") || ends(".gltf")) {
      GltfExportOptions o;
      o.tolerance = reduce > 0 ? reduce : tolerance;
      o.reduce = reduce > 0;
      o.substeps = substeps;
      o.binary = ends(".glb");
      o.cubic = cubic;
      GltfExport out = take(export_gltf(*s.raw, *s.scene, o), s.source);
      bytes = std::move(out.bytes);
      for (const GltfChannelReport& c : out.channels) {
        py::dict d;
        d["object"] = c.object;
        d["path"] = c.path;
        d["interpolation"] = c.interpolation;
        d["refitted"] = c.refitted;
        d["reason"] = c.reason;
        d["keys_before"] = c.keys_before;
        d["keys_after"] = c.keys_after;
        d["max_error"] = c.max_error;
        d["tolerance"] = c.tolerance;
        report.append(d);
      }
    } else {
      throw py::value_error("convert: the output must end in .gltf or .glb (export) or .json (scene file)");
    }
    std::ofstream file(output, std::ios::binary);
    if (!file || !file.write(bytes.data(), std::streamsize(bytes.size()))) {
      throw BindingError(Error{ErrorCode::io, "cannot write " + output});
    }
    return report;
  }, py::arg("input"), py::arg("output"), py::arg("animation") = "", py::arg("fps") = 24.0, py::arg("tolerance") = 1e-5,
     py::arg("reduce") = 0.0, py::arg("substeps") = 4, py::arg("cubic") = true,
     "`inbetween convert`: a scene or glTF file (or a dictionary) to .glb/.gltf (export; channels glTF cannot hold "
     "are refitted within `tolerance`; reduce > 0 refits every channel with that tolerance; cubic=False writes STEP "
     "and LINEAR only, for Blender 3.4) or to .json (a scene file).  Returns the channel report (list of dicts).");
}

}  // namespace inbetween::python
