// load_compressed(): an .ibc file (docs/compression.md) loaded for sampling in place, and
// CompressedClip.sample(): the runtime's float sampler (sample_compressed) into NumPy arrays of
// joints × 10 (tx, ty, tz, qw, qx, qy, qz, sx, sy, sz), local transforms.
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "common.hpp"
#include "inbetween/io/ibc.hpp"

namespace inbetween::python {
namespace {

struct PyCompressedClip {
  std::shared_ptr<const CompressedClip> clip;
};

PyCompressedClip load_compressed(const py::object& path_like) {
  const std::string path = py::str(py::module_::import("os").attr("fspath")(path_like)).cast<std::string>();
  auto clip = read_ibc_file(path);
  if (!clip) throw BindingError(clip.error(), path);
  return {std::make_shared<const CompressedClip>(std::move(*clip))};
}

py::array_t<float> sample(const PyCompressedClip& c, const Array& frames_in) {
  const CompressedClip& clip = *c.clip;
  const py::ssize_t n = frames_in.size();
  const std::size_t joints = clip.joints();
  std::vector<py::ssize_t> shape(frames_in.shape(), frames_in.shape() + frames_in.ndim());
  shape.push_back(py::ssize_t(joints));
  shape.push_back(10);
  py::array_t<float> out(shape);
  float* o = out.mutable_data();
  const double* f = frames_in.data();
  std::vector<JointPose<float>> local(joints);
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i) {
      sample_compressed(clip, f[i], local);
      for (std::size_t j = 0; j < joints; ++j, o += 10) {
        const JointPose<float>& p = local[j];
        const float row[10] = {p.translation.x, p.translation.y, p.translation.z, p.rotation.w, p.rotation.x,
                               p.rotation.y,    p.rotation.z,    p.scale.x,       p.scale.y,    p.scale.z};
        std::copy(row, row + 10, o);
      }
    }
  }
  return out;
}

}  // namespace

void bind_compressed(py::module_& m) {
  py::class_<PyCompressedClip>(m, "CompressedClip",
                               "A compressed clip (.ibc, docs/compression.md) sampled in place: joints (names, "
                               "parents), frames, the error bound and measured error.")
      .def_property_readonly("names", [](const PyCompressedClip& c) {
             return std::vector<std::string>(c.clip->names().begin(), c.clip->names().end());
           }, "Joint names (parents before children).")
      .def_property_readonly("parents", [](const PyCompressedClip& c) {
             py::array_t<std::int64_t> p(py::ssize_t(c.clip->joints()));
             for (std::size_t j = 0; j < c.clip->joints(); ++j) p.mutable_data()[j] = c.clip->parents()[j];
             return p;
           }, "Index of each joint's parent in names, -1 for a root (int64 array).")
      .def_property_readonly("frame_count", [](const PyCompressedClip& c) { return c.clip->frames(); },
                             "Samples per joint (one per frame).")
      .def_property_readonly("first_frame", [](const PyCompressedClip& c) { return c.clip->first_frame(); },
                             "Frame of the first sample.")
      .def_property_readonly("fps", [](const PyCompressedClip& c) { return c.clip->frame_rate(); },
                             "Frames per second.")
      .def_property_readonly("error_bound", [](const PyCompressedClip& c) { return c.clip->error_bound(); },
                             "The error bound E of compression (clip units).")
      .def_property_readonly("measured_error", [](const PyCompressedClip& c) { return c.clip->measured_error(); },
                             "The virtual-vertex error measured at compression (<= error_bound).")
      .def_property_readonly("shell", [](const PyCompressedClip& c) { return c.clip->shell(); },
                             "Distance of the virtual vertices of the metric (clip units).")
      .def_property_readonly("nbytes", [](const PyCompressedClip& c) { return c.clip->bytes().size(); },
                             "Size of the .ibc file in bytes.")
      .def("sample", &sample, py::arg("frames"),
           "Local transforms at `frames` (a number or an array of any shape; clamped to the clip) from the runtime's "
           "float sampler: float32 array frames.shape + (joints, 10): tx, ty, tz, qw, qx, qy, qz, sx, sy, sz.")
      .def("__repr__", [](const PyCompressedClip& c) {
        return "<inbetween.CompressedClip " + std::to_string(c.clip->joints()) + " joints, " +
               std::to_string(c.clip->frames()) + " frames, " + std::to_string(c.clip->bytes().size()) + " bytes>";
      });
  m.def("load_compressed", &load_compressed, py::arg("path"),
        "Loads an .ibc file (inbetween compress) for sampling in place; inbetween.Error names the file and the byte "
        "of a corrupt or truncated file.  load_clip() reads .ibc too (decompressed, keyed at every frame).");
}

}  // namespace inbetween::python
