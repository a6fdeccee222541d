#!/usr/bin/env python3
"""Unit test of tools/bench/write_results.py on the recorded JSON in tests/data/bench/ (issue 12).

The recorded files are the median aggregates of one real run (release preset, 2-core EPYC, 2026-11-24).
Every expected ratio below is recomputed here from the JSON's own cpu_time fields (independent of the
renderer's code path), and the met/missed cases are perturbed copies of the same data, so a wrong
ratio direction, a wrong target or a wrong comparison makes this fail.  Standard library only.
"""

import copy
import json
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "bench"))
import write_results as wr  # noqa: E402

DATA = ROOT / "tests" / "data" / "bench"


def load_docs():
    return {f.stem: json.loads(f.read_text(encoding="utf-8")) for f in sorted(DATA.glob("inbetween_bench_*.json"))}


def results_of(docs):
    r = wr.Results()
    for name, doc in docs.items():
        r.add_json(name, doc)
    return r


def cpu(docs, program, run_name):
    """The recorded median CPU time in ns, read straight from the JSON."""
    for b in docs[program]["benchmarks"]:
        if b["run_name"] == run_name and b["aggregate_name"] == "median":
            assert b["time_unit"] == "ns", b["time_unit"]
            return b["cpu_time"]
    raise KeyError(run_name)


def set_cpu(docs, program, run_name, ns):
    for b in docs[program]["benchmarks"]:
        if b["run_name"] == run_name:
            b["cpu_time"] = ns


def row(text, first_cell):
    """The cells of the table row whose first cell is first_cell."""
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if cells and cells[0] == first_cell:
            return cells
    raise AssertionError(f"no row {first_cell!r} in\n{text}")


def render(docs):
    return wr.render(results_of(docs), "cmd", "2026-11-24", "1.00, 1.00, 1.00", None)


class RatioArithmetic(unittest.TestCase):
    def setUp(self):
        self.docs = load_docs()
        self.text = render(self.docs)

    def test_slerp_ratio_is_peer_over_ours(self):
        ours = cpu(self.docs, "inbetween_bench_math", "BM_SlerpPeers<double, SlerpSide::Ours>/0")
        glm = cpu(self.docs, "inbetween_bench_math", "BM_SlerpPeers<double, SlerpSide::Glm>/0")
        eig = cpu(self.docs, "inbetween_bench_math", "BM_SlerpPeers<double, SlerpSide::Eigen>/0")
        cells = row(self.text, "double, random")
        self.assertEqual(cells[4], f"{glm / ours:.3g}")
        self.assertEqual(cells[5], f"{eig / ours:.3g}")
        self.assertGreater(glm / ours, 1.0)  # in the recording ours is faster: the ratio must exceed 1

    def test_uofs_ratio_is_ours_over_point(self):
        inv = cpu(self.docs, "inbetween_bench_arclength", "BM_ArcLengthInverse_UofS")
        point = cpu(self.docs, "inbetween_bench_arclength", "BM_CurvePoint")
        cells = row(self.text, "u(s), Chebyshev inverse (`ArcLengthInverse`)")
        self.assertEqual(cells[3], f"{inv / point:.3g}")

    def test_batch_uses_time_per_item(self):
        # BM_BatchCubic_* process 1024 points per iteration: per point = cpu_time / 1024 (up to the
        # items_per_second rounding of the JSON).
        track = cpu(self.docs, "inbetween_bench_curves", "BM_BatchCubic_Track") / 1024
        floor = cpu(self.docs, "inbetween_bench_curves", "BM_BatchCubic_NineFmaFloor") / 1024
        cells = row(self.text, "1024 frames over 16 keys")
        self.assertAlmostEqual(float(cells[3]), track / floor, delta=0.01 * track / floor)

    def test_rig_per_joint_and_budget(self):
        rt = cpu(self.docs, "inbetween_bench_tracks", "BM_RigRuntime<float>/551/2")
        fl = cpu(self.docs, "inbetween_bench_tracks", "BM_RigMemoryFloor<float>/551/2")
        cells = row(self.text, "float, 551 joints")
        self.assertEqual(cells[2], wr.fmt_time(rt / 551))
        self.assertEqual(cells[4], f"{rt / fl:.3g}")
        self.assertEqual(cells[8], f"{100 * rt / 1e6:.2g} %")  # ns / (1 ms = 1e6 ns)
        self.assertEqual(row(self.text, "float, 64 joints")[8], "")  # 64 is no game rig size

    def test_fcurve_ratio_against_float_linear_rig(self):
        fc = cpu(self.docs, "inbetween_bench_tracks", "BM_RigFCurveRuntime/71/2")
        lin = cpu(self.docs, "inbetween_bench_tracks", "BM_RigRuntime<float>/71/2")
        self.assertEqual(row(self.text, "71 joints")[3], f"{fc / lin:.3g}")


class MetOrMissed(unittest.TestCase):
    def test_slerp_speed_target_flips_when_ours_slows(self):
        docs = load_docs()
        name = "BM_SlerpPeers<float, SlerpSide::Ours>/0"
        glm = cpu(docs, "inbetween_bench_math", "BM_SlerpPeers<float, SlerpSide::Glm>/0")
        eig = cpu(docs, "inbetween_bench_math", "BM_SlerpPeers<float, SlerpSide::Eigen>/0")
        set_cpu(docs, "inbetween_bench_math", name, min(glm, eig) / 1.6)
        self.assertEqual(row(render(docs), "float, random")[6], "met")
        set_cpu(docs, "inbetween_bench_math", name, min(glm, eig) / 1.4)  # 1.4× < 1.5×
        self.assertTrue(row(render(docs), "float, random")[6].startswith("missed"))

    def test_slerp_accuracy_target(self):
        docs = load_docs()
        for b in docs["inbetween_bench_math"]["benchmarks"]:
            if b["run_name"] == "BM_SlerpPeers<double, SlerpSide::Ours>/1":
                b["max_err_rad"] = 1e-3  # worse than glm and Eigen
        self.assertEqual(row(render(docs), "double, nearly identical")[8], "missed")

    def test_at_most_targets(self):
        docs = load_docs()
        point = cpu(docs, "inbetween_bench_arclength", "BM_CurvePoint")
        label = "u(s), Chebyshev inverse (`ArcLengthInverse`)"
        set_cpu(docs, "inbetween_bench_arclength", "BM_ArcLengthInverse_UofS", 2.9 * point)
        self.assertEqual(row(render(docs), label)[4], "met")
        set_cpu(docs, "inbetween_bench_arclength", "BM_ArcLengthInverse_UofS", 3.1 * point)
        self.assertTrue(row(render(docs), label)[4].startswith("missed"))
        fl = cpu(docs, "inbetween_bench_tracks", "BM_RigMemoryFloor<double>/1024/2")
        set_cpu(docs, "inbetween_bench_tracks", "BM_RigRuntime<double>/1024/2", 4 * fl)
        self.assertTrue(row(render(docs), "double, 1024 joints")[5].startswith("missed"))

    def test_missing_benchmark_is_not_met(self):
        docs = load_docs()
        docs["inbetween_bench_curves"]["benchmarks"] = [
            b for b in docs["inbetween_bench_curves"]["benchmarks"] if "HermiteSequential_Boost" not in b["run_name"]]
        self.assertEqual(row(render(docs), "Hermite scalar, 16 points, Track with cursor")[4], "not measured")

    def test_verdict_edges(self):
        self.assertEqual(wr.verdict(1.5, 1.5, True), "met")
        self.assertEqual(wr.verdict(3.0, 3.0, False), "met")
        self.assertEqual(wr.verdict(None, 3.0, False), "not measured")
        self.assertIsNone(wr.ratio(1.0, 0.0))


class RigSimdKernels(unittest.TestCase):
    """rig_simd_section: each library's kernel against the std::experimental::simd kernel (issue 12)."""

    def kernel(self, docs, scalar, kernel, joints):
        return cpu(docs, "inbetween_bench_tracks", f"BM_RigKernel<{scalar}, RigKernel::{kernel}>/{joints}/2")

    def test_ratio_is_std_simd_over_the_library(self):
        docs = load_docs()
        base = self.kernel(docs, "double", "std_simd", 64)
        hwy = self.kernel(docs, "double", "hwy_dynamic", 64)
        xs = self.kernel(docs, "double", "xsimd", 64)
        cells = row(render(docs), "double kernels, 64 joints")
        self.assertEqual(cells[2], wr.fmt_time(base))
        self.assertEqual(cells[3], f"{wr.fmt_time(xs)} ({base / xs:.2f}×)")
        self.assertEqual(cells[5], f"{wr.fmt_time(hwy)} ({base / hwy:.2f}×)")

    def test_adoption_verdict_flips_at_1_3(self):
        docs = load_docs()
        base = self.kernel(docs, "float", "std_simd", 71)
        name = "BM_RigKernel<float, RigKernel::hwy_dynamic>/71/2"
        set_cpu(docs, "inbetween_bench_tracks", name, base / 1.35)
        self.assertEqual(row(render(docs), "float kernels, 71 joints")[-1], "met")
        set_cpu(docs, "inbetween_bench_tracks", name, base / 1.25)
        self.assertTrue(row(render(docs), "float kernels, 71 joints")[-1].startswith("missed"))

    def test_largest_difference_over_the_kernels(self):
        docs = load_docs()
        diffs = [b["max_abs_diff"] for b in docs["inbetween_bench_tracks"]["benchmarks"]
                 if b["run_name"].startswith("BM_RigKernel<float") and b["run_name"].endswith("/551/2")
                 and "max_abs_diff" in b]
        self.assertTrue(diffs)
        self.assertEqual(row(render(docs), "float kernels, 551 joints")[-2], f"{max(diffs):.2g}")

class Splice(unittest.TestCase):
    def test_replaces_only_the_section(self):
        old = f"intro\n{wr.BEGIN}\nold table\n{wr.END}\n## hand-written analysis\nkept\n"
        new = wr.splice(old, f"{wr.BEGIN}\nnew\n{wr.END}\n")
        self.assertEqual(new, f"intro\n{wr.BEGIN}\nnew\n{wr.END}\n## hand-written analysis\nkept\n")

    def test_inserts_at_top_without_markers(self):
        new = wr.splice("# hand-written\n", f"{wr.BEGIN}\nx\n{wr.END}\n")
        self.assertTrue(new.startswith(wr.BEGIN))
        self.assertTrue(new.endswith("# hand-written\n"))

    def test_main_from_recorded_json_keeps_the_analysis(self):
        with tempfile.TemporaryDirectory() as d:
            results = Path(d) / "RESULTS.md"
            results.write_text("# analysis\n", encoding="utf-8")
            args = ["--json-dir", str(DATA), "--results", str(results), "--build-dir", d, "--load", "1.00"]
            self.assertEqual(wr.main(args), 0)
            once = results.read_text(encoding="utf-8")
            self.assertEqual(wr.main(args), 0)  # a second run replaces, it does not stack
            twice = results.read_text(encoding="utf-8")
            self.assertEqual(once, twice)
            self.assertEqual(twice.count(wr.BEGIN), 1)
            self.assertTrue(twice.endswith("# analysis\n"))
            self.assertEqual(sorted(p.name for p in Path(d).iterdir()), ["RESULTS.md"])  # no temp file left


if __name__ == "__main__":
    unittest.main()
