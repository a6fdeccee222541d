"""Measure the lattice tables of Blender's original noise basis through Blender itself.

    blender -b --python tools/blender/measure_noise_tables.py -- -o src/math/blender_noise_tables.inc

Blender's "BLENDER" noise basis (orgBlenderNoise) is gradient noise on the integer lattice: the
gradient at lattice point (X, Y, Z) is looked up through a 256-periodic hash of (X & 255, Y & 255,
Z & 255), with Z the outermost level.  This script never reads Blender's source tables.  It
evaluates `mathutils.noise.noise(p, noise_basis='BLENDER')`, which is r = float32(2n − 1) with
n = orgBlenderNoise(p + 1) (the +1 in float32; r is exact for n ≥ 1/4 and rounded to 2^-24 below,
so comparisons with a model are made on r, never on n), on lattice lines, where the noise is a
known polynomial of one offset and two gradient components:

  on the line x = X, y = Y (integers), z = Z + t:
      n = 0.5 + w0(t)·g_z(X, Y, Z) + w1(t)·g_z(X, Y, Z + 1),
      w0(t) = (1 − 3t² + 2t³)·t,   w1(t) = (1 − 3(t−1)² − 2(t−1)³)·(t − 1)
  and the same with x or y along the line.

It recovers an equivalent factorisation of the lattice, gradient(X, Y, Z) =
GRAD[(Z + OUTER[(INNER[X] + Y) & 255]) & 255], in three steps:

1. Labels.  Along z, at t = 1/2 the noise is 0.5 + (g_z(Z) − g_z(Z + 1))/4.  The reference line
   (X, Y) = (0, 0) gives R[Z] = n(0, 0, Z + 1/2); every other line (X, Y) must show the same values
   cyclically shifted by some a(X, Y): n(X, Y, Z + 1/2) == R[(a + Z) & 255], bit for bit.  The shift
   is found by exact matching of a few values and then checked on whole lines.  The gradient at
   (0, 0, k) is given label k; then label(X, Y, Z) = (Z + a(X, Y)) & 255.  The 65 536 shifts
   factor as a(X, Y) = OUTER[(INNER[X] + Y) & 255] with INNER[0] = 0 (checked for every X, Y).
2. Values.  Every edge of lines along x, y and z at many offsets t gives one linear equation in
   the components of two labelled gradients; least squares over all of them gives the 768
   components to ~1e-8.  Blender's gradient components are decimals with six places, so they are
   rounded to 1e-6 (the script checks every residual is far below 5e-7) and written as those
   decimals.  Each edge equation is also an exact float32 computation: the script checks that the
   tables reproduce all of them bit for bit (and would try neighbouring decimals where not).
3. Check.  The script re-evaluates the noise at random points with a float32 model of the
   algorithm and the measured tables and reports mismatches against Blender (the C++ test does the
   same at 2 000 recorded points with the library's implementation).

These are not Blender's literal tables (Blender uses one 512-entry hash at all three levels and
its gradient table indexed by that hash), but they define the same function on the whole lattice.
"""

import argparse
import sys

import numpy as np
import mathutils.noise as mn


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", required=True, help="the .inc file to write")
    return parser.parse_args(argv)


def raw_noise(x, y, z):
    """Blender's 2·orgBlenderNoise(x, y, z) − 1, rounded to float32 as mathutils returns it."""
    # mathutils adds 1 to every coordinate for this basis and returns 2n − 1 in float32.
    return mn.noise((float(x) - 1.0, float(y) - 1.0, float(z) - 1.0), noise_basis='BLENDER')


def org_noise(x, y, z):
    """orgBlenderNoise(x, y, z) from Blender: exact for n ≥ 1/4, within 2^-25 below."""
    return (raw_noise(x, y, z) + 1.0) / 2.0


def to_raw(n):
    """What mathutils makes of a float32 noise value n: float32(2n − 1)."""
    f32 = np.float32
    return (f32(2) * np.asarray(n, dtype=f32) - f32(1)).astype(np.float64)


def shifted(values, a):
    return values[a:] + values[:a]


def weights(t):
    w0 = (1.0 - 3.0 * t * t + 2.0 * t * t * t) * t
    j = t - 1.0
    w1 = (1.0 - 3.0 * j * j - 2.0 * j * j * j) * j
    return w0, w1


def main():
    args = parse_args()

    # 1. Labels -------------------------------------------------------------------------------
    R = [org_noise(0, 0, z + 0.5) for z in range(256)]
    probe = 6  # values matched per line; uniqueness of every cyclic probe-tuple is checked
    tuples = {}
    for a in range(256):
        key = tuple(shifted(R, a)[:probe])
        if key in tuples:
            sys.exit(f"reference line: cyclic {probe}-tuples are not unique (labels {tuples[key]}, {a})")
        tuples[key] = a
    shift = np.zeros((256, 256), dtype=np.int64)  # shift[X, Y]
    for X in range(256):
        for Y in range(256):
            key = tuple(org_noise(X, Y, z + 0.5) for z in range(probe))
            if key not in tuples:
                sys.exit(f"line ({X}, {Y}) is not a shifted copy of the reference line")
            shift[X, Y] = tuples[key]
    # Whole lines: one (X, Y) per shift value, and a few more, all 256 values bit for bit.
    checked = {}
    for X in range(256):
        for Y in range(256):
            checked.setdefault(int(shift[X, Y]), (X, Y))
    rng = np.random.default_rng(23)
    extra = [(int(rng.integers(256)), int(rng.integers(256))) for _ in range(256)]
    for X, Y in list(checked.values()) + extra:
        line = [org_noise(X, Y, z + 0.5) for z in range(256)]
        if line != shifted(R, int(shift[X, Y])):
            sys.exit(f"line ({X}, {Y}) differs from the reference shifted by {shift[X, Y]}")
    outer = [int(shift[0, Y]) for Y in range(256)]
    inner = []
    for X in range(256):
        row = [int(shift[X, Y]) for Y in range(256)]
        found = [s for s in range(256) if all(outer[(s + Y) & 255] == row[Y] for Y in range(256))]
        if len(found) != 1:
            sys.exit(f"row X={X}: {len(found)} inner shifts reproduce it")
        inner.append(found[0])

    def label(X, Y, Z):
        return (Z + outer[(inner[X & 255] + (Y & 255)) & 255]) & 255

    # 2. Values -------------------------------------------------------------------------------
    ts = [k / 32.0 for k in range(1, 32)]
    rows, cols, vals, rhs, t_index = [], [], [], [], []
    eq = 0
    lines_per_axis = 6
    for axis in range(3):
        for line in range(lines_per_axis):
            # a line along `axis` through fixed values of the other two coordinates
            u, v = line * 37 % 256, line * 101 % 256
            for s in range(256):
                for ti, t in enumerate(ts):
                    p = [0, 0, 0]
                    q = [0, 0, 0]
                    others = [c for c in range(3) if c != axis]
                    p[others[0]], p[others[1]] = u, v
                    q[others[0]], q[others[1]] = u, v
                    p[axis], q[axis] = s, s + 1
                    point = list(p)
                    point[axis] = s + t
                    n = org_noise(*point)
                    w0, w1 = weights(t)
                    rows += [eq, eq]
                    cols += [3 * label(*p) + axis, 3 * label(*q) + axis]
                    vals += [w0, w1]
                    rhs.append(n - 0.5)
                    t_index.append(ti)
                    eq += 1
    # Normal equations, accumulated (each equation has two non-zeros).
    rows, cols, vals, rhs = np.array(rows), np.array(cols), np.array(vals), np.array(rhs)
    AtA = np.zeros((768, 768))
    Atb = np.zeros(768)
    r0, r1 = rows[0::2], rows[1::2]
    c0, c1 = cols[0::2], cols[1::2]
    v0, v1 = vals[0::2], vals[1::2]
    np.add.at(AtA, (c0, c0), v0 * v0)
    np.add.at(AtA, (c1, c1), v1 * v1)
    np.add.at(AtA, (c0, c1), v0 * v1)
    np.add.at(AtA, (c1, c0), v0 * v1)
    np.add.at(Atb, c0, v0 * rhs[r0])
    np.add.at(Atb, c1, v1 * rhs[r1])
    solution = np.linalg.solve(AtA, Atb)
    scaled = solution * 1e6
    rounded = np.rint(scaled)
    worst = float(np.max(np.abs(scaled - rounded)))
    print(f"least squares over {eq} equations: worst distance from a 6-place decimal "
          f"{worst * 1e-6:.2e}")
    if worst > 0.2:
        sys.exit("gradient components are not 6-place decimals within the measurement error")
    micro = rounded.astype(np.int64)

    # Exact refinement: every edge equation is also an exact float32 computation; a component
    # rounded to the wrong decimal shows as mismatches in the equations that use it.
    f32 = np.float32
    tt = np.array(ts, dtype=np.float32)[np.array(t_index)]
    c0, c1 = cols[0::2], cols[1::2]
    measured = to_raw(rhs + 0.5)  # rhs + 0.5 is (r + 1) / 2: back to r exactly

    def edge_model(micro_values):
        g = (micro_values.astype(np.float64) / 1e6).astype(np.float32)
        o = tt
        j = (o - f32(1)).astype(np.float32)
        s0 = (o * o).astype(np.float32)
        w0 = ((f32(1) - f32(3) * s0).astype(np.float32) + ((f32(2) * s0).astype(np.float32) * o)
              .astype(np.float32)).astype(np.float32)
        s1 = (j * j).astype(np.float32)
        w1 = ((f32(1) - f32(3) * s1).astype(np.float32) - ((f32(2) * s1).astype(np.float32) * j)
              .astype(np.float32)).astype(np.float32)
        n = (f32(0.5) + (w0 * (g[c0] * o).astype(np.float32)).astype(np.float32)).astype(np.float32)
        n = (n + (w1 * (g[c1] * j).astype(np.float32)).astype(np.float32)).astype(np.float32)
        return to_raw(n)

    def bad_per_component(micro_values):
        bad = edge_model(micro_values) != measured
        count = np.zeros(768, dtype=np.int64)
        np.add.at(count, c0[bad], 1)
        np.add.at(count, c1[bad], 1)
        return int(bad.sum()), count

    total, count = bad_per_component(micro)
    print(f"edge equations reproduced exactly: {eq - total} of {eq}")
    for component in np.argsort(-count):
        if count[component] == 0:
            break
        best = (count[component], micro[component])
        for delta in (-3, -2, -1, 1, 2, 3):
            trial = micro.copy()
            trial[component] += delta
            _, trial_count = bad_per_component(trial)
            if trial_count[component] < best[0]:
                best = (trial_count[component], trial[component])
        micro[component] = best[1]
    total, count = bad_per_component(micro)
    print(f"after refinement: {eq - total} of {eq} edge equations exact")
    if total:
        sys.exit("some edge equations are not reproduced exactly: the tables are not Blender's")
    grad = micro.reshape(256, 3)

    # 3. Check --------------------------------------------------------------------------------
    f32 = np.float32
    G = (grad.astype(np.float64) / 1e6).astype(np.float32)

    def model(x, y, z):
        x, y, z = f32(x), f32(y), f32(z)
        fx, fy, fz = np.floor(x), np.floor(y), np.floor(z)
        ox, oy, oz = f32(x - fx), f32(y - fy), f32(z - fz)
        ix, iy, iz = int(fx), int(fy), int(fz)
        jx, jy, jz = f32(ox - f32(1)), f32(oy - f32(1)), f32(oz - f32(1))
        one, three, two = f32(1), f32(3), f32(2)

        def c_lo(o):
            s = f32(o * o)
            return f32(f32(one - f32(three * s)) + f32(f32(two * s) * o))

        def c_hi(j):
            s = f32(j * j)
            return f32(f32(one - f32(three * s)) - f32(f32(two * s) * j))

        cx = (c_lo(ox), c_hi(jx))
        cy = (c_lo(oy), c_hi(jy))
        cz = (c_lo(oz), c_hi(jz))
        dx, dy, dz = (ox, jx), (oy, jy), (oz, jz)
        n = f32(0.5)
        for a in range(2):
            for b in range(2):
                for c in range(2):
                    w = f32(f32(cx[a] * cy[b]) * cz[c])
                    g = G[label(ix + a, iy + b, iz + c)]
                    dot = f32(f32(f32(g[0] * dx[a]) + f32(g[1] * dy[b])) + f32(g[2] * dz[c]))
                    n = f32(n + f32(w * dot))
        return min(max(n, f32(0)), f32(1))

    mismatches = 0
    for _ in range(2000):
        # the argument of mathutils.noise.noise, and the point orgBlenderNoise sees (+1 in float32)
        q = [f32(rng.uniform(-300, 300)) for _ in range(3)]
        p = [f32(c + f32(1)) for c in q]
        blender = mn.noise([float(c) for c in q], noise_basis='BLENDER')
        if float(to_raw(model(*p))) != blender:
            mismatches += 1
            if mismatches < 6:
                print("mismatch at", [float(c) for c in q], float(to_raw(model(*p))), blender)
    print(f"float32 model with the measured tables: {mismatches} of 2000 random points differ")
    if mismatches:
        sys.exit("the measured tables do not reproduce Blender's noise")

    with open(args.output, "w") as out:
        out.write("// Generated by tools/blender/measure_noise_tables.py from Blender "
                  f"{blender_version()}: do not edit.\n")
        out.write("// Regenerate: blender -b --python tools/blender/measure_noise_tables.py -- "
                  "-o src/math/blender_noise_tables.inc\n")
        out.write("// Measured through mathutils.noise.noise(..., noise_basis='BLENDER'), not copied "
                  "from Blender's\n// source (docs/blender-noise.md).  gradient(X, Y, Z) = "
                  "kGradient[(Z + kOuter[(kInner[X] + Y) & 255]) & 255]\n// (X, Y, Z taken & 255); "
                  "an equivalent factorisation of Blender's lattice, not its literal tables.\n")
        out.write(f"// Check at measurement time: {mismatches} of 2000 random points differ from Blender.\n\n")
        for name, table in (("kInner", inner), ("kOuter", outer)):
            out.write(f"constexpr std::uint8_t {name}[256] = {{\n")
            for k in range(0, 256, 16):
                out.write("    " + ", ".join(f"{v:3d}" for v in table[k:k + 16]) + ",\n")
            out.write("};\n\n")
        out.write("constexpr float kGradient[256][3] = {\n")
        for k in range(256):
            out.write("    {" + ", ".join(fmt_decimal(int(v)) for v in grad[k]) + "},\n")
        out.write("};\n")
    print(f"wrote {args.output}")


def fmt_decimal(micro):
    sign = "-" if micro < 0 else ""
    micro = abs(micro)
    return f"{sign}{micro // 1000000}.{micro % 1000000:06d}f"


def blender_version():
    import bpy
    return bpy.app.version_string


if __name__ == "__main__":
    main()
