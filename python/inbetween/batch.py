"""Batch bake, convert and compress on Dask (docs/batch.md, issue 25).

    python3 -m inbetween.batch MANIFEST.json [--scheduler ADDRESS] [--workers N]
                               [--summary OUT.json] [--force] [--jobs-per-task N]
                               [--progress auto|always|never]

or from Python, ``inbetween.batch.run("manifest.json", workers=2, summary="summary.json")``.

A manifest lists jobs, each the arguments of one command of the ``inbetween`` tool (``bake``,
``convert``, ``compress``, ``path fit``, ``path smooth``), file paths relative to the manifest's
folder (docs/batch.schema.json)::

    {"jobs": [{"args": ["bake", "shots/a.json", "--format", "csv", "-o", "out/a.csv"]}, ...]}

Each job runs the command in a worker process through the library (``inbetween._inbetween._run_cli``:
the tool's own code, no subprocess, the GIL released), so its output is the tool's, byte for byte,
and a failing job reports the tool's message and exit code.  A Dask task holds one or more jobs,
run one after the other: large tasks first, single jobs at the end (_chunks).
Without ``scheduler`` a local cluster of the machine's cores (one single-threaded worker process
each) runs the jobs; with it, the jobs go to an existing Dask scheduler.

Outputs are written as the tool writes them: an unnamed file (O_TMPFILE) linked under the output's
name at the end, so a worker killed mid-write leaves nothing; where the file system has no
O_TMPFILE (NFS), a temporary ``.<name>.inbetween-XXXXXX`` beside the output, which the batch sweeps
from its outputs' folders when it ends.  A job whose worker dies is run again by the scheduler
(``distributed.scheduler.allowed-failures`` times, Dask's default 3, which the local cluster sets);
a job that raises (not a failing command: an import error on a worker) is retried ``RETRIES`` times.

A job is skipped when every output exists and is newer than every input (the command's input file
and its ``-o`` / convert's output argument, as the tool marks them); ``force`` runs it anyway.  The
summary (docs/batch-summary.schema.json) gives each job's status, time, exit code and message; the
command-line entry exits 0 when every job succeeded (or was skipped) and 2 when any failed.
"""
from __future__ import annotations

import argparse
import concurrent.futures
import datetime
import json
import math
import os
import pathlib
import re
import socket
import sys
import time

__all__ = ["run", "main", "load_manifest", "ManifestError", "COMMANDS", "RETRIES", "ALLOWED_FAILURES"]

#: The commands a manifest may run (the first one or two arguments of a job).
COMMANDS = (("bake",), ("convert",), ("compress",), ("path", "fit"), ("path", "smooth"))
#: Times Dask retries a job that raised an exception in the worker (not a command that failed:
#: that returns its exit code and is not retried; a deterministic input error would fail again).
RETRIES = 1
#: Times the scheduler reschedules a job whose worker died (SIGKILL, out of memory, a crash) before
#: it reports the job failed (KilledWorker); the local cluster sets it, an existing scheduler keeps
#: its own ``distributed.scheduler.allowed-failures`` (Dask's default is the same 3).
ALLOWED_FAILURES = 3
#: Jobs per Dask task (``jobs_per_task`` unset): guided self-scheduling — each task takes the jobs
#: still unassigned divided by the tasks the workers hold at once (_slots), so tasks shrink towards
#: the end and the workers finish together, at most this many jobs each (a killed worker's task is
#: rerun whole: outputs already written are written again, the same bytes).  Each task costs the
#: scheduler, client and worker 3–4 ms of CPU (messages on loopback TCP): 64 jobs of a few ms keep
#: that under 2 %.
MAX_JOBS_PER_TASK = 64
#: Exit codes, as the tool's.
EXIT_OK, EXIT_INTERNAL, EXIT_FAILED = 0, 1, 2
#: Longest stderr text kept per job in the summary (characters; the tail is cut).
MAX_STDERR_CHARS = 65536
#: Seconds to wait for a scheduler, and for the workers asked for with --workers.
CONNECT_TIMEOUT_S = 30
# The temporary names of apps/inbetween/output.cpp: ".<name, at most 200 bytes>.inbetween-XXXXXX".
_TEMP_SUFFIX = re.compile(r"\.inbetween-[A-Za-z0-9]{6}$")
_MAX_NAME_IN_TEMP = 200


class ManifestError(ValueError):
    """A manifest that cannot be read: str() is one line naming the file and the place (a JSON
    pointer), as the tool's messages do."""


# ----------------------------------------------------------------------------- the manifest
def _pointer(*parts) -> str:
    return "".join("/" + str(p).replace("~", "~0").replace("/", "~1") for p in parts)


def load_manifest(manifest):
    """Reads and checks a manifest: a path (str or os.PathLike) or an already parsed dictionary.
    Returns the list of jobs, each {"args": [...], "name": str or None}.  Raises ManifestError."""
    where = str(manifest) if not isinstance(manifest, dict) else "<manifest>"
    if isinstance(manifest, dict):
        doc = manifest
    else:
        try:
            text = pathlib.Path(manifest).read_bytes()
        except OSError as e:
            raise ManifestError(f"{where}: cannot read: {e.strerror or e}") from None
        try:
            doc = json.loads(text)
        except (ValueError, UnicodeDecodeError) as e:
            line = f"line {e.lineno}, column {e.colno}: " if isinstance(e, json.JSONDecodeError) else ""
            raise ManifestError(f"{where}: {line}not a JSON document: {getattr(e, 'msg', e)}") from None
    if not isinstance(doc, dict):
        raise ManifestError(f"{where}: /: a manifest is an object {{\"jobs\": [...]}} (docs/batch.md)")
    for key in doc:
        if key not in ("jobs", "$schema"):
            raise ManifestError(f"{where}: {_pointer(key)}: unknown member (a manifest has \"jobs\")")
    jobs = doc.get("jobs")
    if not isinstance(jobs, list):
        raise ManifestError(f"{where}: /jobs: " + ("missing: a manifest lists its jobs in \"jobs\"" if jobs is None
                                                     else "must be an array of jobs"))
    out = []
    for i, job in enumerate(jobs):
        if not isinstance(job, dict):
            raise ManifestError(f"{where}: {_pointer('jobs', i)}: a job is an object {{\"args\": [...]}}")
        for key in job:
            if key not in ("args", "name"):
                raise ManifestError(f"{where}: {_pointer('jobs', i, key)}: unknown member (a job has \"args\" and \"name\")")
        args = job.get("args")
        if not isinstance(args, list) or not args:
            raise ManifestError(f"{where}: {_pointer('jobs', i, 'args')}: must be a non-empty array of strings")
        for k, a in enumerate(args):
            if not isinstance(a, str):
                raise ManifestError(f"{where}: {_pointer('jobs', i, 'args', k)}: must be a string")
        name = job.get("name")
        if name is not None and not isinstance(name, str):
            raise ManifestError(f"{where}: {_pointer('jobs', i, 'name')}: must be a string")
        out.append({"args": list(args), "name": name})
    return out


# ----------------------------------------------------------------------------- one job
def _message(stderr: str) -> str:
    """The tool's error line: the last non-empty line of its standard error."""
    lines = [line for line in stderr.splitlines() if line.strip()]
    return lines[-1] if lines else ""


def _start_job(args, base_dir):
    """Runs one job's command in this (worker) process through the library, its file outputs left
    written in full but not yet synced or named; (what the summary records of it, the outputs to
    finish).  A failing command is a result (its exit code and message), not an exception."""
    from inbetween import _inbetween  # noqa: PLC0415 (imported in the worker)
    start = time.perf_counter()
    code, out, err, _inputs, _outputs, pending = _inbetween._run_cli_deferred(list(args), str(base_dir))
    seconds = time.perf_counter() - start
    try:
        from distributed import get_worker
        worker = get_worker().address
    except (ImportError, ValueError):
        worker = ""
    record = {"exit_code": int(code), "message": _message(err) if code else "", "stderr": err,
              "stdout_bytes": len(out), "seconds": seconds, "worker": worker, "host": socket.gethostname(),
              "pid": os.getpid()}
    return record, pending


def _finish_job(pending):
    """The tool's last step for a job's outputs (fsync, then the name): (exit code, stderr, seconds)."""
    start = time.perf_counter()
    code, err = pending.finish()
    return int(code), err, time.perf_counter() - start


def _end_job(record, finished):
    """The job's record once its outputs are finished: a failure to sync or name one is the job's
    failure, with the tool's message (unless the command had already failed: its message stays)."""
    code, err, seconds = finished
    record["seconds"] += seconds
    if code:
        if not record["exit_code"]:
            record.update(exit_code=code, message=_message(err))
        record["stderr"] += err
    record["stderr"] = record["stderr"][-MAX_STDERR_CHARS:]
    return record


#: Jobs of a task whose outputs may wait to be finished while the next job computes (their
#: descriptors and page-cache data held meanwhile).
FINISH_BEHIND = 2
#: Seconds a job's finish may take for the next job's to be done at once rather than behind.  A
#: frame22 bake's 370 kB CSV took 0.018-0.049 ms to finish in a tmpfs and 0.44-0.72 ms on this
#: machine's ext4 disk (50 each, 2026-11-28): a handoff to the second thread costs more than the former.
FINISH_INLINE_BELOW_S = 2e-4


def run_jobs(jobs, base_dir):
    """Runs several jobs (lists of arguments) one after the other in this worker: one Dask task,
    so that jobs of a few milliseconds do not pay the scheduler's per-task cost each.

    A job's outputs are synced and named (the tool's last step: fsync, then the name) at once, as
    the tool does, until one job's finish takes FINISH_INLINE_BELOW_S or longer (a disk, NFS).
    From then on they are finished in a second thread while the next job computes, since the fsync
    waits on the storage, not on the CPU; before a job starts, the outputs of the job FINISH_BEHIND
    before it are named.  A worker killed meanwhile leaves nothing of the unfinished outputs
    (unnamed files), and its task is rerun whole."""
    started, behind = [], False
    with concurrent.futures.ThreadPoolExecutor(1, thread_name_prefix="inbetween-finish") as finisher:
        for i, args in enumerate(jobs):
            if i >= FINISH_BEHIND:
                started[i - FINISH_BEHIND][1].result()
            record, pending = _start_job(args, base_dir)
            if behind:
                finished = finisher.submit(_finish_job, pending)
            else:
                finished = concurrent.futures.Future()
                finished.set_result(_finish_job(pending))
                behind = finished.result()[2] >= FINISH_INLINE_BELOW_S
            started.append((record, finished))
        return [_end_job(record, finished.result()) for record, finished in started]


def _slots(workers, saturation):
    """The tasks Dask hands the workers at once: for each worker (scheduler_info()["workers"]
    values) ceil(saturation × its threads), at least 1 (Dask's _task_slots_available); the rest
    wait in the scheduler's queue for the next free slot.  Without a queue (saturation inf: every
    task is sent to a worker at once and work stealing balances them) two per thread."""
    threads = [max(1, int(w.get("nthreads", 1))) for w in workers]
    if not isinstance(saturation, (int, float)) or math.isinf(saturation) or saturation <= 0:
        return max(1, 2 * sum(threads))
    return max(1, sum(max(1, math.ceil(saturation * t)) for t in threads))


def _chunks(jobs, slots, jobs_per_task=None):
    """The jobs cut into Dask tasks, in order.  `jobs_per_task` given: tasks of that many jobs.
    Unset: guided self-scheduling — a task takes ceil(unassigned / slots) jobs, at least 1 and at
    most MAX_JOBS_PER_TASK, `slots` being the tasks the workers hold at once (_slots): few, large
    tasks first (Dask's per-task cost of 3–4 ms of CPU against jobs of a few ms), single jobs last,
    so no worker waits long on another's last task."""
    chunks, start = [], 0
    while start < len(jobs):
        if jobs_per_task:
            size = jobs_per_task
        else:
            size = -(-(len(jobs) - start) // max(1, slots))
            size = max(1, min(MAX_JOBS_PER_TASK, size))
        chunks.append(jobs[start:start + size])
        start += size
    return chunks


def _command_of(args):
    for c in COMMANDS:
        if tuple(args[:len(c)]) == c:
            return c
    return None


def _plan(index, job, base_dir):
    """The job's summary entry before it runs: its files (the tool's own argument parsing, in this
    process, nothing run) or why it cannot run ("failed" with the tool's message)."""
    from inbetween import _inbetween
    args = job["args"]
    entry = {"index": index, "name": job["name"], "args": args, "status": "pending", "exit_code": None,
             "message": "", "seconds": None, "worker": "", "inputs": [], "outputs": [], "stderr": ""}
    if _command_of(args) is None:
        names = ", ".join(" ".join(c) for c in COMMANDS)
        return dict(entry, status="failed", exit_code=EXIT_FAILED,
                    message=f"batch: jobs/{index}: '{' '.join(args[:2])}' is not a batch command ({names})")
    code, _out, err, inputs, outputs = _inbetween._run_cli(list(args), str(base_dir), True)
    entry.update(inputs=list(inputs), outputs=list(outputs))
    if code != 0:  # the tool's own message: a bad option, an unknown command (compress before it exists)
        return dict(entry, status="failed", exit_code=int(code), message=_message(err), stderr=err)
    if not outputs:
        return dict(entry, status="failed", exit_code=EXIT_FAILED,
                    message=f"batch: jobs/{index}: writes to standard output; give the output file (-o FILE)")
    if any(p == "-" for p in inputs):
        return dict(entry, status="failed", exit_code=EXIT_FAILED,
                    message=f"batch: jobs/{index}: reads standard input; give the input file")
    return entry


def _up_to_date(inputs, outputs) -> bool:
    """Every output exists and is newer than every input (modification times)."""
    try:
        newest_input = max((os.stat(p).st_mtime_ns for p in inputs), default=0)
        oldest_output = min(os.stat(p).st_mtime_ns for p in outputs)
    except OSError:
        return False
    return oldest_output > newest_input


def _sweep(outputs):
    """Removes the tool's temporaries (".<name>.inbetween-XXXXXX") of these outputs: those a worker
    killed between linking and renaming its file, or writing where O_TMPFILE is missing, left."""
    swept = []
    by_folder = {}  # one listing per folder: a batch writes many outputs into few folders
    for out in set(outputs):
        folder, name = os.path.split(out)
        prefix = "." + os.fsencode(name)[:_MAX_NAME_IN_TEMP].decode(errors="surrogateescape")
        by_folder.setdefault(folder, set()).add(prefix)
    for folder in sorted(by_folder):
        try:
            entries = os.listdir(folder or ".")
        except OSError:
            continue
        prefixes = by_folder[folder]
        for e in sorted(entries):
            m = _TEMP_SUFFIX.search(e)  # the temporary's name: its output's prefix, then the suffix
            if m is None or e[:m.start()] not in prefixes:
                continue
            path = os.path.join(folder, e)
            try:
                if os.path.isfile(path) and not os.path.islink(path):
                    os.unlink(path)
                    swept.append(path)
            except OSError:
                pass
    return swept


# ----------------------------------------------------------------------------- progress
class _Progress:
    """"\\rbatch [#####.....]  12/50 jobs  1 failed  ETA 8 s" on standard error, redrawn at most
    every 0.1 s; only on a terminal in "auto" mode (as `inbetween bake --progress`)."""

    def __init__(self, total, mode="auto", stream=None):
        self.stream = stream or sys.stderr
        isatty = getattr(self.stream, "isatty", lambda: False)()
        self.enabled = mode == "always" or (mode == "auto" and isatty)
        self.total, self.start, self.next, self.width = total, time.monotonic(), 0.0, 0

    def update(self, done, failed, force=False):
        if not self.enabled:
            return
        now = time.monotonic()
        if not force and now < self.next:
            return
        self.next = now + 0.1
        fraction = done / self.total if self.total else 1.0
        cells = int(fraction * 30)
        line = f"\rbatch [{'#' * cells}{'.' * (30 - cells)}] {int(fraction * 100):3d}%  {done}/{self.total} jobs"
        if failed:
            line += f"  {failed} failed"
        if 0 < done < self.total:
            line += f"  ETA {int((now - self.start) * (self.total - done) / done + 0.5)} s"
        self.width = max(self.width, len(line))
        self.stream.write(line.ljust(self.width))
        self.stream.flush()

    def finish(self):
        if self.enabled and self.width:
            self.stream.write("\r" + " " * self.width + "\r")
            self.stream.flush()


# ----------------------------------------------------------------------------- the batch
def _write_json_atomically(path, doc):
    path = pathlib.Path(path)
    tmp = path.with_name(f".{path.name}.batch-{os.getpid()}")
    tmp.write_text(json.dumps(doc, indent=1, ensure_ascii=False) + "\n")
    os.replace(tmp, path)


#: Settings of the local cluster (local_cluster): the scheduler and the nannies share the machine's
#: cores with the workers, so their periodic work is made rarer — no work stealing (the scheduler
#: queues the batch's tasks and hands each to the next free worker, nothing to steal), the event
#: loop's tick and the memory and system monitors every second instead of every 20–500 ms, no
#: dashboards.  A worker holds one task at a time (saturation 1.0: _chunks balances the workers
#: exactly) and runs no statistical profiler (a stack sample every 10 ms).
LOCAL_CLUSTER_CONFIG = {
    "distributed.scheduler.allowed-failures": ALLOWED_FAILURES,
    "distributed.scheduler.work-stealing": False,
    "distributed.scheduler.worker-saturation": 1.0,
    "distributed.admin.tick.interval": "1s",
    "distributed.worker.memory.monitor-interval": "1s",
    "distributed.admin.system-monitor.interval": "2s",
    "distributed.worker.profile.enabled": False,
}


#: Dask configuration under which run() submits: every module's frames skipped when Dask looks for
#: the code that submitted the jobs (distributed.diagnostics.computations.ignore-modules), so it
#: does not read and tokenize run()'s source for the dashboard on every batch.
NO_COMPUTATION_CODE = {"distributed.diagnostics.computations.ignore-modules": [".*"]}


def local_cluster(n_workers):
    """The batch's own cluster on this machine: `n_workers` single-threaded worker processes on
    127.0.0.1 with LOCAL_CLUSTER_CONFIG (the workers inherit it).  The caller closes it."""
    import dask
    from distributed import LocalCluster
    with dask.config.set(LOCAL_CLUSTER_CONFIG):
        return LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                            dashboard_address=None, worker_dashboard_address=None, silence_logs=40)


def run(manifest, scheduler=None, workers=None, summary=None, force=False, progress="auto", client=None,
        base_dir=None, jobs_per_task=None):
    """Runs a manifest's jobs on Dask; returns the summary (a dictionary, also written to `summary`
    when given).  `manifest`: a file (paths relative to its folder) or a dictionary (paths relative
    to `base_dir`, default the current folder).  `scheduler`: an existing scheduler's address
    ("tcp://host:8786"); without it a local cluster of `workers` processes (default: the machine's
    cores) runs the jobs and is closed at the end.  `client`: a distributed.Client to use instead of
    either.  `force`: run the jobs whose outputs are up to date too.  `progress`: "auto" (a bar on a
    terminal), "always" or "never".  `jobs_per_task`: jobs sent to a worker as one Dask task (default:
    tasks that shrink towards the end, see _chunks).  Raises ManifestError for a manifest that cannot be read; jobs
    that fail are in the summary ("status": "failed"), never raised."""
    import dask
    from distributed import Client, LocalCluster, as_completed

    jobs = load_manifest(manifest)
    if base_dir is None:
        base_dir = os.getcwd() if isinstance(manifest, dict) else os.path.dirname(os.path.abspath(manifest))
    base_dir = os.path.abspath(base_dir)
    started = datetime.datetime.now(datetime.timezone.utc)
    t0 = time.perf_counter()

    # Planning parses every job with the tool (25 us each, 5 ms for 200 jobs) before the first one
    # can run.  In one thread: a thread pool made it slower (6-7 ms), its per-call cost being larger
    # than the parse it spreads.
    entries = [_plan(i, job, base_dir) for i, job in enumerate(jobs)]
    writers = {}
    for e in entries:  # two jobs writing one file would race: the later one fails
        if e["status"] != "pending":
            continue
        for out in e["outputs"]:
            if out in writers:
                e.update(status="failed", exit_code=EXIT_FAILED,
                         message=f"batch: jobs/{e['index']}: writes {out}, as jobs/{writers[out]} does")
                break
        else:
            for out in e["outputs"]:
                writers[out] = e["index"]
    for e in entries:
        if e["status"] == "pending" and not force and _up_to_date(e["inputs"], e["outputs"]):
            e.update(status="skipped", exit_code=EXIT_OK)
    to_run = [e for e in entries if e["status"] == "pending"]

    cluster = own_client = None
    per_task = 0
    address, n_workers, allowed_failures = "", 0, ALLOWED_FAILURES
    bar = _Progress(len(entries), progress)
    done = sum(1 for e in entries if e["status"] != "pending")
    failed = sum(1 for e in entries if e["status"] == "failed")
    try:
        if to_run:
            if client is None:
                if scheduler:
                    own_client = client = Client(scheduler, timeout=CONNECT_TIMEOUT_S)
                    if workers:
                        client.wait_for_workers(int(workers), timeout=CONNECT_TIMEOUT_S)
                else:
                    cluster = local_cluster(int(workers or os.cpu_count() or 1))
                    own_client = client = Client(cluster)
            address = client.scheduler.address
            workers_info = list(client.scheduler_info().get("workers", {}).values())
            n_workers = len(workers_info)
            saturation = LOCAL_CLUSTER_CONFIG["distributed.scheduler.worker-saturation"]
            if cluster is None:  # an existing scheduler's own settings
                try:
                    # a lambda: pickled by value, the scheduler need not import inbetween
                    allowed_failures, saturation = client.run_on_scheduler(
                        lambda dask_scheduler: (dask_scheduler.allowed_failures,
                                                getattr(dask_scheduler, "WORKER_SATURATION", float("inf"))))
                except Exception:  # noqa: BLE001 (an older scheduler: report Dask's defaults)
                    saturation = 1.1
            bar.update(done, failed, force=True)
            token = f"{os.getpid()}-{int(time.time() * 1e6)}"
            chunks = _chunks(to_run, _slots(workers_info, saturation), jobs_per_task)
            per_task = max(len(chunk) for chunk in chunks)
            # One map call, not a submit per task.  Dask sends the calling code to the scheduler for
            # its dashboard's "computations" (inspect.getsource: 4 ms here, serial before any job
            # starts); NO_COMPUTATION_CODE has it skip every frame and send "<Code not available>".
            with dask.config.set(NO_COMPUTATION_CODE):
                submitted = client.map(run_jobs, [[e["args"] for e in chunk] for chunk in chunks], base_dir=base_dir,
                                       key=[f"inbetween-jobs-{chunk[0]['index']:09d}-{token}" for chunk in chunks],
                                       pure=False, retries=RETRIES)
            futures = dict(zip(submitted, chunks))
            # with_results: the loop thread gathers each result as its task ends, rather than a
            # round trip from this thread per task (f.result())
            for f, results in as_completed(list(futures), loop=client.loop, with_results=True, raise_errors=False):
                chunk = futures[f]
                try:
                    if f.status == "error":  # raise_errors=False: (type, exception, traceback)
                        raise results[1]
                    if f.status == "cancelled":  # a CancelledError
                        raise results
                    for e, r in zip(chunk, results):
                        e.update(status="done" if r["exit_code"] == 0 else "failed", exit_code=r["exit_code"],
                                 message=r["message"], seconds=r["seconds"], worker=r["worker"], stderr=r["stderr"])
                except Exception as exc:  # noqa: BLE001 (KilledWorker, or the task raised RETRIES + 1 times)
                    kind = type(exc).__name__
                    for e in chunk:
                        if kind == "KilledWorker":
                            why = (f"batch: jobs/{e['index']}: its worker died {allowed_failures + 1} times "
                                   f"(allowed-failures {allowed_failures}): {exc}")
                        else:
                            why = f"batch: jobs/{e['index']}: {kind}: {exc}"
                        e.update(status="failed", exit_code=EXIT_INTERNAL, message=" ".join(why.split()))
                done += len(chunk)
                failed += sum(e["status"] == "failed" for e in chunk)
                bar.update(done, failed)
    finally:
        bar.finish()
        if own_client is not None:
            own_client.close()
        if cluster is not None:
            cluster.close()
    swept = _sweep([out for e in to_run for out in e["outputs"]])

    counts = {s: sum(1 for e in entries if e["status"] == s) for s in ("done", "skipped", "failed")}
    result = {
        "inbetween_batch": 1,
        "manifest": os.path.abspath(manifest) if not isinstance(manifest, dict) else None,
        "base_dir": base_dir,
        "scheduler": address,
        "workers": n_workers,
        "retries": RETRIES,
        "jobs_per_task": per_task,
        "allowed_failures": allowed_failures,
        "started": started.isoformat(timespec="seconds"),
        "seconds": time.perf_counter() - t0,
        "counts": counts,
        "swept": swept,
        "jobs": entries,
    }
    if summary:
        _write_json_atomically(summary, result)
    return result


def main(argv=None) -> int:
    """The command line (module docstring); returns the exit code."""
    p = argparse.ArgumentParser(prog="python3 -m inbetween.batch",
                                description="Run a manifest of inbetween commands (bake, convert, compress, path "
                                            "fit/smooth) on Dask (docs/batch.md)")
    p.add_argument("manifest", help="the manifest (JSON, docs/batch.schema.json); paths relative to its folder")
    p.add_argument("--scheduler", help="an existing Dask scheduler (tcp://HOST:8786); default: a local cluster")
    p.add_argument("--workers", type=int, help="local cluster: worker processes (default: the machine's cores); "
                                               "--scheduler: wait until this many workers are connected")
    p.add_argument("--summary", help="write the summary (JSON, docs/batch-summary.schema.json) to this file")
    p.add_argument("--force", action="store_true", help="run the jobs whose outputs are newer than their inputs too")
    p.add_argument("--jobs-per-task", type=int, help="jobs sent to a worker as one Dask task (default: the unassigned "
                                                     "jobs / the tasks the workers hold at once, 1 to 64: tasks shrink "
                                                     "towards the end)")
    p.add_argument("--progress", choices=("auto", "always", "never"), default="auto",
                   help="progress bar on standard error: auto (when it is a terminal), always, never")
    a = p.parse_args(argv)
    if a.workers is not None and a.workers < 1:
        p.error("--workers: at least 1")
    if a.jobs_per_task is not None and a.jobs_per_task < 1:
        p.error("--jobs-per-task: at least 1")
    try:
        result = run(a.manifest, scheduler=a.scheduler, workers=a.workers, summary=a.summary, force=a.force,
                     progress=a.progress, jobs_per_task=a.jobs_per_task)
    except ManifestError as e:
        print(f"batch: {e}", file=sys.stderr)
        return EXIT_FAILED
    except OSError as e:  # the scheduler cannot be reached, the summary cannot be written
        print(f"batch: {e}", file=sys.stderr)
        return EXIT_FAILED
    for e in result["jobs"]:
        if e["status"] == "failed":
            print(f"batch: jobs/{e['index']} ({' '.join(e['args'])}): {e['message']}", file=sys.stderr)
    c = result["counts"]
    print(f"batch: {len(result['jobs'])} jobs: {c['done']} done, {c['skipped']} skipped (up to date), "
          f"{c['failed']} failed in {result['seconds']:.1f} s"
          + (f" on {result['workers']} workers" if result["workers"] else "")
          + (f"; summary in {a.summary}" if a.summary else ""))
    return EXIT_FAILED if c["failed"] else EXIT_OK


if __name__ == "__main__":
    # Through the package's module (not this __main__ copy), so that the jobs Dask sends to the
    # workers name inbetween.batch.run_jobs, which every worker imports.
    from inbetween.batch import main as _main
    sys.exit(_main())
