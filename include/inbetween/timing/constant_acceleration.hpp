#pragma once
/// Constant-acceleration ease-in/ease-out from whichever parameters the user knows (Parent §3.2.3,
/// Figures 3.16–3.18): acceleration a on [0, t1], cruise at v0 on [t1, t2], deceleration d on
/// [t2, 1], over normalised time 1.  Continuity of the velocity (it starts and ends at rest) gives
/// v0 = a·t1 = d·(1 − t2) — the texts' "area under acc equals the area above dec" —, and covering
/// the distance D gives D = v0·(1 + t2 − t1)/2 (Eq. 3.21).
///
/// Two solvers, for the texts' two ways of specifying the profile:
/// - solve_constant_acceleration(): the distance is normalised (D = 1), so two equations hold and
///   any TWO independent values of {t1, t2, v0, acceleration, deceleration} fix the profile (the
///   texts: "two of the three variables t1, t2 and v0", extended to the accelerations).
/// - solve_equal_areas(): the acceleration graph of Figure 3.16 with the distance free (the texts:
///   "three of the four variables acc, dec, t1, t2 can be specified and the system can solve for
///   the fourth"); only the equal-areas equation holds and the distance D is an output.  The
///   normalised ease of that graph is ConstantAccelerationEase::make(t1, t2), whose accelerations
///   are a/D and d/D.
/// Closed forms and their derivations: docs/timing.md, "Constant acceleration from any parameters".

#include <optional>

#include "inbetween/math/expected.hpp"
#include "inbetween/math/scalar.hpp"
#include "inbetween/timing/ease.hpp"

namespace inbetween {

/// The parameters a user may give for a constant-acceleration ease in normalised units (distance 1
/// over time 1); unset members are solved for.  Exactly two must be set.
template <Real T>
struct ConstantAccelerationParams {
  std::optional<T> t1{};            ///< end of the acceleration phase, in [0, 1]
  std::optional<T> t2{};            ///< start of the deceleration phase, in [t1, 1]
  std::optional<T> v0{};            ///< cruising velocity (normalised distance per normalised time), in [1, 2]
  std::optional<T> acceleration{};  ///< a = v0/t1 (normalised), > 0
  std::optional<T> deceleration{};  ///< d = v0/(1 − t2), the magnitude of the slowing down, > 0
};

/// The complete acceleration graph of Figure 3.16 over normalised time 1 with its distance.
template <Real T>
struct ConstantAccelerationGraph {
  T acceleration{};  ///< a on [0, t1] (distance units per unit time²)
  T deceleration{};  ///< d on [t2, 1] (magnitude)
  T t1{};            ///< end of the acceleration
  T t2{};            ///< start of the deceleration
  T v0{};            ///< cruising velocity a·t1 = d·(1 − t2)
  T distance{};      ///< D = v0·(1 + t2 − t1)/2, the area under the velocity (Eq. 3.21)
};

/// The three-of-four form of Figure 3.16 (unset members are solved for); exactly three must be set.
template <Real T>
struct EqualAreasParams {
  std::optional<T> acceleration{};  ///< a > 0 on [0, t1]
  std::optional<T> deceleration{};  ///< d > 0 on [t2, 1]
  std::optional<T> t1{};            ///< in (0, 1)
  std::optional<T> t2{};            ///< in [t1, 1)
};

/// The ease fixed by exactly two of `p`'s members (closed forms, no iteration):
///   t1, t2 → v0 = 2/(1 + t2 − t1);      t1, v0 → t2 = t1 + 2/v0 − 1;    t2, v0 → t1 = t2 − 2/v0 + 1;
///   a, t1  → v0 = a·t1, then t2;          d, t2 → v0 = d·(1 − t2), then t1;
///   a, v0  → t1 = v0/a, then t2;          d, v0 → t2 = 1 − v0/d, then t1;
///   a, t2  → t1 = 4/(a·(1 + t2 + √((1 + t2)² − 8/a))), the root of a·t1² − a(1 + t2)·t1 + 2 = 0
///            below t2 (it exists iff a·t2 ≥ 2);
///   d, t1  → 1 − t2 the same with (d, 1 − t1) (exists iff d·(1 − t1) ≥ 2);
///   a, d   → v0 = 2/(1 + √(1 − 2k)), k = 1/a + 1/d (exists iff k ≤ 1/2), t1 = v0/a, t2 = 1 − v0/d.
/// Errors (location: the member): NotFinite for a non-finite value; InvalidArgument for a value
/// outside its range, fewer or more than two members set (naming the first one too many, or
/// none when too few), or a pair with no profile (t1 > t2 or outside [0, 1] would follow; the
/// message gives the admissible range of the member named, the second of the pair in the order
/// t1, t2, v0, acceleration, deceleration).
template <Real T>
[[nodiscard]] Expected<ConstantAccelerationEase<T>> solve_constant_acceleration(const ConstantAccelerationParams<T>& p);

/// Figure 3.16 with the distance free: the member left unset follows from a·t1 = d·(1 − t2)
/// (t2 = 1 − a·t1/d, t1 = d·(1 − t2)/a, a = d·(1 − t2)/t1 or d = a·t1/(1 − t2)), and the distance
/// from Eq. 3.21.  Every phase has positive length (finite accelerations need t1 > 0 and t2 < 1).
/// Errors (location: the member): NotFinite; InvalidArgument for a value out of range, other than
/// exactly three set (naming the fourth when all four are set), or t1 > t2 following (naming the
/// member that was solved for, or t2 when it was given).
template <Real T>
[[nodiscard]] Expected<ConstantAccelerationGraph<T>> solve_equal_areas(const EqualAreasParams<T>& p);

/// The graph of a built ease (distance 1): acceleration v0/t1 and deceleration v0/(1 − t2), +∞ for
/// a phase of zero length (the velocity jumps there).
template <Real T>
[[nodiscard]] ConstantAccelerationGraph<T> graph_of(const ConstantAccelerationEase<T>& ease) noexcept;

}  // namespace inbetween
