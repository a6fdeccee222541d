"""The batch on Dask (issue 25): 200 scenes the size of examples/scenes/frame22.json baked at 10x
their frame count (frames 16..86 step 0.1: 701 rows x 52 columns, CSV), on a local cluster of 2
single-threaded workers against 1 (target: speed-up >= 1.8x), and the overhead per job against
running the same job with the tool (one process per job).  Prints a table and one JSON line; the
machine's load average (os.getloadavg) is taken before and after every run, since on a shared
machine the speed-up is bounded by the cores other processes leave free.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/batch_bench.py [--cli build/release/inbetween]
        [--scenes 200] [--repeat 3] [--work DIR]

Run by `make bench`.  The cluster start (a few seconds) is measured apart: the speed-up is over the
jobs' wall time, from submitting the first job to the last result.
"""
import argparse
import json
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import inbetween.batch as batch

ROOT = pathlib.Path(__file__).resolve().parents[1]
SEED = 25            # the scenes' perturbation (issue 25)
FRAMES = "16:86:0.1"  # frame22's range [16, 86] at 10x its 71 frames
CLI_JOBS = 20        # jobs run with the tool itself for its time per job (and to check the bytes)


def write_scenes(folder, n, rng):
    """n variants of frame22.json: its path points moved by up to 0.5, so each scene is its own."""
    base = json.loads((ROOT / "examples" / "scenes" / "frame22.json").read_text())
    (folder / "shots").mkdir(parents=True, exist_ok=True)
    (folder / "out").mkdir(exist_ok=True)
    for k in range(n):
        scene = json.loads(json.dumps(base))
        for path in scene["paths"]:
            pts = np.asarray(path["curve"]["points"], dtype=float)
            path["curve"]["points"] = np.round(pts + rng.uniform(-0.5, 0.5, pts.shape), 6).tolist()
        (folder / "shots" / f"f{k:03d}.json").write_text(json.dumps(scene))
    jobs = [["bake", f"shots/f{k:03d}.json", "--frames", FRAMES, "--progress", "never", "-o", f"out/f{k:03d}.csv"]
            for k in range(n)]
    return {"jobs": [{"args": a} for a in jobs]}


def timed_run(manifest, folder, client, jobs_per_task=None):
    load_before = os.getloadavg()[0]
    t0 = time.perf_counter()
    s = batch.run(manifest, client=client, base_dir=folder, force=True, progress="never", jobs_per_task=jobs_per_task)
    wall = time.perf_counter() - t0
    load_after = os.getloadavg()[0]
    assert s["counts"]["failed"] == 0, [j["message"] for j in s["jobs"] if j["status"] == "failed"]
    in_worker = [j["seconds"] for j in s["jobs"]]
    return {"wall": wall, "load": (load_before, load_after), "job_median": statistics.median(in_worker),
            "jobs_per_task": s["jobs_per_task"]}


def threads_wall(manifest, folder, n_threads):
    """The same jobs through _run_cli in n_threads threads of this process, no Dask: what the
    machine's free cores allow right now (the ceiling of the workers' speed-up)."""
    from concurrent.futures import ThreadPoolExecutor
    from inbetween import _inbetween
    t0 = time.perf_counter()
    with ThreadPoolExecutor(n_threads) as pool:
        codes = list(pool.map(lambda job: _inbetween._run_cli(job["args"], str(folder))[0], manifest["jobs"]))
    assert not any(codes)
    return time.perf_counter() - t0


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cli", default=str(ROOT / "build" / "release" / "inbetween"))
    p.add_argument("--scenes", type=int, default=200)
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--work", help="folder for the scenes and outputs (default: a temporary one, removed)")
    a = p.parse_args()
    a.cli = os.path.abspath(a.cli)
    import distributed

    folder = pathlib.Path(a.work or tempfile.mkdtemp(prefix="inbetween-batch-bench-"))
    try:
        manifest = write_scenes(folder, a.scenes, np.random.default_rng(SEED))
        print(f"batch bench: {a.scenes} frame22-sized scenes, frames {FRAMES} (701 rows each), "
              f"{os.cpu_count()} cores, seed {SEED}, {folder}")
        clusters, results = {}, {1: [], 2: [], "1x1": []}
        for n in (1, 2):
            t0 = time.perf_counter()
            cluster = batch.local_cluster(n)  # the batch's own local cluster and its settings
            client = distributed.Client(cluster)
            clusters[n] = (cluster, client, time.perf_counter() - t0)
            timed_run({"jobs": manifest["jobs"][:4]}, folder, client)  # warm-up: imports in the workers
        for _ in range(a.repeat):  # interleaved: 1, 2, 1 one job per task, 1, 2, …
            for n in (1, 2):
                results[n].append(timed_run(manifest, folder, clusters[n][1]))
            results["1x1"].append(timed_run(manifest, folder, clusters[1][1], jobs_per_task=1))
        for cluster, client, _ in clusters.values():
            client.close()
            cluster.close()
        ceiling = {1: [], 2: []}
        for _ in range(a.repeat):
            for n in (1, 2):
                ceiling[n].append(threads_wall(manifest, folder, n))

        # the tool, one process per job, on the first CLI_JOBS jobs (and the same bytes)
        cli_times = []
        for job in manifest["jobs"][:CLI_JOBS]:
            args = list(job["args"])
            out = folder / (args[-1] + ".cli")
            args[-1] = str(out)
            t0 = time.perf_counter()
            subprocess.run([a.cli, *args], cwd=folder, check=True)
            cli_times.append(time.perf_counter() - t0)
            assert out.read_bytes() == (folder / job["args"][-1]).read_bytes(), job
        cli_job = statistics.median(cli_times)

        best = {n: min(results[n], key=lambda r: r["wall"]) for n in results}
        print(f"{'workers':>8} {'jobs/task':>9} {'jobs wall (min of ' + str(a.repeat) + ')':>22} {'all runs':>24} "
              f"{'per job':>10} {'in worker':>10} {'load avg before/after':>22}")
        for n in results:
            b = best[n]
            runs = ", ".join(f"{r['wall']:.2f}" for r in results[n])
            print(f"{str(n)[0]:>8} {b['jobs_per_task']:>9} {b['wall']:>20.2f} s {runs:>22} s "
                  f"{b['wall'] / a.scenes * 1e3:>7.1f} ms {b['job_median'] * 1e3:>7.1f} ms "
                  f"{b['load'][0]:>10.2f} / {b['load'][1]:.2f}")
        speedup = best[1]["wall"] / best[2]["wall"]
        machine = min(ceiling[1]) / min(ceiling[2])
        per_job_1 = best[1]["wall"] / a.scenes
        print(f"speed-up 2 workers / 1: {speedup:.2f}x (target >= 1.8x); cluster start "
              f"{clusters[1][2]:.1f} s (1 worker), {clusters[2][2]:.1f} s (2 workers)")
        print(f"the machine's ceiling now: the same jobs in 2 threads / 1 of one process, no Dask: {machine:.2f}x "
              f"({', '.join(f'{t:.2f}' for t in ceiling[1])} s / {', '.join(f'{t:.2f}' for t in ceiling[2])} s; "
              f"load {os.getloadavg()[0]:.2f})")
        print(f"per job: the tool (one process) {cli_job * 1e3:.1f} ms median of {CLI_JOBS}; the batch on 1 worker "
              f"{per_job_1 * 1e3:.1f} ms (the command itself {best[1]['job_median'] * 1e3:.1f} ms in the worker): "
              f"overhead against the tool {(per_job_1 - cli_job) * 1e3:+.1f} ms, Dask's own "
              f"{(per_job_1 - best[1]['job_median']) * 1e3:.1f} ms ({best['1x1']['wall'] / a.scenes * 1e3:.1f} ms per job "
              f"at one job per task: Dask's per-task cost "
              f"{(best['1x1']['wall'] / a.scenes - best['1x1']['job_median']) * 1e3:.1f} ms)")
        print(json.dumps({"scenes": a.scenes, "speedup": speedup, "machine_ceiling": machine,
                          "threads_1": ceiling[1], "threads_2": ceiling[2], "wall_1": best[1]["wall"], "wall_2": best[2]["wall"],
                          "all_1": [r["wall"] for r in results[1]], "all_2": [r["wall"] for r in results[2]],
                          "all_1x1": [r["wall"] for r in results["1x1"]],
                          "load": {str(n): [r["load"] for r in results[n]] for n in results},
                          "cli_job": cli_job, "batch_job_1": per_job_1, "in_worker_job": best[1]["job_median"]}))
    finally:
        if not a.work:
            shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
