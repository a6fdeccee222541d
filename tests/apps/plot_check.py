#!/usr/bin/env python3
"""The plot test: `inbetween plot` draws the baked values, and its tick labels say where they are.

For every input (scene files, glTF files) it runs `inbetween plot INPUT -o DIR`, reads the sampled
grid from DIR/index.html (<meta name="inbetween-grid" content="START STEP COUNT FPS">), bakes the
same grid with `inbetween bake --frames A:B:STEP --format csv` (the same frames in the same order,
so also the sign-continuous rotations agree), and parses every SVG with xml.etree:

- per panel (<g class="panel">), the axis transform pixel = p0 + k·value is recovered from the tick
  marks and their *labels* (<g class="tick-x|tick-y">: <line> position, <text> label); every tick
  must lie on it, and the seconds ticks on top (tick-x2) must sit at label·fps frames — so a wrong
  tick label fails;
- every <polyline class="data"> and <circle class="data"> is mapped back through that transform and
  compared with the baked values at its frames (data-frames / data-frame): x is the frame (or a
  column, path views), y a column, angle_deg(PREFIX) (2·atan2(|xyz|, w) of the quaternion columns,
  in degrees) or derivative(COLUMN) (d/dt of the column, checked against the central difference of
  the baked column on the grid, where both neighbours are in the same piece).  Orientation markers of
  path views (<line class="frame-axis">) must start at the baked position and end data-length along the
  baked rotation of their axis; bones of trajectory plots (<line class="bone">) must join the baked
  positions of their parent (columns data-x1, data-y1) and child (data-x2, data-y2).

Frames that are not grid frames (key frames, ease phase boundaries) are baked alone with
--frames F:F (only track, distance and speed columns are drawn there; they do not depend on the
sequence).

Tolerance (named, from the digits written): coordinates are written with the shortest text that
reads back to the same double (std::to_chars), so the written pixel is the computed one; computing
it (left + (x − x0)/(x1 − x0)·width, values ≤ 2000 px) and inverting it here costs a few roundings of
2000·2⁻⁵³ ≈ 4.4e-13 px each.  PIXEL_TOL = 1e-9 px is 2000 times that and far below anything visible.
Derivatives: the central difference of the baked speed, D = v' + h^2/6 v''' + O(h^4), with v'''
estimated by the third difference of the baked speed on the grid: the tolerance is twice that
truncation estimate plus DERIVATIVE_REL_TOL = 1e-6 of the panel's value span for rounding
(constant-acceleration and cubic eases have speeds at most quadratic within a piece, where the
difference is exact up to rounding).

--self-test also perturbs a plot (one point by 0.01 px, one tick label, one data frame) and checks
that each perturbation is caught.
"""

import argparse
import csv
import io
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET

SVG = "{http://www.w3.org/2000/svg}"
PIXEL_TOL = 1e-9          # pixels; see the module docstring
DERIVATIVE_REL_TOL = 1e-6  # of the panel's value span


class Baker:
    """Baked values of one input: the grid in one bake, other frames one bake each (cached)."""

    def __init__(self, cli, input_path, extra_args, grid):
        self.cli, self.input, self.extra = cli, input_path, extra_args
        self.start, self.step, self.count, self.fps = grid
        end = self.start + (self.count - 1) * self.step
        self.columns, rows = self._bake(f"{self.start!r}:{end!r}:{self.step!r}")
        if len(rows) != self.count:
            raise AssertionError(f"bake gave {len(rows)} rows for the {self.count} grid frames")
        self.grid_rows = rows
        self.single = {}
        self.single_precision = single_precision_columns(input_path)

    def _bake(self, frames):
        cmd = [self.cli, "bake", self.input, "--frames", frames, "--format", "csv", "--progress", "never"] + self.extra
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise AssertionError(f"{' '.join(cmd)} failed: {r.stderr}")
        table = list(csv.reader(io.StringIO(r.stdout)))
        header = table[0]
        return {name: i for i, name in enumerate(header)}, [[float(v) for v in row] for row in table[1:]]

    def grid_index(self, frame):
        i = round((frame - self.start) / self.step)
        if 0 <= i < self.count and self.start + float(i) * self.step == frame:
            return i
        return None

    def row(self, frame):
        i = self.grid_index(frame)
        if i is not None:
            return self.grid_rows[i]
        if frame not in self.single:
            _, rows = self._bake(f"{frame!r}:{frame!r}")
            self.single[frame] = rows[0]
        return self.single[frame]

    def value(self, expr, frame, row=None):
        row = row if row is not None else self.row(frame)
        if expr == "frame":
            return frame
        m = re.fullmatch(r"angle_deg\((.+)\)", expr)
        if m:
            p = m.group(1)
            w, x, y, z = (row[self.columns[f"{p}.{c}"]] for c in "wxyz")
            return 2 * math.atan2(math.sqrt(x * x + y * y + z * z), w) * 180 / math.pi
        if expr not in self.columns:
            raise AssertionError(f"no baked column {expr!r}")
        v = row[self.columns[expr]]
        # A single-precision column is written as the shortest text of its float: the value drawn
        # is that float, which is the float nearest to the text.
        return struct.unpack("f", struct.pack("f", v))[0] if expr in self.single_precision else v


def single_precision_columns(input_path):
    """Columns of F-curve tracks (scene kind "scalar", the default): bake writes them as floats.
    glTF files have none (their scalars are vec1 tracks, double)."""
    if not input_path.endswith(".json"):
        return set()
    with open(input_path, encoding="utf-8") as f:
        scene = json.load(f)
    return {t["name"] for t in scene.get("tracks", []) if t.get("kind", "scalar") == "scalar"}


def fit_axis(ticks, what):
    """pixel = p0 + k·value from (pixel, label) pairs; every tick must lie on it."""
    if len(ticks) < 2:
        raise AssertionError(f"{what}: fewer than two ticks")
    (pa, va), (pb, vb) = ticks[0], ticks[-1]
    if va == vb:
        raise AssertionError(f"{what}: the first and last ticks are both labelled {va!r}")
    k = (pb - pa) / (vb - va)
    p0 = pa - k * va
    for p, v in ticks:
        if abs(p0 + k * v - p) > PIXEL_TOL:
            raise AssertionError(f"{what}: tick labelled {v!r} is at pixel {p!r}, the other ticks put it at {p0 + k * v!r}")
    return p0, k


def ticks_of(panel, cls, coord):
    out = []
    for g in panel.iter(SVG + "g"):
        if g.get("class") != cls:
            continue
        line, text = g.find(SVG + "line"), g.find(SVG + "text")
        out.append((float(line.get(coord)), float(text.text)))
    return out


def check_svg(path, baker):
    """Checks one SVG; returns (points checked, list of failures)."""
    failures, checked = [], 0
    root = ET.parse(path).getroot()
    panels = [g for g in root.iter(SVG + "g") if g.get("class") == "panel"]
    if not panels:
        return 0, [f"{path}: no panel"]
    for n, panel in enumerate(panels):
        where = f"{os.path.basename(path)} panel {n}"
        try:
            x0, kx = fit_axis(ticks_of(panel, "tick-x", "x1"), where + " x axis")
            y0, ky = fit_axis(ticks_of(panel, "tick-y", "y1"), where + " y axis")
            for p, seconds in ticks_of(panel, "tick-x2", "x1"):
                f = seconds * baker.fps
                if abs(x0 + kx * f - p) > PIXEL_TOL:
                    raise AssertionError(f"{where}: seconds tick {seconds!r} at pixel {p!r}, frame {f!r} is at {x0 + kx * f!r}")
        except AssertionError as e:
            failures.append(str(e))
            continue
        tol_x, tol_y = PIXEL_TOL / abs(kx), PIXEL_TOL / abs(ky)
        y_span = abs((panel_height(panel)) / ky)
        for el in panel.iter():
            cls = (el.get("class") or "").split()
            if "frame-axis" in cls:
                checked += 1
                failures += check_frame_axis(el, where, baker, (x0, kx), (y0, ky))
                continue
            if "bone" in cls:
                checked += 1
                failures += check_bone(el, where, baker, (x0, kx), (y0, ky))
                continue
            if "data" not in cls:
                continue
            dx, dy = el.get("data-x"), el.get("data-y")
            if el.tag == SVG + "polyline":
                frames = [float(f) for f in el.get("data-frames").split()]
                pts = [tuple(float(c) for c in p.split(",")) for p in el.get("points").split()]
            elif el.tag == SVG + "circle":
                frames = [float(el.get("data-frame"))]
                pts = [(float(el.get("cx")), float(el.get("cy")))]
            else:
                continue
            if len(frames) != len(pts):
                failures.append(f"{where}: {dy}: {len(pts)} points but {len(frames)} frames")
                continue
            for j, (f, (px, py)) in enumerate(zip(frames, pts)):
                vx, vy = (px - x0) / kx, (py - y0) / ky
                m = re.fullmatch(r"derivative\((.+)\)", dy)
                if m:
                    i = baker.grid_index(f)
                    if i is None or j < 2 or j + 2 >= len(frames):
                        continue
                    if any(baker.grid_index(frames[j + d]) != i + d for d in (-2, -1, 1, 2)):
                        continue  # the central differences need i ± 2 inside the same piece
                    col = m.group(1)
                    v = [baker.value(col, 0, baker.grid_rows[i + d]) for d in (-2, -1, 0, 1, 2)]
                    h = baker.step / baker.fps  # seconds
                    want_y = (v[3] - v[1]) / (2 * h)
                    # Central difference: D = v' + h^2/6 v''' + O(h^4); v''' from the third difference
                    # (v[i+2] - 2 v[i+1] + 2 v[i-1] - v[i-2]) / (2 h^3), so the error is about
                    # |third difference| / (12 h).  Twice that, plus DERIVATIVE_REL_TOL of the span for
                    # rounding (for speeds at most quadratic the third difference is rounding only).
                    truncation = abs(v[4] - 2 * v[3] + 2 * v[1] - v[0]) / (12 * h)
                    tol = 2 * truncation + DERIVATIVE_REL_TOL * y_span
                else:
                    want_y = baker.value(dy, f)
                    tol = tol_y
                want_x = baker.value(dx, f)
                checked += 1
                if abs(vx - want_x) > tol_x:
                    failures.append(f"{where}: {dy} point {j}: x reads {vx!r}, baked {dx} at frame {f!r} is {want_x!r}")
                if abs(vy - want_y) > tol:
                    failures.append(f"{where}: {dy} point {j} (frame {f!r}): y reads {vy!r}, baked value {want_y!r} "
                                    f"(off by {abs(vy - want_y):.3g}, tolerance {tol:.3g})")
    return checked, failures


def rotate(q, v):
    """v rotated by the unit quaternion q = (w, x, y, z): v + 2w(u × v) + 2u × (u × v)."""
    w, ux, uy, uz = q
    cx, cy, cz = uy * v[2] - uz * v[1], uz * v[0] - ux * v[2], ux * v[1] - uy * v[0]
    dx, dy, dz = uy * cz - uz * cy, uz * cx - ux * cz, ux * cy - uy * cx
    return (v[0] + 2 * (w * cx + dx), v[1] + 2 * (w * cy + dy), v[2] + 2 * (w * cz + dz))


def check_bone(el, where, baker, xmap, ymap):
    """A bone of a trajectory plot's pose: from the parent's baked position (columns data-x1,
    data-y1) to the child's (data-x2, data-y2) at data-frame."""
    f = float(el.get("data-frame"))
    row = baker.row(f)
    out = []
    for end in ("1", "2"):
        wx, wy = baker.value(el.get("data-x" + end), f, row), baker.value(el.get("data-y" + end), f, row)
        ex, ey = xmap[0] + xmap[1] * wx, ymap[0] + ymap[1] * wy
        px, py = float(el.get("x" + end)), float(el.get("y" + end))
        if abs(ex - px) > PIXEL_TOL or abs(ey - py) > PIXEL_TOL:
            out.append(f"{where}: bone {el.get('data-parent')}-{el.get('data-child')} at frame {f!r}: end {end} drawn at "
                       f"({px!r}, {py!r}), baked positions put it at ({ex!r}, {ey!r})")
    return out


def check_frame_axis(el, where, baker, xmap, ymap):
    """An orientation marker of a path view: from the baked position along data-length times the
    baked rotation of the object's axis (x, y or z), projected on the view's two axes."""
    f = float(el.get("data-frame"))
    row = baker.row(f)
    dx, dy = el.get("data-x"), el.get("data-y")
    q = [baker.value(f"{el.get('data-rotation')}.{c}", f, row) for c in "wxyz"]
    n = math.sqrt(sum(c * c for c in q))
    axis = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}[el.get("data-axis")]
    tip = rotate([c / n for c in q], axis)
    length = float(el.get("data-length"))
    comp = {"x": 0, "y": 1, "z": 2}
    want = [(baker.value(dx, f, row), baker.value(dy, f, row))]
    want.append((want[0][0] + length * tip[comp[dx[-1]]], want[0][1] + length * tip[comp[dy[-1]]]))
    got = [(float(el.get("x1")), float(el.get("y1"))), (float(el.get("x2")), float(el.get("y2")))]
    out = []
    for (wx, wy), (px, py), end in zip(want, got, ("start", "tip")):
        ex, ey = xmap[0] + xmap[1] * wx, ymap[0] + ymap[1] * wy
        # The tip goes through one more rotation and addition than the position: a few more
        # roundings of the same size, still far inside PIXEL_TOL.
        if abs(ex - px) > PIXEL_TOL or abs(ey - py) > PIXEL_TOL:
            out.append(f"{where}: frame axis {el.get('data-axis')} at frame {f!r}: {end} drawn at ({px!r}, {py!r}), "
                       f"baked rotation puts it at ({ex!r}, {ey!r})")
    return out


def panel_height(panel):
    for el in panel.iter(SVG + "rect"):
        if el.get("class") == "frame":
            return float(el.get("height"))
    return 0.0


def read_grid(index_html):
    with open(index_html, encoding="utf-8") as f:
        m = re.search(r'<meta name="inbetween-grid" content="([^"]+)">', f.read())
    start, step, count, fps = m.group(1).split()
    return float(start), float(step), int(count), float(fps)


def plot(cli, input_path, out, extra):
    if os.path.exists(out):
        shutil.rmtree(out)
    cmd = [cli, "plot", input_path, "-o", out, "--progress", "never"] + extra
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise AssertionError(f"{' '.join(cmd)} failed ({r.returncode}): {r.stderr}")


def check_input(cli, input_path, out, extra):
    plot(cli, input_path, out, extra)
    baker = Baker(cli, input_path, extra, read_grid(os.path.join(out, "index.html")))
    svgs = sorted(os.path.join(d, f) for d, _, fs in os.walk(out) for f in fs if f.endswith(".svg"))
    total, failures = 0, []
    for svg in svgs:
        n, fails = check_svg(svg, baker)
        if n == 0:
            fails.append(f"{svg}: no data point checked")
        total += n
        failures += fails
    return svgs, total, failures, baker


def self_test(svg, baker, work):
    """Each perturbation of a good plot must be caught."""
    text = open(svg, encoding="utf-8").read()
    cases = []
    # 1. One point of the first data polyline (or the first data dot) moved by 0.01 px in y.
    m = re.search(r'(<polyline class="data[^"]*"[^>]*points=")([^ "]+),([^ "]+)', text)
    if m:
        cases.append(("a point moved 0.01 px", text[:m.start(3)] + repr(float(m.group(3)) + 0.01) + text[m.end(3):]))
    m = re.search(r'<circle class="data[^>]* cy="([^"]+)"', text)
    if m:
        cases.append(("a dot moved 0.01 px", text[:m.start(1)] + repr(float(m.group(1)) + 0.01) + text[m.end(1):]))
    # 2. One y tick label changed (the line stays): the axis transform no longer fits the labels.
    # A middle tick of the first panel, so the fit (first and last ticks) stays possible.
    m = list(re.finditer(r'<g class="tick-y">\s*<line[^>]*/>\s*<text[^>]*>([^<]+)</text>', text))[1]
    cases.append(("a y tick label changed", text[:m.start(1)] + repr(float(m.group(1)) + 1) + text[m.end(1):]))
    # 3. One frame of a polyline changed (the point now claims its neighbour's frame): at the first
    # point whose drawn position differs from its neighbour's (a trail held before its first key
    # starts with equal points, where a swap cannot show).
    m = re.search(r'<polyline class="data[^"]*"[^>]*data-frames="([^"]+)"[^>]*points="([^"]+)"', text)
    if m:
        frames, points = m.group(1).split(" "), m.group(2).split(" ")
        j = next((j for j in range(1, min(len(frames), len(points))) if points[j] != points[j - 1]), None)
        if j is not None:
            frames[j] = frames[j - 1]
            cases.append(("a data frame swapped", text[:m.start(1)] + " ".join(frames) + text[m.end(1):]))
    # 4. An orientation marker claims another axis of the object (path views only).
    m = re.search(r'class="frame-axis"[^>]*data-axis="(x)"', text)
    if m:
        cases.append(("an orientation axis swapped", text[:m.start(1)] + "y" + text[m.end(1):]))
    # 5. A bone's child end moved 0.01 px (trajectory plots with poses only).
    m = re.search(r'<line class="bone"[^>]* y2="([^"]+)"', text)
    if m:
        cases.append(("a bone end moved 0.01 px", text[:m.start(1)] + repr(float(m.group(1)) + 0.01) + text[m.end(1):]))
    ok = True
    for name, bad in cases:
        path = os.path.join(work, "perturbed.svg")
        with open(path, "w", encoding="utf-8") as f:
            f.write(bad)
        _, failures = check_svg(path, baker)
        print(f"self-test: {name}: {'caught' if failures else 'NOT CAUGHT'}" + (f" ({failures[0]})" if failures else ""))
        ok &= bool(failures)
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", required=True, help="the inbetween executable")
    ap.add_argument("--work", required=True, help="a scratch folder")
    ap.add_argument("--self-test", action="store_true", help="also check that perturbed plots fail")
    ap.add_argument("--skip-unreadable", action="store_true",
                    help="print SKIPPED and pass when `inbetween bake` cannot read an input (a format not read yet)")
    ap.add_argument("inputs", nargs="+", help="scene or glTF files; INPUT::ARG,ARG passes extra arguments")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    if args.skip_unreadable:
        for spec in args.inputs:
            input_path = spec.partition("::")[0]
            r = subprocess.run([args.cli, "bake", input_path, "--frames", "0:0"], capture_output=True, text=True)
            if r.returncode != 0:
                print(f"SKIPPED: {input_path}: {r.stderr.strip()}")
                return 0
    all_ok = True
    for spec in args.inputs:
        input_path, _, extra = spec.partition("::")
        extra = extra.split(",") if extra else []
        out = os.path.join(args.work, os.path.basename(input_path) + ".plots")
        svgs, total, failures, baker = check_input(args.cli, input_path, out, extra)
        print(f"{input_path}: {len(svgs)} plots, {total} drawn points equal the baked values; "
              f"{len(baker.single)} extra single-frame bakes; {len(failures)} failures")
        for f in failures[:20]:
            print("  FAIL " + f)
        all_ok &= not failures and len(svgs) > 0
        if args.self_test and svgs:
            target = next((s for s in svgs if "/tracks/" in s), svgs[0])
            all_ok &= self_test(target, baker, args.work)
            views = next((s for s in svgs if s.endswith("-views.svg")), None)
            if views:
                all_ok &= self_test(views, baker, args.work)
            trajectory = next((s for s in svgs if "/trajectories/" in s), None)
            if trajectory:
                all_ok &= self_test(trajectory, baker, args.work)
    print("plot test " + ("passed" if all_ok else "FAILED"))
    return 0 if all_ok else 1


if __name__ == "__main__":
    sys.exit(main())
