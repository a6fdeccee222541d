"""inbetween.batch on Dask (issue 25, docs/batch.md), on loopback only (127.0.0.1): a local cluster
of 2 workers bakes 50 scenes and converts 10 to .glb, byte for byte the tool's output; a
dask-scheduler with two dask-worker processes, one killed (SIGKILL) while it writes, loses no
output and leaves no partial or temporary file; failing jobs (a bad scene, a missing input, an
unwritable output, `compress` before the command exists) report the tool's message and exit code
while the others finish; up-to-date jobs are skipped, --force reruns them; temporaries are swept.

Run by ctest as python.batch (skipped, with the [  SKIPPED ] marker, where python3-distributed is
not installed).  The reference bytes come from the built tool (INBETWEEN_CLI), a few processes."""
import json
import os
import pathlib
import shlex
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

distributed = pytest.importorskip("distributed")
# Debian's tornado 6.2 with distributed 2022.12 warns about its own event-loop set-up
pytestmark = pytest.mark.filterwarnings("ignore:make_current is deprecated:DeprecationWarning")
from inbetween import _inbetween  # noqa: E402
import inbetween.batch as batch  # noqa: E402

from test_run_cli import open_unnamed_file  # noqa: E402

if not hasattr(_inbetween, "_run_cli"):
    pytest.skip("module built without the tool (INBETWEEN_BUILD_APPS off)", allow_module_level=True)

SCENES = 50     # issue 25: a manifest of 50 scenes
CONVERTS = 10   # … of which 10 are converted to .glb
START_TIMEOUT_S = 60  # a scheduler or worker process that has not started by then fails the test


def cli_binary():
    p = os.environ.get("INBETWEEN_CLI", "")
    if not (p and os.access(p, os.X_OK)):
        pytest.skip("the inbetween tool is not built (INBETWEEN_CLI unset)")
    return p


def small_scene(rng, k):
    """Scene k: two objects keyed at 4–6 random frames (translation, rotation), a scalar track."""
    def keys(n, dim):
        frames = np.sort(rng.choice(np.arange(0, 40), size=n, replace=False))
        return [{"frame": int(f), "value": [round(float(v), 6) for v in rng.uniform(-5, 5, dim)]}
                for f in frames]
    rot = [{"frame": k0["frame"], "value": list(np.round(q / np.linalg.norm(q), 9))}
           for k0, q in zip(keys(4, 1), rng.normal(size=(4, 4)))]
    return {"inbetween": 1, "fps": 24, "range": [0, 39],
            "tracks": [{"name": f"weight{k}", "keys": [{"frame": d["frame"], "value": d["value"][0]}
                                                        for d in keys(5, 1)]}],
            "objects": [{"name": "a", "translation": {"keys": keys(int(rng.integers(4, 7)), 3)},
                         "rotation": {"keys": rot}},
                        {"name": "b", "parent": "a", "translation": {"keys": keys(4, 3)}}]}


def write_scenes(folder, n, rng):
    (folder / "shots").mkdir(parents=True)
    for k in range(n):
        (folder / "shots" / f"s{k:02d}.json").write_text(json.dumps(small_scene(rng, k)))
    # inputs older than anything the batch writes (a file system's clock ticks are coarse)
    past = time.time() - 100
    for p in (folder / "shots").iterdir():
        os.utime(p, (past, past))


def reference(folder, jobs):
    """Each job run by the tool itself (one shell, one process per job, cwd = the manifest's
    folder, the output renamed ref/<i>): {job index: bytes}."""
    (folder / "ref").mkdir()
    lines = []
    for i, args in jobs:
        out_at = args.index("-o") + 1 if "-o" in args else len(args) - 1
        ref_args = list(args)
        ref_args[out_at] = f"ref/{i}{pathlib.Path(args[out_at]).suffix}"
        lines.append(" ".join(map(shlex.quote, [cli_binary(), *ref_args])) + " 2>/dev/null")
    subprocess.run(["sh", "-ec", "\n".join(lines)], cwd=folder, check=True)
    return {i: next((folder / "ref").glob(f"{i}.*")).read_bytes() for i, _ in jobs}


def temporaries(folder):
    return [p.name for p in pathlib.Path(folder).iterdir() if p.name.startswith(".")]


@pytest.fixture(scope="module")
def client():
    """A local cluster of 2 single-threaded worker processes on 127.0.0.1, shared by the tests that
    need no fresh one."""
    cluster = batch.local_cluster(2)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def test_local_cluster_bakes_50_scenes_and_converts_10_byte_for_byte(tmp_path, rng):
    write_scenes(tmp_path, SCENES, rng)
    jobs = [["bake", f"shots/s{k:02d}.json", "--format", "csv" if k % 2 else "json", "-o", f"out/s{k:02d}.csv"]
            for k in range(SCENES)]
    jobs += [["convert", f"shots/s{k:02d}.json", f"glb/s{k:02d}.glb"] for k in range(CONVERTS)]
    (tmp_path / "out").mkdir()
    (tmp_path / "glb").mkdir()
    manifest = tmp_path / "manifest.json"
    manifest.write_text(json.dumps({"jobs": [{"args": a} for a in jobs]}))
    # the command line, as a user runs it, with its own local cluster of 2 workers
    r = subprocess.run([sys.executable, "-m", "inbetween.batch", str(manifest), "--workers", "2",
                        "--summary", str(tmp_path / "summary.json")], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr
    assert "batch [" not in r.stderr, "no progress bar when standard error is not a terminal"
    assert f"{len(jobs)} jobs: {len(jobs)} done, 0 skipped (up to date), 0 failed" in r.stdout, r.stdout
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["workers"] == 2 and summary["counts"] == {"done": len(jobs), "skipped": 0, "failed": 0}
    assert len({j["worker"] for j in summary["jobs"]}) == 2, "both workers ran jobs"
    refs = reference(tmp_path, list(enumerate(jobs)))
    for i, args in enumerate(jobs):
        out = tmp_path / (args[-1])
        assert out.read_bytes() == refs[i], args
        assert summary["jobs"][i]["status"] == "done" and summary["jobs"][i]["exit_code"] == 0
        assert summary["jobs"][i]["outputs"] == [str(out)]
    assert "keys" in summary["jobs"][SCENES]["stderr"], "convert's channel report is kept"
    assert temporaries(tmp_path / "out") == [] and temporaries(tmp_path / "glb") == []
    check_schema(tmp_path / "manifest.json", "batch.schema.json")
    check_schema(tmp_path / "summary.json", "batch-summary.schema.json")


def check_schema(doc_path, schema_name):
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads((pathlib.Path(os.environ.get("INBETWEEN_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
                         / "docs" / schema_name).read_text())
    jsonschema.validate(json.loads(pathlib.Path(doc_path).read_text()), schema)


def test_failures_are_reported_with_the_tools_message_and_the_others_finish(tmp_path, client, rng):
    write_scenes(tmp_path, 4, rng)
    bad = tmp_path / "shots" / "bad.json"
    bad.write_text('{"inbetween": 1, "tracks": [{"name": "x", "keys": [{"frame": 3, "value": 0}, '
                   '{"frame": 1, "value": 1}]}]}')
    (tmp_path / "out").mkdir()
    (tmp_path / "blocker").write_text("a file, not a folder")
    jobs = [["bake", "shots/s00.json", "-o", "out/s00.csv"],
            ["bake", "shots/bad.json", "-o", "out/bad.csv"],                  # a bad scene
            ["bake", "shots/missing.json", "-o", "out/missing.csv"],          # a missing input
            ["bake", "shots/s01.json", "-o", "blocker/s01.csv"],              # an unwritable output
            ["convert", "shots/s02.json", "out/s02.glb"],
            ["compress", "shots/s03.json", "-o", "out/s03.ibc"],              # a scene's objects as a clip
            ["bake", "shots/s03.json", "-o", "out/s03.csv"],
            ["plot", "shots/s03.json", "-o", "plots"],                        # not a batch command
            ["bake", "shots/s03.json"],                                       # no output file
            ["bake", "shots/s02.json", "-o", "out/s00.csv"]]                  # the same output as job 0
    manifest = tmp_path / "manifest.json"
    manifest.write_text(json.dumps({"jobs": [{"args": a} for a in jobs]}))
    # 2 jobs per Dask task: a failing job does not take the others of its task with it
    code = batch.main([str(manifest), "--scheduler", client.scheduler.address, "--summary",
                       str(tmp_path / "summary.json"), "--progress", "never", "--jobs-per-task", "2"])
    assert code == 2
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["jobs_per_task"] == 2
    status = [j["status"] for j in s["jobs"]]
    assert status == ["done", "failed", "failed", "failed", "done", "done", "done", "failed", "failed", "failed"]
    assert s["counts"] == {"done": 4, "skipped": 0, "failed": 6}
    # the tool's own line and exit code for the same command, paths as the batch resolved them
    for i in (1, 2, 3):
        # the files the tool knows (input, -o) resolved as the batch resolves them
        args = [str(tmp_path / a) if a.startswith(("shots/", "out/", "blocker/")) else a for a in jobs[i]]
        ref = subprocess.run([cli_binary(), *args], capture_output=True, text=True, cwd=tmp_path)
        assert s["jobs"][i]["exit_code"] == ref.returncode == 2, i
        assert s["jobs"][i]["message"] == ref.stderr.strip(), i
    assert "/keys/1" in s["jobs"][1]["message"] and str(bad) in s["jobs"][1]["message"]
    assert "missing.json" in s["jobs"][2]["message"] and "No such file" in s["jobs"][2]["message"]
    assert "blocker/s01.csv: cannot open for writing: Not a directory" in s["jobs"][3]["message"]
    assert "not a batch command" in s["jobs"][7]["message"]
    assert "writes to standard output" in s["jobs"][8]["message"]
    assert "as jobs/0 does" in s["jobs"][9]["message"]
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["s00.csv", "s02.glb", "s03.csv", "s03.ibc"]
    check_schema(tmp_path / "summary.json", "batch-summary.schema.json")


CMU = pathlib.Path("/usr/share/assimp/models/BVH")


@pytest.mark.skipif(not (CMU / "01_01.bvh").exists(), reason="Debian's assimp-testmodels is not installed")
def test_compress_of_the_cmu_clips_matches_the_tool_byte_for_byte(tmp_path, client):
    # Issue 25: compress runs in the batch like bake and convert.  E = 0.1 and --refine 0 keep it
    # short (about a second per clip); the bytes must equal the tool's own run of the same job.
    (tmp_path / "out").mkdir()
    jobs = [(i, ["compress", str(CMU / f"{name}.bvh"), "-o", f"out/{name}.ibc", "--error", "0.1", "--refine", "0"])
            for i, name in enumerate(["01_01", "01_03", "Boxing_Toes"])]
    summary = batch.run({"jobs": [{"args": a} for _, a in jobs]}, client=client, base_dir=tmp_path, progress="never")
    assert summary["counts"] == {"done": 3, "skipped": 0, "failed": 0}, summary
    ref = reference(tmp_path, jobs)
    for i, args in jobs:
        out = (tmp_path / args[3]).read_bytes()
        assert out[:4] == b"IBC\x1a" and out == ref[i], args[1]


def test_up_to_date_jobs_are_skipped_and_force_reruns_them(tmp_path, client, rng):
    write_scenes(tmp_path, 3, rng)
    (tmp_path / "out").mkdir()
    manifest = {"jobs": [{"args": ["bake", f"shots/s{k:02d}.json", "-o", f"out/s{k:02d}.csv"], "name": f"shot {k}"}
                         for k in range(3)]}
    first = batch.run(manifest, client=client, base_dir=tmp_path, progress="never")
    assert first["counts"] == {"done": 3, "skipped": 0, "failed": 0}
    assert [j["name"] for j in first["jobs"]] == ["shot 0", "shot 1", "shot 2"]
    again = batch.run(manifest, client=client, base_dir=tmp_path, progress="never")
    assert again["counts"] == {"done": 0, "skipped": 3, "failed": 0} and again["scheduler"] == ""
    # an input newer than its output: that job runs again
    future = time.time() + 100
    os.utime(tmp_path / "shots" / "s01.json", (future, future))
    third = batch.run(manifest, client=client, base_dir=tmp_path, progress="never")
    assert [j["status"] for j in third["jobs"]] == ["skipped", "done", "skipped"]
    forced = batch.run(manifest, client=client, base_dir=tmp_path, progress="never", force=True)
    assert forced["counts"] == {"done": 3, "skipped": 0, "failed": 0}


def test_temporaries_of_the_outputs_are_swept_and_nothing_else(tmp_path, client, rng):
    write_scenes(tmp_path, 1, rng)
    out = tmp_path / "out"
    out.mkdir()
    left = [".s00.csv.inbetween-Ab12Cd", ".s00.csv.inbetween-zzzzzz"]  # what a killed worker leaves
    kept = [".s00.csv.inbetween-tmp", ".other.csv.inbetween-Ab12Cd", "s00.csv.inbetween-Ab12Cd", ".s00.csv.x"]
    for name in left + kept:
        (out / name).write_text("x")
    s = batch.run({"jobs": [{"args": ["bake", "shots/s00.json", "-o", "out/s00.csv"]}]}, client=client,
                  base_dir=tmp_path, progress="never")
    assert s["counts"]["done"] == 1
    assert sorted(s["swept"]) == sorted(str(out / n) for n in left)
    assert sorted(p.name for p in out.iterdir()) == sorted(kept + ["s00.csv"])


def test_the_progress_bar_draws_on_a_terminal_only():
    class Stream:
        def __init__(self, tty):
            self.tty, self.text = tty, ""

        def isatty(self):
            return self.tty

        def write(self, t):
            self.text += t

        def flush(self):
            pass

    for tty, mode, drawn in ((True, "auto", True), (False, "auto", False), (False, "always", True),
                             (True, "never", False)):
        s = Stream(tty)
        bar = batch._Progress(4, mode, s)
        bar.update(1, 0, force=True)
        bar.update(3, 1, force=True)
        bar.finish()
        assert ("batch [" in s.text) == drawn, (tty, mode, s.text)
        if drawn:
            assert "\rbatch [######################........]  75%  3/4 jobs  1 failed  ETA" in s.text, s.text
            assert s.text.endswith("\r") and s.text.rsplit("\r", 2)[1].strip() == "", "the line is cleared"


def test_manifest_errors_name_the_place(tmp_path):
    cases = {"[]": "/: a manifest is an object", '{"jobs": 3}': "/jobs: must be an array",
             '{"jobs": [{"args": []}]}': "/jobs/0/args: must be a non-empty array",
             '{"jobs": [{"args": ["bake", 3]}]}': "/jobs/0/args/1: must be a string",
             '{"jobs": [{"argz": ["bake"]}]}': "/jobs/0/argz: unknown member", "{": "line 1, column 2"}
    for text, expected in cases.items():
        m = tmp_path / "m.json"
        m.write_text(text)
        with pytest.raises(batch.ManifestError, match=expected.replace("[", r"\[")):
            batch.load_manifest(m)
    m.write_text('{"jobs": 3}')
    r = subprocess.run([sys.executable, "-m", "inbetween.batch", str(m)], capture_output=True, text=True)
    assert r.returncode == 2 and r.stderr == f"batch: {m}: /jobs: must be an array of jobs\n", r.stderr


class Processes:
    """Processes this test started, each ended (SIGTERM, then SIGKILL) at the end."""

    def __init__(self):
        self.procs = []

    def start(self, args, log, env=None, cwd=None):
        p = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT, start_new_session=True, env=env, cwd=cwd)
        self.procs.append(p)
        return p

    def end(self):
        for p in self.procs:
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)
        for p in self.procs:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


def test_a_worker_killed_mid_write_loses_nothing(tmp_path, source_dir):
    """dask-scheduler and two dask-worker processes (no nanny: the worker is the process we kill);
    one is killed with SIGKILL while it has an output open; every output still appears, equal to
    the tool's bytes, and no partial or temporary file is left."""
    frame22 = json.loads((source_dir / "examples" / "scenes" / "frame22.json").read_text())
    (tmp_path / "shots").mkdir()
    variants = 3
    for k in range(variants):  # three different scenes (a shifted range), four outputs of each
        scene = dict(frame22, range=[16 + k, 86])
        (tmp_path / "shots" / f"f{k}.json").write_text(json.dumps(scene))
    jobs = [["bake", f"shots/f{i % variants}.json", "--frames", f"{16 + i % variants}:86:0.01", "--progress",
             "never", "-o", f"out/b{i:02d}.csv"] for i in range(12)]
    (tmp_path / "out").mkdir()
    manifest = tmp_path / "manifest.json"
    manifest.write_text(json.dumps({"jobs": [{"args": a} for a in jobs]}))

    procs = Processes()
    log = open(tmp_path / "dask.log", "w")
    try:
        scheduler_file = tmp_path / "scheduler.json"
        # The scheduler's own settings, which the batch reads and reports (allowed-failures) or sizes its
        # tasks by (worker-saturation); it cannot import inbetween (no PYTHONPATH, started in tmp_path):
        # what the batch runs on it must travel by value.
        scheduler_env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        scheduler_env.update(DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES="5",
                             DASK_DISTRIBUTED__SCHEDULER__WORKER_SATURATION="3.0")
        procs.start([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0",
                     "--no-dashboard", "--dashboard-address", "127.0.0.1:0", "--scheduler-file", str(scheduler_file)], log,
                    env=scheduler_env, cwd=tmp_path)
        deadline = time.monotonic() + START_TIMEOUT_S
        while not scheduler_file.exists():
            assert time.monotonic() < deadline, (tmp_path / "dask.log").read_text()
            time.sleep(0.05)
        time.sleep(0.1)  # the file is written whole before the scheduler listens; read it once complete
        address = json.loads(scheduler_file.read_text())["address"]
        assert address.startswith("tcp://127.0.0.1:")
        workers = [procs.start([sys.executable, "-m", "distributed.cli.dask_worker", address, "--host", "127.0.0.1",
                                "--nthreads", "1", "--no-nanny", "--no-dashboard", "--dashboard-address", "127.0.0.1:0",
                                "--death-timeout", "60",
                                "--local-directory", str(tmp_path / f"w{k}")], log) for k in range(2)]
        result = {}
        runner = threading.Thread(target=lambda: result.update(
            s=batch.run(manifest, scheduler=address, workers=2, progress="never")))
        runner.start()
        victim = workers[1]
        deadline = time.monotonic() + START_TIMEOUT_S
        while not open_unnamed_file(victim.pid, tmp_path / "out"):
            assert runner.is_alive(), "the batch ended before the victim was seen writing"
            assert time.monotonic() < deadline, (tmp_path / "dask.log").read_text()
            time.sleep(0.002)
        victim.send_signal(signal.SIGKILL)
        victim.wait()
        runner.join(timeout=120)
        assert not runner.is_alive()
    finally:
        procs.end()
        log.close()
    s = result["s"]
    assert s["counts"] == {"done": 12, "skipped": 0, "failed": 0}, [j["message"] for j in s["jobs"]]
    assert s["allowed_failures"] == 5, "the scheduler's own setting, not the batch's default"
    assert s["jobs_per_task"] == 2, "12 jobs over 2 workers x ceil(3.0 x 1 thread) = 6 slots: 2 jobs per task first"
    assert "Remove worker" in (tmp_path / "dask.log").read_text(), "the scheduler saw the worker die"
    refs = reference(tmp_path, [(k, jobs[k]) for k in range(variants)])
    for i, args in enumerate(jobs):
        assert (tmp_path / args[-1]).read_bytes() == refs[i % variants], args
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == sorted(pathlib.Path(a[-1]).name for a in jobs)


def test_tasks_shrink_towards_the_end_and_keep_every_job_once_in_order():
    """Guided self-scheduling (batch._chunks): the jobs in order, each once; task sizes never grow,
    stay within 1..MAX_JOBS_PER_TASK, start at unassigned / slots and end at single jobs (two slots
    or more); a fixed
    jobs_per_task cuts equal tasks."""
    for n_jobs in (1, 2, 7, 50, 200, 1000):
        for slots in (1, 2, 4, 8, 32):
            chunks = batch._chunks(list(range(n_jobs)), slots)
            assert [j for c in chunks for j in c] == list(range(n_jobs))
            sizes = [len(c) for c in chunks]
            assert sizes == sorted(sizes, reverse=True), sizes
            assert 1 <= min(sizes) and max(sizes) <= batch.MAX_JOBS_PER_TASK
            first = -(-n_jobs // slots)
            assert sizes[0] == max(1, min(batch.MAX_JOBS_PER_TASK, first))
            if slots > 1:  # one slot: nothing to balance, the remainder is the last task
                assert sizes[-1] == 1, (n_jobs, slots, sizes)
    assert [len(c) for c in batch._chunks(list(range(7)), 2, jobs_per_task=3)] == [3, 3, 1]
    assert batch._chunks([], 2) == []


def test_slots_are_the_tasks_dask_hands_the_workers_at_once():
    """batch._slots follows the scheduler's queue (distributed.scheduler._task_slots_available):
    ceil(saturation × threads) per worker, at least 1; without a queue (inf) two per thread."""
    two_single = [{"nthreads": 1}, {"nthreads": 1}]
    assert batch._slots(two_single, 1.0) == 2
    assert batch._slots(two_single, 1.1) == 4  # ceil(1.1) = 2 each: one running, one waiting
    assert batch._slots([{"nthreads": 8}, {"nthreads": 4}], 1.1) == 9 + 5
    assert batch._slots([{"nthreads": 8}], 0.5) == 4
    assert batch._slots([{"nthreads": 3}], float("inf")) == 6
    assert batch._slots([], 1.0) == 1  # no worker yet: one task at a time until one comes


@pytest.mark.parametrize("inline_below_s", [0.0, 3600.0], ids=["finished-behind", "finished-at-once"])
def test_a_tasks_jobs_finished_behind_or_at_once_give_the_tools_bytes(tmp_path, rng, monkeypatch, inline_below_s):
    """run_jobs in this process (no Dask): with every finish counted slow, each job's outputs are
    synced and named in the second thread while the next job computes; with none, at once.  Either
    way the outputs are the tool's bytes, nothing else is left, and a job whose output folder is
    missing fails with the tool's message without stopping the others."""
    monkeypatch.setattr(batch, "FINISH_INLINE_BELOW_S", inline_below_s)
    finished_in = []  # the thread that finished each job's outputs: which path was taken
    finish = batch._finish_job

    def traced_finish(pending):
        finished_in.append(threading.current_thread().name)
        return finish(pending)

    monkeypatch.setattr(batch, "_finish_job", traced_finish)
    write_scenes(tmp_path, 6, rng)
    (tmp_path / "out").mkdir()
    jobs = [["bake", f"shots/s{k:02d}.json", "--frames", "0:20:0.5", "-o", f"out/s{k:02d}.csv"] for k in range(6)]
    jobs.insert(3, ["bake", "shots/s00.json", "-o", "missing/s00.csv"])
    results = batch.run_jobs(jobs, str(tmp_path))
    assert [r["exit_code"] for r in results] == [0, 0, 0, 2, 0, 0, 0]
    assert results[3]["message"] == f"inbetween: {tmp_path / 'missing' / 's00.csv'}: cannot open for writing: No such file or directory"
    refs = reference(tmp_path, [(i, a) for i, a in enumerate(jobs) if i != 3])
    for i, args in enumerate(jobs):
        if i != 3:
            assert (tmp_path / args[-1]).read_bytes() == refs[i], args
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == [f"s{k:02d}.csv" for k in range(6)]
    here = threading.current_thread().name
    if inline_below_s == 0:  # the first finish counts slow: every later one is behind
        assert finished_in[0] == here and all(t.startswith("inbetween-finish") for t in finished_in[1:]), finished_in
    else:
        assert finished_in == [here] * len(jobs), finished_in
