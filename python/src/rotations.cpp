// Rotations on arrays: every conversion of inbetween/math/rotation.hpp and euler.hpp, slerp
// (orientation_interp.hpp) and the Euler filter.  Quaternions are (..., 4) arrays in w, x, y, z
// order (Hamilton, w first), matrices (..., 3, 3) with v' = R v, angles in radians.
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>

#include "common.hpp"
#include "inbetween/math/euler.hpp"
#include "inbetween/math/format.hpp"
#include "inbetween/math/orientation_interp.hpp"
#include "inbetween/math/rotation.hpp"

namespace inbetween::python {
namespace {

Quatd quat_at(const double* p) { return Quatd::from_wxyz(p[0], p[1], p[2], p[3]); }
void put_quat(double* p, const Quatd& q) { p[0] = q.w, p[1] = q.x, p[2] = q.y, p[3] = q.z; }
Mat3d mat_at(const double* p) {
  Mat3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m.m[r][c] = p[3 * r + c];
  return m;
}
void put_mat(double* p, const Mat3d& m) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p[3 * r + c] = m.m[r][c];
}
Vec3d vec_at(const double* p) { return {p[0], p[1], p[2]}; }
void put_vec(double* p, const Vec3d& v) { p[0] = v.x, p[1] = v.y, p[2] = v.z; }

EulerSequence sequence(const std::string& name) { return take(parse_euler_sequence(name), "seq"); }

/// Refuses an input array with a NaN or infinite element: inbetween.Error (code NotFinite) naming
/// `what` and the item's flat index ("/i"), as quat_from_matrix's own check does.  The conversions
/// themselves would quietly turn such input into the identity.
void require_finite(const Array& a, std::size_t item_size, const char* what) {
  const double* p = a.data();
  const std::size_t n = std::size_t(a.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(p[k])) {
      throw BindingError(Error{ErrorCode::NotFinite, std::string(what) + " has a value that is not finite (" + shortest_text(p[k]) + ")",
                               "", {item_size ? k / item_size : k}},
                         what);
    }
  }
}

/// q scaled to unit length when it is not unit already (a unit q is kept bit for bit), first
/// divided by its largest component so that a finite q of any magnitude (1e308) normalises
/// without overflow; zero stays zero.
Quatd unit_quat(Quatd q) {
  const double n2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
  if (std::abs(n2 - 1) <= 1e-12) return q;
  const double m = std::max({std::abs(q.w), std::abs(q.x), std::abs(q.y), std::abs(q.z)});
  if (!(m > 0)) return q;
  q = q / m;
  return q / norm(q);
}

/// Applies f(in_item, out_item) to each of the n items of `in` (item sizes in_size, out_size),
/// after require_finite(in).
template <class F>
Array map_items(const Array& in, std::initializer_list<py::ssize_t> tail_in, std::initializer_list<py::ssize_t> tail_out,
                const char* what, F f) {
  const std::size_t n = batch_count(in, tail_in, what);
  Array out(out_shape(in, tail_in.size(), tail_out));
  std::size_t in_size = 1, out_size = 1;
  for (auto t : tail_in) in_size *= std::size_t(t);
  for (auto t : tail_out) out_size *= std::size_t(t);
  require_finite(in, in_size, what);
  const double* src = in.data();
  double* dst = out.mutable_data();
  {
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < n; ++i) f(src + i * in_size, dst + i * out_size, i);
  }
  return out;
}

}  // namespace

void bind_rotations(py::module_& m) {
  m.def("euler_sequences", [] {
    std::vector<std::string> names;
    for (const EulerSequence& s : all_euler_sequences()) names.push_back(s.name());
    return names;
  }, "The 24 Euler conventions as SciPy-style names: the 12 axis sequences intrinsic (upper case, "
     "rotating axes: \"XYZ\"), then extrinsic (lower case, fixed axes: \"xyz\").  docs/conventions.md.");

  m.def("matrix_from_quat", [](const Array& q) {
    return map_items(q, {4}, {3, 3}, "q", [](const double* a, double* b, std::size_t) { put_mat(b, matrix_from_quat(quat_at(a))); });
  }, py::arg("q"), "Rotation matrices (..., 3, 3) of quaternions (..., 4) w, x, y, z of any non-zero length "
                   "(the scale cancels; zero or non-finite q gives the identity).  v' = R v.");

  m.def("quat_from_matrix", [](const Array& r, bool check, double tolerance) {
    if (!(tolerance >= 0) || !std::isfinite(tolerance)) {
      throw BindingError(Error{ErrorCode::InvalidArgument, "tolerance must be finite and >= 0, got " + shortest_text(tolerance), "",
                               {"tolerance"}});
    }
    return map_items(r, {3, 3}, {4}, "matrix", [&](const double* a, double* b, std::size_t i) {
      const Mat3d mat = mat_at(a);
      if (check) {
        auto ok = check_rotation(mat, tolerance);
        if (!ok) {
          Error e = ok.error();
          e.prepend({i});
          throw BindingError(e, "matrix");
        }
      }
      put_quat(b, quat_from_matrix(mat));
    });
  }, py::arg("matrix"), py::arg("check") = true, py::arg("tolerance") = rotation_check_tolerance<double>,
     "Unit quaternions (..., 4), canonical (w >= 0), of rotation matrices (..., 3, 3) (Shepperd's method).  "
     "check: each matrix must be a rotation (finite, max |R^T R - I| <= tolerance, |det R - 1| <= tolerance), "
     "else inbetween.Error at its flat index (\"/i\").");

  m.def("quat_from_rotvec", [](const Array& r) {
    return map_items(r, {3}, {4}, "rotvec", [](const double* a, double* b, std::size_t) { put_quat(b, quat_from_rotation_vector(vec_at(a))); });
  }, py::arg("rotvec"), "Unit quaternions (..., 4) of rotation vectors (..., 3) (axis times angle in radians).");
  m.def("rotvec_from_quat", [](const Array& q) {
    return map_items(q, {4}, {3}, "q", [](const double* a, double* b, std::size_t) { put_vec(b, rotation_vector_from_quat(quat_at(a))); });
  }, py::arg("q"), "Rotation vectors (..., 3) of quaternions (..., 4): axis times the angle in [0, pi].");
  m.def("matrix_from_rotvec", [](const Array& r) {
    return map_items(r, {3}, {3, 3}, "rotvec", [](const double* a, double* b, std::size_t) { put_mat(b, matrix_from_rotation_vector(vec_at(a))); });
  }, py::arg("rotvec"), "Rotation matrices (..., 3, 3) of rotation vectors (..., 3).");
  m.def("rotvec_from_matrix", [](const Array& r) {
    return map_items(r, {3, 3}, {3}, "matrix", [](const double* a, double* b, std::size_t) { put_vec(b, rotation_vector_from_matrix(mat_at(a))); });
  }, py::arg("matrix"), "Rotation vectors (..., 3) of rotation matrices (..., 3, 3) (not checked).");

  m.def("quat_from_axis_angle", [](const Array& axis, const Array& angle_rad) {
    const std::size_t n = batch_count(axis, {3}, "axis");
    if (std::size_t(angle_rad.size()) != n) {
      throw py::value_error("angle_rad: expected " + std::to_string(n) + " angles (one per axis), got " +
                            std::to_string(angle_rad.size()));
    }
    require_finite(angle_rad, 1, "angle_rad");
    const double* ang = angle_rad.data();
    return map_items(axis, {3}, {4}, "axis", [&](const double* a, double* b, std::size_t i) {
      put_quat(b, quat_from_axis_angle(AxisAngled{vec_at(a), ang[i]}));
    });
  }, py::arg("axis"), py::arg("angle_rad"), "Unit quaternions (..., 4) of rotations by angle_rad (...) about axis (..., 3) "
                                            "(normalised first; a zero axis gives the identity).");
  m.def("axis_angle_from_quat", [](const Array& q) {
    const std::size_t n = batch_count(q, {4}, "q");
    Array angle(out_shape(q, 1, {}));
    double* ang = angle.mutable_data();
    Array axis = map_items(q, {4}, {3}, "q", [&](const double* a, double* b, std::size_t i) {
      const AxisAngled aa = axis_angle_from_quat(quat_at(a));
      put_vec(b, aa.axis);
      ang[i] = aa.angle_rad;
    });
    (void)n;
    return py::make_tuple(axis, angle);
  }, py::arg("q"), "(axis (..., 3), angle_rad (...)) of quaternions (..., 4): unit axis, angle in [0, pi] "
                   "(the identity gives axis x and angle 0).");
  m.def("matrix_from_axis_angle", [](const Array& axis, const Array& angle_rad) {
    const std::size_t n = batch_count(axis, {3}, "axis");
    if (std::size_t(angle_rad.size()) != n) {
      throw py::value_error("angle_rad: expected " + std::to_string(n) + " angles (one per axis), got " +
                            std::to_string(angle_rad.size()));
    }
    require_finite(angle_rad, 1, "angle_rad");
    const double* ang = angle_rad.data();
    return map_items(axis, {3}, {3, 3}, "axis", [&](const double* a, double* b, std::size_t i) {
      put_mat(b, matrix_from_axis_angle(AxisAngled{vec_at(a), ang[i]}));
    });
  }, py::arg("axis"), py::arg("angle_rad"), "Rotation matrices (..., 3, 3) of axis-angle pairs.");
  m.def("axis_angle_from_matrix", [](const Array& r) {
    Array angle(out_shape(r, 2, {}));
    batch_count(r, {3, 3}, "matrix");
    double* ang = angle.mutable_data();
    Array axis = map_items(r, {3, 3}, {3}, "matrix", [&](const double* a, double* b, std::size_t i) {
      const AxisAngled aa = axis_angle_from_matrix(mat_at(a));
      put_vec(b, aa.axis);
      ang[i] = aa.angle_rad;
    });
    return py::make_tuple(axis, angle);
  }, py::arg("matrix"), "(axis (..., 3), angle_rad (...)) of rotation matrices (..., 3, 3).");

  m.def("quat_from_euler", [](const std::string& seq, const Array& angles_rad) {
    const EulerSequence s = sequence(seq);
    return map_items(angles_rad, {3}, {4}, "angles_rad", [&](const double* a, double* b, std::size_t) {
      put_quat(b, quat_from_euler(s, EulerTriple<double>{a[0], a[1], a[2]}));
    });
  }, py::arg("seq"), py::arg("angles_rad"),
     "Unit quaternions (..., 4), canonical (w >= 0), of Euler angles (..., 3) in radians, in the order of the letters "
     "of seq (one of euler_sequences(): upper case intrinsic, lower case extrinsic, as SciPy's Rotation.from_euler).");
  m.def("matrix_from_euler", [](const std::string& seq, const Array& angles_rad) {
    const EulerSequence s = sequence(seq);
    return map_items(angles_rad, {3}, {3, 3}, "angles_rad", [&](const double* a, double* b, std::size_t) {
      put_mat(b, matrix_from_euler(s, EulerTriple<double>{a[0], a[1], a[2]}));
    });
  }, py::arg("seq"), py::arg("angles_rad"), "Rotation matrices (..., 3, 3) of Euler angles (..., 3) in convention seq.");

  const auto euler_out = [](const EulerSequence& s, const Array& in, std::initializer_list<py::ssize_t> tail, const char* what,
                            double tol, bool with_lock, bool from_matrix) -> py::object {
    batch_count(in, tail, what);
    py::array_t<bool> lock(out_shape(in, tail.size(), {}));
    bool* lk = lock.mutable_data();
    EulerOptions<double> opt;
    opt.gimbal_tolerance_rad = tol;
    Array angles = map_items(in, tail, {3}, what, [&](const double* a, double* b, std::size_t i) {
      const EulerAngles<double> e = from_matrix ? euler_from_matrix(s, mat_at(a), opt) : euler_from_quat(s, quat_at(a), opt);
      b[0] = e.angles_rad[0], b[1] = e.angles_rad[1], b[2] = e.angles_rad[2];
      lk[i] = e.gimbal_lock;
    });
    if (with_lock) return py::make_tuple(angles, lock);
    return angles;
  };
  m.def("euler_from_quat", [euler_out](const std::string& seq, const Array& q, double gimbal_tolerance_rad, bool return_gimbal_lock) {
    return euler_out(sequence(seq), q, {4}, "q", gimbal_tolerance_rad, return_gimbal_lock, false);
  }, py::arg("seq"), py::arg("q"), py::arg("gimbal_tolerance_rad") = EulerOptions<double>{}.gimbal_tolerance_rad,
     py::arg("return_gimbal_lock") = false,
     "Euler angles (..., 3) in radians of quaternions (..., 4) (any non-zero scale and sign) in convention seq, in "
     "SciPy's ranges: first and third in (-pi, pi], middle in [-pi/2, pi/2] (Tait-Bryan) or [0, pi] (proper).  "
     "At gimbal lock (middle angle within gimbal_tolerance_rad of singular) the third angle is 0 where the split is "
     "rounding noise (SciPy's choice).  return_gimbal_lock: also return a bool array (...) of the lock flags.");
  m.def("euler_from_matrix", [euler_out](const std::string& seq, const Array& r, double gimbal_tolerance_rad, bool return_gimbal_lock) {
    return euler_out(sequence(seq), r, {3, 3}, "matrix", gimbal_tolerance_rad, return_gimbal_lock, true);
  }, py::arg("seq"), py::arg("matrix"), py::arg("gimbal_tolerance_rad") = EulerOptions<double>{}.gimbal_tolerance_rad,
     py::arg("return_gimbal_lock") = false,
     "Euler angles (..., 3) of rotation matrices (..., 3, 3) (through Shepperd's quaternion); see euler_from_quat.");

  m.def("euler_filter", [](const std::string& seq, const Array& angles_rad, double gimbal_tolerance_rad) {
    const EulerSequence s = sequence(seq);
    const std::size_t n = batch_count(angles_rad, {3}, "angles_rad");
    if (angles_rad.ndim() != 2) throw py::value_error("angles_rad: expected an array of shape (n, 3) (a sequence of keys)");
    require_finite(angles_rad, 3, "angles_rad");
    Array out(out_shape(angles_rad, 1, {3}));
    const double* a = angles_rad.data();
    double* b = out.mutable_data();
    EulerOptions<double> opt;
    opt.gimbal_tolerance_rad = gimbal_tolerance_rad;
    py::gil_scoped_release release;
    EulerTriple<double> prev{};
    for (std::size_t i = 0; i < n; ++i) {
      EulerTriple<double> cur{a[3 * i], a[3 * i + 1], a[3 * i + 2]};
      if (i > 0) cur = euler_filter(s, prev, cur, opt);
      b[3 * i] = cur[0], b[3 * i + 1] = cur[1], b[3 * i + 2] = cur[2];
      prev = cur;
    }
    return out;
  }, py::arg("seq"), py::arg("angles_rad"), py::arg("gimbal_tolerance_rad") = EulerOptions<double>{}.gimbal_tolerance_rad,
     "The Euler filter along a sequence of keys (n, 3): the first triple is kept; each next one is replaced by the "
     "triple of the same rotation closest to the previous (filtered) one -- the alternate solution and 2*pi shifts, "
     "and at gimbal lock the free combination split evenly.  The result may leave the extraction ranges.");

  m.def("slerp", [](const Array& a, const Array& b, const Array& u, const std::string& path) {
    const std::size_t na = batch_count(a, {4}, "a"), nb = batch_count(b, {4}, "b");
    const std::size_t nu = std::size_t(u.size());
    const std::size_t n = std::max({na, nb, nu});
    for (auto [k, what] : {std::pair{na, "a"}, std::pair{nb, "b"}, std::pair{nu, "u"}}) {
      if (k != 1 && k != n) {
        throw py::value_error(std::string("slerp: ") + what + " has " + std::to_string(k) + " items; expected 1 or " +
                              std::to_string(n) + " (a and b (..., 4) quaternions, u (...) parameters)");
      }
    }
    require_finite(a, 4, "a");
    require_finite(b, 4, "b");
    require_finite(u, 1, "u");
    SlerpOptions opt;
    if (path == "shortest") opt.path = RotationPath::shortest;
    else if (path == "longest") opt.path = RotationPath::longest;
    else if (path == "as_given") opt.path = RotationPath::as_given;
    else throw py::value_error("slerp: path \"" + path + "\" is not one of shortest, longest, as_given");
    std::vector<py::ssize_t> shape = nu == n && u.ndim() > 0 ? out_shape(u, 0, {4})
                                     : na == n ? out_shape(a, 1, {4}) : out_shape(b, 1, {4});
    Array out(shape);
    const double *pa = a.data(), *pb = b.data(), *pu = u.data();
    double* po = out.mutable_data();
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < n; ++i) {
      // Normalised first: slerp wants unit quaternions, and a finite 1e308 one overflows a plain norm.
      const Quatd qa = unit_quat(quat_at(pa + (na == 1 ? 0 : 4 * i))), qb = unit_quat(quat_at(pb + (nb == 1 ? 0 : 4 * i)));
      put_quat(po + 4 * i, slerp(qa, qb, pu[nu == 1 ? 0 : i], opt));
    }
    return out;
  }, py::arg("a"), py::arg("b"), py::arg("u"), py::arg("path") = "shortest",
     "Spherical linear interpolation of quaternions a, b (..., 4) (normalised first when not unit; any finite "
     "non-zero magnitude) at parameters u (...), broadcasting items of "
     "count 1: the great arc at constant angular speed, a at u = 0 and the oriented b at u = 1 exactly.  path: "
     "\"shortest\" (b's sign flipped when a.b < 0), \"longest\" or \"as_given\".");
}

}  // namespace inbetween::python
