"""The batch on Dask (issue 25): 200 scenes the size of examples/scenes/frame22.json baked at 10x
their frame count (frames 16..86 step 0.1: 701 rows x 52 columns, CSV), on a local cluster of 2
single-threaded workers against 1 (target: speed-up >= 1.8x), and the overhead per job against
running the same job with the tool (one process per job).  Prints a table per storage and one JSON
line; the machine's load average (os.getloadavg) is taken before and after every run, since on a
shared machine the speed-up is bounded by the cores other processes leave free.

Each job writes its CSV as the tool does (an unnamed file, fsync, linked at the end), so the
storage takes part: the bench runs once in a tmpfs (/dev/shm: the batch's own scaling, storage out
of the picture) and once on the disk of the temporary folder (TMPDIR, /tmp), whose journal
serialises the two workers' fsyncs.  Beside each it runs the machine's ceiling on that storage: the
same jobs in 1 and 2 plain processes (a multiprocessing pool, half the jobs each, no Dask).

    PYTHONPATH=build/release/python /usr/bin/python3 bench/batch_bench.py [--cli build/release/inbetween]
        [--scenes 200] [--repeat 7] [--work DIR]

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


def _run_half(args):
    """A plain process's share of the jobs (the ceiling's pool): run one after the other in a thread
    of their own, as a Dask worker runs a task in its executor's thread (the main thread's malloc
    arena behaves otherwise: the jobs took 8 % longer there)."""
    import threading
    jobs, folder = args
    runner = threading.Thread(target=batch.run_jobs, args=(jobs, folder))
    runner.start()
    runner.join()
    return len(jobs)


def processes_wall(pool, n, manifest, folder):
    """The same jobs in n plain processes (the pool's), 1/n of them each, no Dask: what the machine
    and the storage allow right now (the ceiling of the workers' speed-up)."""
    jobs = [job["args"] for job in manifest["jobs"]]
    t0 = time.perf_counter()
    pool.map(_run_half, [(jobs[i::n], str(folder)) for i in range(n)], chunksize=1)
    return time.perf_counter() - t0


def file_system(folder):
    """The type of the file system holding folder (/proc/self/mounts: the longest mount point)."""
    best, kind = "", "?"
    try:
        with open("/proc/self/mounts") as f:
            for line in f:
                fields = line.split()
                point = fields[1].replace("\\040", " ")
                if str(folder).startswith(point.rstrip("/") + "/") and len(point) > len(best):
                    best, kind = point, fields[2]
    except OSError:
        pass
    return kind


def storages(work):
    """(label, folder, remove afterwards) for each storage the bench runs on."""
    if work:
        folder = pathlib.Path(work)
        return [(file_system(folder.resolve()), folder, False)]
    out = []
    if os.path.isdir("/dev/shm") and os.access("/dev/shm", os.W_OK):
        out.append(pathlib.Path(tempfile.mkdtemp(prefix="inbetween-batch-bench-", dir="/dev/shm")))
    out.append(pathlib.Path(tempfile.mkdtemp(prefix="inbetween-batch-bench-")))
    return [(file_system(f), f, True) for f in out]


def bench_storage(label, folder, a, clusters, pools):
    manifest = write_scenes(folder, a.scenes, np.random.default_rng(SEED))
    for n in (1, 2):
        timed_run({"jobs": manifest["jobs"][:4]}, folder, clusters[n][1])  # warm-up: the page cache
    results = {1: [], 2: [], "1x1": []}
    ceiling = {1: [], 2: []}
    for _ in range(a.repeat):  # interleaved: 1, 2, 1 one job per task, the plain processes' 1 and 2, …
        for n in (1, 2):
            results[n].append(timed_run(manifest, folder, clusters[n][1]))
        results["1x1"].append(timed_run(manifest, folder, clusters[1][1], jobs_per_task=1))
        for n in (1, 2):
            ceiling[n].append(processes_wall(pools[n], n, manifest, folder))

    best = {n: min(results[n], key=lambda r: r["wall"]) for n in results}
    print(f"\n{label} ({folder}):")
    print(f"{'workers':>8} {'jobs/task':>9} {'jobs wall (min of ' + str(a.repeat) + ')':>22} {'all runs':>34} "
          f"{'per job':>10} {'in worker':>10} {'load avg before/after':>22}")
    for n in results:
        b = best[n]
        runs = ", ".join(f"{r['wall']:.2f}" for r in results[n])
        print(f"{str(n)[0]:>8} {b['jobs_per_task']:>9} {b['wall']:>20.2f} s {runs:>32} s "
              f"{b['wall'] / a.scenes * 1e3:>7.1f} ms {b['job_median'] * 1e3:>7.1f} ms "
              f"{b['load'][0]:>10.2f} / {b['load'][1]:.2f}")
    speedup = best[1]["wall"] / best[2]["wall"]
    medians = {n: statistics.median(r["wall"] for r in results[n]) for n in (1, 2)}
    machine = min(ceiling[1]) / min(ceiling[2])
    print(f"speed-up 2 workers / 1: {speedup:.2f}x (target >= 1.8x; medians {medians[1]:.3f} / {medians[2]:.3f} s: "
          f"{medians[1] / medians[2]:.2f}x)")
    print(f"the machine's ceiling on this storage now: the same jobs in 2 plain processes / 1, no Dask: {machine:.2f}x "
          f"({', '.join(f'{t:.2f}' for t in ceiling[1])} s / {', '.join(f'{t:.2f}' for t in ceiling[2])} s; "
          f"load {os.getloadavg()[0]:.2f}); the batch reaches {speedup / machine:.0%} of it")
    return manifest, {"file_system": label, "folder": str(folder), "speedup": speedup,
                      "speedup_medians": medians[1] / medians[2], "machine_ceiling": machine,
                      "processes_1": ceiling[1], "processes_2": ceiling[2],
                      "wall_1": best[1]["wall"], "wall_2": best[2]["wall"],
                      "all_1": [r["wall"] for r in results[1]], "all_2": [r["wall"] for r in results[2]],
                      "all_1x1": [r["wall"] for r in results["1x1"]],
                      "load": {str(n): [r["load"] for r in results[n]] for n in results},
                      "batch_job_1": best[1]["wall"] / a.scenes, "in_worker_job": best[1]["job_median"],
                      "batch_job_1x1": best["1x1"]["wall"] / a.scenes, "in_worker_job_1x1": best["1x1"]["job_median"]}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cli", default=str(ROOT / "build" / "release" / "inbetween"))
    p.add_argument("--scenes", type=int, default=200)
    p.add_argument("--repeat", type=int, default=7)
    p.add_argument("--work", help="one folder for the scenes and outputs (default: a temporary one in /dev/shm "
                                  "and one in TMPDIR, removed)")
    a = p.parse_args()
    a.cli = os.path.abspath(a.cli)
    import multiprocessing

    import distributed

    places = storages(a.work)
    print(f"batch bench: {a.scenes} frame22-sized scenes, frames {FRAMES} (701 rows each), "
          f"{os.cpu_count()} cores, seed {SEED}, on {', '.join(f'{k} ({f})' for k, f, _ in places)}")
    clusters, pools, report = {}, {}, {"scenes": a.scenes, "storages": []}
    try:
        for n in (1, 2):
            t0 = time.perf_counter()
            cluster = batch.local_cluster(n)  # the batch's own local cluster and its settings
            clusters[n] = (cluster, distributed.Client(cluster), time.perf_counter() - t0)
            pools[n] = multiprocessing.get_context("spawn").Pool(n)
            pools[n].map(_run_half, [([], "/")] * n)  # the pool's processes started and importing
        print(f"cluster start {clusters[1][2]:.1f} s (1 worker), {clusters[2][2]:.1f} s (2 workers)")
        first = None
        for label, folder, _ in places:
            manifest, r = bench_storage(label, folder, a, clusters, pools)
            report["storages"].append(r)
            first = first or (folder, manifest, r)

        # the tool, one process per job, on the first CLI_JOBS jobs (and the same bytes)
        folder, manifest, r = first
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
        per_job_1 = r["batch_job_1"]
        print(f"\nper job ({r['file_system']}): the tool (one process) {cli_job * 1e3:.1f} ms median of {CLI_JOBS}; "
              f"the batch on 1 worker {per_job_1 * 1e3:.1f} ms (the command itself {r['in_worker_job'] * 1e3:.1f} ms "
              f"in the worker): overhead against the tool {(per_job_1 - cli_job) * 1e3:+.1f} ms, Dask's own "
              f"{(per_job_1 - r['in_worker_job']) * 1e3:.1f} ms ({r['batch_job_1x1'] * 1e3:.1f} ms per job at one job "
              f"per task: Dask's per-task cost {(r['batch_job_1x1'] - r['in_worker_job_1x1']) * 1e3:.1f} ms)")
        report.update(cli_job=cli_job)
        print(json.dumps(report))
    finally:
        for cluster, client, _ in clusters.values():
            client.close()
            cluster.close()
        for pool in pools.values():
            pool.terminate()
        for _, folder, remove in places:
            if remove:
                shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
