// Bindings of the blending runtime (include/inbetween/tracks/runtime/blend.hpp, root_motion.hpp;
// docs/blending.md) on NumPy arrays: a pose is an array (..., J, 10) of joints as
// [tx, ty, tz, qw, qx, qy, qz, sx, sy, sz] (JointPose's order), computed in double.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "common.hpp"
#include "inbetween/tracks/runtime/blend.hpp"
#include "inbetween/tracks/runtime/root_motion.hpp"

namespace inbetween::python {
namespace {

using Pose = JointPose<double>;
static_assert(sizeof(Pose) == 10 * sizeof(double));

// The poses of `a` (shape (..., 10)) as a span over its own data (C-contiguous doubles).
std::span<const Pose> poses_of(const Array& a, const char* what) {
  const std::size_t n = batch_count(a, {10}, what);
  return {reinterpret_cast<const Pose*>(a.data()), n};
}

std::string shape_text(const Array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

MotionReference reference_of(const std::string& name, const char* what) {
  if (name == "absolute") return MotionReference::absolute;
  if (name == "rest") return MotionReference::rest;
  if (name == "first_frame") return MotionReference::first_frame;
  throw py::value_error(std::string(what) + ": expected 'absolute', 'rest' or 'first_frame', got '" + name + "'");
}

}  // namespace

void bind_blend(py::module_& m) {
  m.def("blend_poses", [](const Array& poses, const Array& weights, const std::optional<Array>& masks,
                          const std::optional<Array>& rest, const std::optional<Array>& additive,
                          const std::optional<Array>& additive_weights, const std::optional<Array>& additive_masks,
                          double threshold) {
    if (poses.ndim() != 3 || poses.shape(2) != 10)
      throw py::value_error("poses: expected an array of shape (layers, joints, 10), got shape " + shape_text(poses));
    const std::size_t layers = std::size_t(poses.shape(0)), joints = std::size_t(poses.shape(1));
    if (weights.ndim() != 1 || std::size_t(weights.shape(0)) != layers)
      throw py::value_error("weights: expected " + std::to_string(layers) + " layer weights, got shape " + shape_text(weights));
    if (!(threshold > 0) || !(threshold <= blend_weight_max<double>))
      throw py::value_error("threshold: expected a finite value > 0, got " + std::to_string(threshold));
    const auto check_masks = [&](const std::optional<Array>& mk, std::size_t count, const char* what) {
      if (mk && (mk->ndim() != 2 || std::size_t(mk->shape(0)) != count || std::size_t(mk->shape(1)) != joints))
        throw py::value_error(std::string(what) + ": expected an array of shape (" + std::to_string(count) + ", " +
                              std::to_string(joints) + "), got shape " + shape_text(*mk));
    };
    check_masks(masks, layers, "masks");
    std::vector<Pose> rest_pose(joints);
    if (rest) {
      if (rest->ndim() != 2 || std::size_t(rest->shape(0)) != joints || rest->shape(1) != 10)
        throw py::value_error("rest: expected an array of shape (" + std::to_string(joints) + ", 10), got shape " + shape_text(*rest));
      const auto r = poses_of(*rest, "rest");
      rest_pose.assign(r.begin(), r.end());
    }
    std::size_t nadd = 0;
    if (additive) {
      if (additive->ndim() != 3 || std::size_t(additive->shape(1)) != joints || additive->shape(2) != 10)
        throw py::value_error("additive: expected an array of shape (additive layers, " + std::to_string(joints) +
                              ", 10), got shape " + shape_text(*additive));
      nadd = std::size_t(additive->shape(0));
      if (!additive_weights || additive_weights->ndim() != 1 || std::size_t(additive_weights->shape(0)) != nadd)
        throw py::value_error("additive_weights: expected " + std::to_string(nadd) + " weights (one per additive layer)");
    }
    check_masks(additive_masks, nadd, "additive_masks");
    if (layers > blend_max_layers)
      throw py::value_error("poses: at most " + std::to_string(blend_max_layers) + " layers per call, got " + std::to_string(layers));
    const Pose* p = reinterpret_cast<const Pose*>(poses.data());
    std::vector<BlendLayer<double>> ls;
    for (std::size_t l = 0; l < layers; ++l)
      ls.push_back({{p + l * joints, joints}, weights.at(l),
                    masks ? std::span<const double>(masks->data() + l * joints, joints) : std::span<const double>{}});
    std::vector<AdditiveLayer<double>> as;
    for (std::size_t l = 0; l < nadd; ++l)
      as.push_back({{reinterpret_cast<const Pose*>(additive->data()) + l * joints, joints}, additive_weights->at(l),
                    additive_masks ? std::span<const double>(additive_masks->data() + l * joints, joints)
                                   : std::span<const double>{}});
    py::array_t<double> out({py::ssize_t(joints), py::ssize_t(10)});
    std::span<Pose> o(reinterpret_cast<Pose*>(out.mutable_data()), joints);
    blend_poses<double>(ls, as, rest_pose, o, {.threshold = threshold});
    return out;
  }, py::arg("poses"), py::arg("weights"), py::arg("masks") = py::none(), py::arg("rest") = py::none(),
     py::arg("additive") = py::none(), py::arg("additive_weights") = py::none(), py::arg("additive_masks") = py::none(),
     py::arg("threshold") = 0.1,
     "Blend of layers (L, J, 10) of poses [tx, ty, tz, qw, qx, qy, qz, sx, sy, sz] with weights (L,), optional "
     "per-joint masks (L, J), rest pose (J, 10) (default identity) used where the summed weight is below "
     "threshold, and additive delta layers (A, J, 10) with additive_weights (A,) and additive_masks (A, J); "
     "returns (J, 10).  NaN and negative weights count as 0 (docs/blending.md).");
  m.def("additive_delta", [](const Array& pose, const Array& reference) {
    const auto p = poses_of(pose, "pose");
    const auto r = poses_of(reference, "reference");
    if (p.size() != r.size())
      throw py::value_error("reference: expected the shape of pose " + shape_text(pose) + ", got " + shape_text(reference));
    py::array_t<double> out(std::vector<py::ssize_t>(pose.shape(), pose.shape() + pose.ndim()));
    additive_delta<double>(p, r, std::span<Pose>(reinterpret_cast<Pose*>(out.mutable_data()), p.size()));
    return out;
  }, py::arg("pose"), py::arg("reference"),
     "Delta poses (..., 10) of pose relative to reference (same shape): t - t_ref, q_ref* q, s / s_ref "
     "(a zero reference scale gives 1); an additive layer of blend_poses.");
  m.def("extract_root_motion", [](const Array& root, bool x, bool y, bool z, bool yaw, bool pitch, bool roll,
                                  const std::string& position_reference, const std::string& rotation_reference,
                                  bool bake, bool loop, const std::optional<Array>& rest) {
    if (root.ndim() != 2 || root.shape(1) != 10)
      throw py::value_error("root: expected an array of shape (frames, 10), got shape " + shape_text(root));
    const auto r = poses_of(root, "root");
    RootMotionOptions options{.x = x, .y = y, .z = z, .yaw = yaw, .pitch = pitch, .roll = roll,
                              .position_reference = reference_of(position_reference, "position_reference"),
                              .rotation_reference = reference_of(rotation_reference, "rotation_reference"),
                              .bake = bake, .loop = loop};
    Pose rest_pose;
    if (rest) {
      if (rest->ndim() != 1 || rest->shape(0) != 10)
        throw py::value_error("rest: expected an array of shape (10,), got shape " + shape_text(*rest));
      rest_pose = poses_of(*rest, "rest")[0];
    }
    std::vector<RootMotion<double>> motion(r.size());
    py::array_t<double> character({py::ssize_t(r.size()), py::ssize_t(10)});
    extract_root_motion<double>(r, options, motion,
                                std::span<Pose>(reinterpret_cast<Pose*>(character.mutable_data()), r.size()), rest_pose);
    py::array_t<double> m_out({py::ssize_t(r.size()), py::ssize_t(7)});
    double* o = m_out.mutable_data();
    for (std::size_t i = 0; i < r.size(); ++i) {
      const auto& mi = motion[i];
      const double v[7] = {mi.translation.x, mi.translation.y, mi.translation.z, mi.rotation.w, mi.rotation.x,
                           mi.rotation.y, mi.rotation.z};
      std::copy(v, v + 7, o + 7 * i);
    }
    return py::make_tuple(m_out, character);
  }, py::arg("root"), py::arg("x") = true, py::arg("y") = false, py::arg("z") = true, py::arg("yaw") = true,
     py::arg("pitch") = false, py::arg("roll") = false, py::arg("position_reference") = "first_frame",
     py::arg("rotation_reference") = "first_frame", py::arg("bake") = true, py::arg("loop") = false,
     py::arg("rest") = py::none(),
     "Root motion of a root joint's poses (N, 10) (Y up, ozz-animation's MotionExtractor semantics): returns "
     "(motion (N, 7) [tx, ty, tz, qw, qx, qy, qz], root in character space (N, 10)); world = motion applied to "
     "the character-space root (docs/blending.md).");
}

}  // namespace inbetween::python
