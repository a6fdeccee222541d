"""Type stubs of the inbetween module (docs/python.md).  Kept in sync with the bindings by
python/tests/test_api.py (every public name appears here and has a docstring)."""
from os import PathLike
from typing import Any, Mapping, Sequence

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
NDArray = npt.NDArray[np.float64]
Source = str | PathLike[str] | Mapping[str, Any]

class Error(ValueError):
    """Bad user data: .message (what is wrong), .where (JSON pointer or free-text place, may be
    empty), .code (inbetween::ErrorCode name).  str() is the command-line tool's "place: message"."""
    message: str
    where: str
    code: str

# ----------------------------------------------------------------------------------- rotations
def euler_sequences() -> list[str]:
    """The 24 Euler conventions: "XYZ" … intrinsic (upper case), "xyz" … extrinsic (lower case)."""
def matrix_from_quat(q: ArrayLike) -> NDArray:
    """Rotation matrices (..., 3, 3) of quaternions (..., 4) w, x, y, z (any non-zero length)."""
def quat_from_matrix(matrix: ArrayLike, check: bool = True, tolerance: float = 1e-6) -> NDArray:
    """Unit quaternions (..., 4), w >= 0, of rotation matrices (..., 3, 3); check: Error if not a rotation."""
def quat_from_rotvec(rotvec: ArrayLike) -> NDArray:
    """Unit quaternions (..., 4) of rotation vectors (..., 3) (axis times angle in radians)."""
def rotvec_from_quat(q: ArrayLike) -> NDArray:
    """Rotation vectors (..., 3) of quaternions (..., 4), angle in [0, pi]."""
def matrix_from_rotvec(rotvec: ArrayLike) -> NDArray:
    """Rotation matrices (..., 3, 3) of rotation vectors (..., 3)."""
def rotvec_from_matrix(matrix: ArrayLike) -> NDArray:
    """Rotation vectors (..., 3) of rotation matrices (..., 3, 3)."""
def quat_from_axis_angle(axis: ArrayLike, angle_rad: ArrayLike) -> NDArray:
    """Unit quaternions (..., 4) of rotations by angle_rad (...) about axis (..., 3)."""
def axis_angle_from_quat(q: ArrayLike) -> tuple[NDArray, NDArray]:
    """(axis (..., 3), angle_rad (...)) of quaternions (..., 4), angle in [0, pi]."""
def matrix_from_axis_angle(axis: ArrayLike, angle_rad: ArrayLike) -> NDArray:
    """Rotation matrices (..., 3, 3) of axis-angle pairs."""
def axis_angle_from_matrix(matrix: ArrayLike) -> tuple[NDArray, NDArray]:
    """(axis (..., 3), angle_rad (...)) of rotation matrices (..., 3, 3)."""
def quat_from_euler(seq: str, angles_rad: ArrayLike) -> NDArray:
    """Unit quaternions (..., 4) of Euler angles (..., 3) in radians, convention seq (SciPy's names)."""
def matrix_from_euler(seq: str, angles_rad: ArrayLike) -> NDArray:
    """Rotation matrices (..., 3, 3) of Euler angles (..., 3) in convention seq."""
def euler_from_quat(seq: str, q: ArrayLike, gimbal_tolerance_rad: float = 1e-7,
                    return_gimbal_lock: bool = False) -> NDArray | tuple[NDArray, npt.NDArray[np.bool_]]:
    """Euler angles (..., 3) of quaternions (..., 4) in SciPy's ranges; optionally the gimbal-lock flags."""
def euler_from_matrix(seq: str, matrix: ArrayLike, gimbal_tolerance_rad: float = 1e-7,
                      return_gimbal_lock: bool = False) -> NDArray | tuple[NDArray, npt.NDArray[np.bool_]]:
    """Euler angles (..., 3) of rotation matrices (..., 3, 3); see euler_from_quat."""
def euler_filter(seq: str, angles_rad: ArrayLike, gimbal_tolerance_rad: float = 1e-7) -> NDArray:
    """The Euler filter along keys (n, 3): each triple replaced by the equivalent one closest to the previous."""
def slerp(a: ArrayLike, b: ArrayLike, u: ArrayLike, path: str = "shortest") -> NDArray:
    """Spherical linear interpolation of quaternions a, b (..., 4) at u (...); path shortest, longest, as_given."""

# ----------------------------------------------------------------------------------- curves
class Curve:
    """A curve of any family from a curve-file dictionary or JSON text (docs/curve-format.md)."""
    def __init__(self, spec: Mapping[str, Any] | str) -> None:
        """Reads and builds the curve; Error with the JSON pointer on bad data."""
    @property
    def kind(self) -> str:
        """The family: the curve file's "type" string."""
    @property
    def dimension(self) -> int:
        """1, 2 or 3: components of the points as authored."""
    @property
    def domain(self) -> tuple[float, float]:
        """(u_lo, u_hi): the parameter domain."""
    @property
    def segment_count(self) -> int:
        """Number of pieces."""
    @property
    def closed(self) -> bool:
        """True for a closed curve."""
    @property
    def control_points(self) -> NDArray:
        """Control points (n, dimension)."""
    def point(self, u: ArrayLike) -> NDArray:
        """P(u) (u clamped): shape u.shape + (dimension,)."""
    def derivative(self, u: ArrayLike, k: int = 1) -> NDArray:
        """d^kP/du^k (u clamped, right limit at joints): shape u.shape + (dimension,)."""
    def continuity(self) -> list[dict[str, Any]]:
        """Continuity at every joint: u, left_segment, right_segment, c_order, g1, tangent_angle_rad, jump."""
    def to_json(self) -> str:
        """The curve as a version-1 curve file (JSON text)."""

class ArcLength:
    """Arc-length parameterisation of a curve: s(u), u(s) and points at arc lengths (clamped)."""
    def __init__(self, curve: Curve, relative_tolerance: float = 1e-11) -> None:
        """Builds the adaptive Gauss table and the piecewise Chebyshev inverse."""
    @property
    def length(self) -> float:
        """Total length L >= 0."""
    @property
    def domain(self) -> tuple[float, float]:
        """(u_lo, u_hi): the curve's parameter domain."""
    def s(self, u: ArrayLike, out: NDArray | None = None) -> NDArray:
        """s(u): arc length from the start (u clamped)."""
    def u(self, s: ArrayLike, out: NDArray | None = None) -> NDArray:
        """u(s) by the piecewise Chebyshev inverse (s clamped into [0, L]); into `out` when given."""
    def u_newton(self, s: ArrayLike) -> NDArray:
        """u(s) by Newton-Raphson on the Gauss table (the reference)."""
    def point_at_length(self, s: ArrayLike) -> NDArray:
        """P(u(s)): shape s.shape + (dimension,)."""

# ----------------------------------------------------------------------------------- timing, tracks
class Speed:
    """Distance along a path over frames from a scene file's "speed" dictionary (eases, keys, velocities)."""
    def __init__(self, spec: Mapping[str, Any] | str, length: float = 1.0, fps: float = 24.0) -> None:
        """Builds the speed for a path of `length` at `fps`; Error with the place inside spec."""
    @property
    def frame_range(self) -> tuple[float, float]:
        """(first, last): the frames over which the distance changes."""
    def distance(self, frames: ArrayLike) -> NDArray:
        """s(frame), clamped into [0, length]."""
    def velocity(self, frames: ArrayLike) -> NDArray:
        """ds/dframe."""
    def acceleration(self, frames: ArrayLike) -> NDArray:
        """d^2s/dframe^2."""

def ease(spec: Mapping[str, Any], t: ArrayLike) -> NDArray:
    """The normalised ease S(t) of an ease dictionary (speed.ease) at normalised times t."""

class Track:
    """A track from a scene-file track dictionary: scalar F-curve (with its "modifiers", Blender's
    F-curve modifier stack), vector, colour, quaternion or euler."""
    def __init__(self, spec: Mapping[str, Any] | str, fps: float = 24.0) -> None:
        """Builds the track; Error with the place inside spec."""
    @property
    def columns(self) -> list[str]:
        """Names of the components."""
    def sample(self, frames: ArrayLike) -> NDArray:
        """Values at each frame: frames.shape (scalar) or frames.shape + (components,)."""

# ----------------------------------------------------------------------------------- scenes, glTF
class Scene:
    """A scene file (path, dictionary or JSON text) or a glTF file, read and built once."""
    def __init__(self, source: Source, animation: str = "", fps: float = 24.0) -> None:
        """Reads and builds; glTF: animation name or index, frame = time * fps."""
    @property
    def fps(self) -> float:
        """Frames per second of the time column."""
    @property
    def range(self) -> tuple[float, float]:
        """(first, last): the default bake range."""
    @property
    def columns(self) -> list[str]:
        """frame, time, then the scene's columns."""
    def bake(self, frames: ArrayLike | None = None, step: float = 1.0) -> tuple[NDArray, list[str]]:
        """(values (n, len(columns)), columns): the numbers of `inbetween bake`."""
    def to_json(self) -> str:
        """The scene as a scene file (JSON text)."""

def bake(scene: Scene | Source, frames: ArrayLike | None = None, step: float = 1.0, animation: str = "",
         fps: float = 24.0) -> tuple[NDArray, list[str]]:
    """Bakes a scene (object, path, dictionary or JSON text): (values, columns) as `inbetween bake`."""
def convert(input: Source, output: str, animation: str = "", fps: float = 24.0, tolerance: float = 1e-5,
            reduce: float = 0.0, substeps: int = 4, cubic: bool = True) -> list[dict[str, Any]]:
    """`inbetween convert`: scene or glTF to .glb/.gltf or .json; returns the channel report."""

class Clip:
    """A file's objects (a skeleton's joints) sampled at frames, in local or world space."""
    def __init__(self) -> None:
        """Not constructible from Python: load_clip() makes one."""
    @property
    def names(self) -> list[str]:
        """Object (joint) names, in the file's order."""
    @property
    def parents(self) -> NDArray:
        """int64 index of each object's parent in names, -1 for a root."""
    @property
    def frames(self) -> NDArray:
        """The frames sampled (1-D)."""
    @property
    def times(self) -> NDArray:
        """frames / fps, seconds."""
    @property
    def fps(self) -> float:
        """Frames per second."""
    @property
    def space(self) -> str:
        """Either "local" (relative to the parent) or "world"."""
    @property
    def transforms(self) -> NDArray:
        """(len(frames), len(names), 10): tx, ty, tz, qw, qx, qy, qz, sx, sy, sz."""
    @property
    def skins(self) -> list[tuple[str, list[int]]]:
        """(name, joint indices into names) per skin of the file."""

def load_clip(path: str | PathLike[str], space: str = "local", frames: ArrayLike | None = None,
              fps: float | None = None, animation: str | None = None) -> Clip:
    """Any file inbetween reads, every object sampled at frames (default the file's range, step 1) in
    space "local" or "world", as `inbetween bake --space`; inbetween.Error names the file and place."""

class CompressedClip:
    """A compressed clip (.ibc) sampled in place."""
    def __init__(self) -> None:
        """Not constructible from Python: load_compressed() makes one."""
    @property
    def names(self) -> list[str]:
        """Joint names (parents before children)."""
    @property
    def parents(self) -> NDArray:
        """int64 index of each joint's parent in names, -1 for a root."""
    @property
    def frame_count(self) -> int:
        """Samples per joint."""
    @property
    def first_frame(self) -> float:
        """Frame of the first sample."""
    @property
    def fps(self) -> float:
        """Frames per second."""
    @property
    def error_bound(self) -> float:
        """The error bound of compression (clip units)."""
    @property
    def measured_error(self) -> float:
        """The measured virtual-vertex error (<= error_bound)."""
    @property
    def shell(self) -> float:
        """Distance of the metric's virtual vertices."""
    @property
    def nbytes(self) -> int:
        """Size of the .ibc file."""
    def sample(self, frames: ArrayLike) -> NDArray:
        """float32 frames.shape + (joints, 10) local transforms from the runtime's float sampler."""

def load_compressed(path: str | PathLike[str]) -> CompressedClip:
    """Loads an .ibc file for sampling in place; inbetween.Error names the byte of a corrupt file."""

# ----------------------------------------------------------------------------------- paths
def fit_bspline(t: ArrayLike, points: ArrayLike, degree: int = 3,
                control_points: int = 0) -> tuple[Curve, dict[str, Any]]:
    """Least-squares B-spline through points (n, d) at times t: (Curve, info)."""
def smooth(points: ArrayLike, method: str = "convolution", iterations: int = 1, kernel: str = "tent",
           radius: float = 1.0, fix_ends: bool = False, smooth_ends: bool = False) -> NDArray:
    """Smoothed copy of sampled points (n, d): linear, cubic or convolution."""
def surface_path(obj: str | PathLike[str], from_vertex: int, to_vertex: int, method: str = "plane") -> NDArray:
    """A path on a triangle mesh (OBJ) between two vertices: points (n, 3)."""
def downhill_path(obj: str | PathLike[str], start_vertex: int, up: ArrayLike = ...) -> NDArray:
    """The downhill path on a triangle mesh from a vertex: points (n, 3)."""
def find_path(environment: Source, steering: bool = True) -> tuple[Curve, dict[str, Any]]:
    """Path finding among obstacles: (Curve, timing dict)."""
def surface_uv_path(surface: Source, from_uv: ArrayLike, to_uv: ArrayLike, count: int = 33) -> NDArray:
    """The straight (u, v) line mapped onto a named surface: points (n, 3)."""
def surface_downhill_path(surface: Source, start: ArrayLike, up: ArrayLike = ..., step: float = 0.0,
                          max_steps: int = 100000) -> NDArray:
    """Downhill on a named surface from S(u, v) or a point (x, y, z): points (n, 3)."""
def blend_poses(poses: ArrayLike, weights: ArrayLike, masks: ArrayLike | None = None, rest: ArrayLike | None = None,
                additive: ArrayLike | None = None, additive_weights: ArrayLike | None = None,
                additive_masks: ArrayLike | None = None, threshold: float = 0.1) -> NDArray:
    """Blend of layers (L, J, 10) of poses [tx, ty, tz, qw, qx, qy, qz, sx, sy, sz] with weights (L,), masks (L, J), rest (J, 10), additive deltas (A, J, 10); returns (J, 10)."""
def additive_delta(pose: ArrayLike, reference: ArrayLike) -> NDArray:
    """Delta poses (..., 10) of pose relative to reference: t - t_ref, q_ref* q, s / s_ref."""
def extract_root_motion(root: ArrayLike, x: bool = True, y: bool = False, z: bool = True, yaw: bool = True,
                        pitch: bool = False, roll: bool = False, position_reference: str = "first_frame",
                        rotation_reference: str = "first_frame", bake: bool = True, loop: bool = False,
                        rest: ArrayLike | None = None) -> tuple[NDArray, NDArray]:
    """Root motion (N, 7) [tx, ty, tz, qw, qx, qy, qz] and the root in character space (N, 10) of root poses (N, 10); Y up."""
