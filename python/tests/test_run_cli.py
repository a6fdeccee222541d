"""The tool's commands in-process (inbetween._inbetween._run_cli, apps/inbetween/run.hpp), what the
batch runs in its workers (docs/batch.md): the same bytes and messages as the tool, relative paths
resolved against a folder given (never a chdir), standard streams captured, safe in threads; and
an output that a SIGKILL interrupts leaves nothing behind (O_TMPFILE, apps/inbetween/output.cpp)."""
import os
import pathlib
import signal
import subprocess
import threading
import time

import pytest

from inbetween import _inbetween

run_cli = getattr(_inbetween, "_run_cli", None)
pytestmark = pytest.mark.skipif(run_cli is None, reason="module built without the tool (INBETWEEN_BUILD_APPS off)")

# Frames of the threaded run: enough rows that the 8 runs overlap in time (about 10 ms each).
THREAD_FRAMES = "0:66:0.05"
THREADS = 8


@pytest.fixture
def scene(source_dir):
    return source_dir / "examples" / "scenes" / "bouncing_cube.json"


def test_bake_to_a_file_equals_the_tools_bytes(cli, scene, tmp_path):
    ref = tmp_path / "ref.csv"
    cli("bake", scene, "--frames", "0:20:0.5", "-o", ref)
    code, out, err, inputs, outputs = run_cli(["bake", str(scene), "--frames", "0:20:0.5", "-o", "in.csv"],
                                              str(tmp_path))
    assert (code, out, err) == (0, b"", "")
    assert (tmp_path / "in.csv").read_bytes() == ref.read_bytes()
    assert inputs == [str(scene)] and outputs == [str(tmp_path / "in.csv")]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.csv", "ref.csv"]  # no temporary left


def test_standard_output_and_messages_are_captured(cli, scene, source_dir, tmp_path):
    ref = cli("bake", scene, "--frames", "0:3", "--format", "json")
    code, out, err, _, outputs = run_cli(["bake", str(scene), "--frames", "0:3", "--format", "json"])
    assert (code, err, outputs) == (0, "", [])
    assert out == ref.stdout.encode()
    # convert's channel report goes to standard error: the same text, the same .glb bytes
    ball = source_dir / "examples" / "scenes" / "bouncing_ball.json"
    ref = cli("convert", ball, tmp_path / "ref.glb")
    code, out, err, _, _ = run_cli(["convert", str(ball), "in.glb"], str(tmp_path))
    assert code == 0 and out == b"" and err == ref.stderr and "keys" in err
    assert (tmp_path / "in.glb").read_bytes() == (tmp_path / "ref.glb").read_bytes()


def test_errors_are_the_tools_line_and_exit_code(cli, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"inbetween": 1, "tracks": [{"name": "x", "keys": [{"frame": 2, "value": 0}, '
                   '{"frame": 1, "value": 1}]}]}')
    for args in (["bake", str(bad), "-o", str(tmp_path / "o.csv")],
                 ["bake", str(tmp_path / "missing.json"), "-o", str(tmp_path / "o.csv")],
                 ["bake", "--frames"],
                 ["compress", "clip.bvh", "-o", "out.ibc"],  # a missing clip
                 ["no-such-command"]):
        ref = cli(*args, check=False)
        code, out, err, _, _ = run_cli(args)
        assert (code, out, err) == (ref.returncode, ref.stdout.encode(), ref.stderr), args
        assert code == 2 and err.startswith("inbetween: ") and err.count("\n") == 1, err
    assert not (tmp_path / "o.csv").exists()


def test_relative_paths_resolve_against_the_base_folder_not_the_current_one(scene, tmp_path):
    (tmp_path / "shots").mkdir()
    (tmp_path / "out").mkdir()
    (tmp_path / "shots" / "a.json").write_bytes(scene.read_bytes())
    cwd = os.getcwd()
    code, _, err, inputs, outputs = run_cli(["bake", "shots/a.json", "--frames", "0:2", "-o", "out/a.csv"],
                                            str(tmp_path))
    assert code == 0, err
    assert os.getcwd() == cwd
    assert inputs == [str(tmp_path / "shots" / "a.json")] and outputs == [str(tmp_path / "out" / "a.csv")]
    assert (tmp_path / "out" / "a.csv").read_text().startswith("frame,time,")
    # convert's second positional is its output; "-" is no file
    code, _, err, inputs, outputs = run_cli(["convert", "shots/a.json", "out/a.glb"], str(tmp_path), True)
    assert (code, inputs, outputs) == (0, [str(tmp_path / "shots" / "a.json")], [str(tmp_path / "out" / "a.glb")])
    assert not (tmp_path / "out" / "a.glb").exists(), "plan_only runs nothing"
    code, _, _, inputs, outputs = run_cli(["path", "smooth", "-", "-o", "s.csv"], str(tmp_path), True)
    assert (code, inputs, outputs) == (0, [], [str(tmp_path / "s.csv")])


def test_standard_input_of_an_in_process_run_is_empty(cli, tmp_path):
    args = ["path", "smooth", "-", "-o", str(tmp_path / "s.csv")]
    ref = subprocess.run([os.environ["INBETWEEN_CLI"], *args], stdin=subprocess.DEVNULL, capture_output=True, text=True)
    code, _, err, _, _ = run_cli(args)
    assert (code, err) == (ref.returncode, ref.stderr) and code == 2, err


def test_concurrent_runs_in_threads_give_the_tools_bytes(cli, source_dir, tmp_path):
    scenes = sorted((source_dir / "examples" / "scenes").glob("*.json"))
    scenes = [s for s in scenes if s.name != "surface_walk.json"][:4]  # surface_walk needs its mesh's folder
    refs = {}
    for s in scenes:
        ref = tmp_path / f"ref-{s.stem}.csv"
        cli("bake", s, "-o", ref)
        refs[s] = ref.read_bytes()
    results = {}

    def work(k):
        s = scenes[k % len(scenes)]
        results[k] = (s, run_cli(["bake", str(s), "-o", f"t{k}.csv"], str(tmp_path)))

    threads = [threading.Thread(target=work, args=(k,)) for k in range(THREADS)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for k, (s, (code, out, err, _, _)) in results.items():
        assert (code, out, err) == (0, b"", ""), err
        assert (tmp_path / f"t{k}.csv").read_bytes() == refs[s], k
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]


def test_no_signal_handler_is_installed(scene, tmp_path):
    before = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}
    code, _, _, _, _ = run_cli(["bake", str(scene), "-o", str(tmp_path / "a.csv")])
    assert code == 0
    assert {s: signal.getsignal(s) for s in before} == before
    mask = os.umask(0o22)
    os.umask(mask)
    assert (tmp_path / "a.csv").stat().st_mode & 0o777 == 0o666 & ~mask


def open_unnamed_file(pid, folder):
    """True when process `pid` holds an unnamed (O_TMPFILE) file of `folder` open."""
    try:
        fds = os.listdir(f"/proc/{pid}/fd")
    except OSError:
        return False
    for fd in fds:
        try:
            target = os.readlink(f"/proc/{pid}/fd/{fd}")
        except OSError:
            continue
        if target.startswith(str(folder) + "/") and target.endswith("(deleted)"):
            return True
    return False


def test_the_tool_killed_mid_write_leaves_nothing(cli, source_dir, tmp_path):
    """SIGKILL (no handler can run) while `bake` writes: no output, no temporary file."""
    out = tmp_path / "out"
    out.mkdir()
    scene = source_dir / "examples" / "scenes" / "frame22.json"
    p = subprocess.Popen([os.environ["INBETWEEN_CLI"], "bake", str(scene), "--frames", "16:86:0.002",
                          "--progress", "never", "-o", str(out / "big.csv")])
    try:
        deadline = time.monotonic() + 10
        while not open_unnamed_file(p.pid, out):
            assert p.poll() is None, "the bake ended before it was seen writing"
            assert time.monotonic() < deadline
            time.sleep(0.002)
        p.send_signal(signal.SIGKILL)
    finally:
        p.wait()
    assert p.returncode == -signal.SIGKILL
    assert list(out.iterdir()) == []


def test_deferred_outputs_are_named_by_finish_with_the_tools_bytes(cli, scene, source_dir, tmp_path):
    """_run_cli_deferred: the command writes its files in full but leaves the tool's last step (fsync,
    then the name) to pending.finish(), which gives the tool's bytes, a new file and a replaced one alike."""
    ref = tmp_path / "ref.csv"
    cli("bake", scene, "--frames", "0:20:0.5", "-o", ref)
    ball = source_dir / "examples" / "scenes" / "bouncing_ball.json"
    cli("convert", ball, tmp_path / "ref.glb")
    (tmp_path / "old.glb").write_bytes(b"an older file, replaced whole")
    for args, name, reference in ((["bake", str(scene), "--frames", "0:20:0.5", "-o", "new.csv"], "new.csv", ref),
                                  (["convert", str(ball), "old.glb"], "old.glb", tmp_path / "ref.glb")):
        before = sorted(p.name for p in tmp_path.iterdir())
        code, out, err, _, outputs, pending = _inbetween._run_cli_deferred(args, str(tmp_path))
        assert code == 0 and out == b"" and outputs == [str(tmp_path / name)]
        assert len(pending) == 1
        assert sorted(p.name for p in tmp_path.iterdir()) == before, "nothing named before finish()"
        assert pending.finish() == (0, "")
        assert (tmp_path / name).read_bytes() == reference.read_bytes()
        assert pending.finish() == (0, "")  # once only: nothing left to do
    assert sorted(p.name for p in tmp_path.iterdir()) == ["new.csv", "old.glb", "ref.csv", "ref.glb"]


def test_deferred_outputs_dropped_unfinished_leave_nothing(scene, tmp_path):
    code, _, _, _, _, pending = _inbetween._run_cli_deferred(
        ["bake", str(scene), "--frames", "0:20:0.5", "-o", "dropped.csv"], str(tmp_path))
    assert code == 0 and len(pending) == 1
    del pending
    assert list(tmp_path.iterdir()) == []


def test_a_deferred_output_that_cannot_be_named_fails_with_the_tools_message(scene, tmp_path):
    """The folder removed between the command and finish(): linking the unnamed file fails, reported as
    the tool reports a failed commit (exit 2, one line naming the file and the reason)."""
    folder = tmp_path / "gone"
    folder.mkdir()
    code, _, _, _, _, pending = _inbetween._run_cli_deferred(
        ["bake", str(scene), "--frames", "0:20:0.5", "-o", "gone/out.csv"], str(tmp_path))
    assert code == 0
    folder.rmdir()  # empty: the unnamed file has no name in it
    code, err = pending.finish()
    assert code == 2
    assert err == f"inbetween: {folder / 'out.csv'}: cannot replace the file: No such file or directory\n"
    assert list(tmp_path.iterdir()) == []
