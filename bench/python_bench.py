"""Python against C++ on the same work (issue 14: within 1.5x of the C++ time): 10^6 u(s) queries
and a bake of examples/scenes/frame22.json at 7001 frames, through the inbetween module, next to
bench/python_peer_bench.cpp (Google Benchmark, same inputs) when its binary is given or found.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_bench.py [build/release/bench/inbetween_bench_python_peer]
"""
import json
import pathlib
import subprocess
import sys
import time

import numpy as np

import inbetween

ROOT = pathlib.Path(__file__).resolve().parents[1]
N = 1_000_000


def min_of(f, repeat=15):
    """Fastest wall time of `repeat` runs: on a shared, loaded machine the minimum is the figure
    least disturbed by other processes (the C++ side is taken the same way, over its repetitions)."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times)


def main():
    curve = inbetween.Curve((ROOT / "examples" / "curves" / "catmull-rom-centripetal.json").read_text())
    arc = inbetween.ArcLength(curve)
    s = arc.length * ((np.arange(N, dtype=np.int64) * 7919) % N) / N  # the C++ peer's sequence
    t_us = min_of(lambda: arc.u(s))
    u_out = np.empty_like(s)
    t_us_out = min_of(lambda: arc.u(s, out=u_out))  # no allocation, as the C++ loop
    scene = inbetween.Scene(ROOT / "examples" / "scenes" / "frame22.json")
    frames = 16.0 + np.arange(7001) * 0.01
    t_bake = min_of(lambda: scene.bake(frames))
    py = {"BM_Python_UofS_1e6": t_us, "BM_Python_UofS_1e6 (out=)": t_us_out, "BM_Python_Bake_Frame22": t_bake}

    peer = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "build" / "release" / "bench" / "inbetween_bench_python_peer"
    cpp = {}
    if peer.exists():
        out = subprocess.run([str(peer), "--benchmark_format=json", "--benchmark_repetitions=15"],
                             capture_output=True, text=True, check=True).stdout
        for b in json.loads(out)["benchmarks"]:
            if b.get("run_type") == "iteration":
                t = b["real_time"] / 1e3  # ms -> s (time per iteration)
                cpp[b["run_name"]] = min(cpp.get(b["run_name"], t), t)
    print(f"{'workload':28} {'Python (min of 15)':>20} {'C++':>12} {'ratio':>7}")
    worst = 0.0
    for name, t in py.items():
        c = cpp.get(name.split(" ")[0])
        ratio = t / c if c else float("nan")
        worst = max(worst, ratio) if c else worst
        print(f"{name:28} {t * 1e3:17.2f} ms {c * 1e3 if c else float('nan'):9.2f} ms {ratio:7.2f}")
    if cpp:
        print(f"worst ratio {worst:.2f} (target <= 1.5)")


if __name__ == "__main__":
    main()
