#!/usr/bin/python3
"""Minimax coefficients for inbetween's fast_slerp weights (include/inbetween/math/orientation_interp.hpp).

After the half-angle step the weights are s*g(s, phi)/(2 cos phi) with s = 2(1-u) or 2u in [0, 2],
phi = theta/2 in [0, pi/4] and g = sin(s phi)/(s sin phi).  Eberly (2011, "A fast and accurate
algorithm for computing SLERP", Journal of Graphics, GPU, and Game Tools 15(3)) writes
g = 1 + b1(1 + b2(1 + ...)) with b_i = (s^2/(i(2i+1)) - i/(2i+1)) y, y = cos phi - 1, and tunes the
last term's coefficients (u_n, v_n) by minimax.  Here the first m-1 terms keep his exact u_i, v_i and
the innermost factor R = 1 + y P(s^2, y) replaces the whole tail, with P a small polynomial whose
coefficients minimise max |g - g_approx| over a grid (a linear program: g_approx is affine in P's
coefficients).  g is computed in long double (x86 80-bit), the LP in double on the scaled residual.

Usage: tools/slerp/fit_slerp_weights.py [--quarter] [m basis]  (prints the C++ constants and the max truncation error on
a finer grid than the fit's).  Needs Debian's python3-numpy and python3-scipy.
"""
import sys
import numpy as np
from scipy.optimize import linprog

LD = np.longdouble
# Argument reduction: with --quarter two half-angle steps (phi = theta/4 <= pi/8, s = 4u in [0, 4]),
# else one (phi = theta/2 <= pi/4, s = 2u in [0, 2]); theta <= pi/2 on the shortest arc.
QUARTER = "--quarter" in sys.argv
if QUARTER:
    sys.argv.remove("--quarter")
PHI_MAX = LD(np.pi) / (8 if QUARTER else 4)
S_MAX = LD(4 if QUARTER else 2)


def grid(ns, nphi):
    s = np.linspace(LD(0), S_MAX, ns, dtype=LD)
    # phi denser near pi/4 (largest |y|, where the truncation error lives) and near 0
    t = np.linspace(LD(0), LD(1), nphi, dtype=LD)
    phi = PHI_MAX * (LD(1) - np.cos(t * LD(np.pi)) ) / 2
    phi = phi[phi > 0]
    S, P = np.meshgrid(s, phi)
    return S.ravel(), P.ravel()


def exact(S, P):
    g = np.empty_like(S)
    z = S == 0
    g[z] = P[z] / np.sin(P[z])
    g[~z] = np.sin(S[~z] * P[~z]) / (S[~z] * np.sin(P[~z]))
    return g


BASES = {  # P(s2, y) terms as (power of s2, power of y)
    "2": [(0, 0), (1, 0)],                      # Eberly's own form: (u s^2 - v)
    "4": [(0, 0), (1, 0), (0, 1), (1, 1)],
    "5": [(0, 0), (1, 0), (0, 1), (1, 1), (2, 1)],
}


def affine(S, P, m):
    """g_approx = A + B*R for the nest 1 + b1(1 + ... (1 + b_{m-1} R))."""
    y = np.cos(P) - 1
    s2 = S * S
    A = np.ones_like(S) * 0  # nest with R as a symbol: value = A + B R
    B = np.ones_like(S)
    for i in range(m - 1, 0, -1):
        b = (s2 / LD(i * (2 * i + 1)) - LD(i) / LD(2 * i + 1)) * y
        A, B = 1 + b * A, b * B
    return A, B, y, s2


def fit(m, basis, ns=81, nphi=81):
    S, P = grid(ns, nphi)
    A, B, y, s2 = affine(S, P, m)
    g = exact(S, P)
    r = g - (A + B)  # what B*y*P must supply
    cols = np.stack([B * y * s2**a * y**b for a, b in BASES[basis]], axis=1)
    scale = 1 / np.max(np.abs(r))
    M = (cols * scale).astype(np.float64)
    rr = (r * scale).astype(np.float64)
    k = M.shape[1]
    # minimise t subject to -t <= M c - r <= t
    c_obj = np.zeros(k + 1); c_obj[-1] = 1
    A_ub = np.block([[M, -np.ones((len(rr), 1))], [-M, -np.ones((len(rr), 1))]])
    b_ub = np.concatenate([rr, -rr])
    res = linprog(c_obj, A_ub=A_ub, b_ub=b_ub, bounds=[(None, None)] * (k + 1), method="highs")
    assert res.status == 0, res.message
    return res.x[:k]


def check(m, basis, c, ns=401, nphi=401):
    S, P = grid(ns, nphi)
    A, B, y, s2 = affine(S, P, m)
    Pv = sum(LD(ci) * s2**a * y**b for ci, (a, b) in zip(c, BASES[basis]))
    approx = A + B * (1 + y * Pv)
    return float(np.max(np.abs(approx - exact(S, P))))


def main():
    configs = [(m, b) for m in range(2, 16) for b in BASES]
    if len(sys.argv) > 1:
        configs = [(int(sys.argv[1]), sys.argv[2])]
    for m, basis in configs:
        c = fit(m, basis)
        err = check(m, basis, c)
        print(f"m={m:2d} (exact terms {m-1}) basis {basis}: max |g - approx| = {err:.3e}  coeffs = "
              + ", ".join(f"{float(x):.17g}" for x in c))


if __name__ == "__main__":
    main()
