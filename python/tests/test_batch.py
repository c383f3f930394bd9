"""python3 -m icm.batch: a LocalCluster of 2 workers and a serial run over the bundled meshes
and broken files (truncated, non-manifold, an infinite coordinate, a crash), against each other,
against icm_param one mesh at a time and against icm_param's own batch (-O); a cluster made by
`dask scheduler` and `dask worker` (--scheduler); --resume, --timeout, --max-memory, the options,
the usage errors.

The two big runs are made once (module-scoped fixtures) and checked by several tests."""

import json
import os
import shutil
import subprocess
import sys
import time

import pytest

import icm
from conftest import DATA, ICM_PARAM, MESHES

# The broken inputs, each with what its row's error must say.
BROKEN = {
    "truncated.off": "the file ends after 1091 of the 3671 faces its header announces",
    "nonmanifold.off": "a non-manifold edge",
    "infinite.off": "non-finite coordinate 'inf'",
    "crash.off": "crashed: signal 11 (SIGSEGV)",
}
CRASH = {"ICM_BATCH_TEST_CRASH": "crash.off"}  # the test hook of icm/batch.py
KEY_FIGURES = ("vertices", "faces", "charts", "cones", "seam_edges", "flipped_faces")


def batch(*args, cwd, environment=None):
    """Runs python3 -m icm.batch ARGS in `cwd`."""
    return subprocess.run([sys.executable, "-m", "icm.batch", *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=300, env=dict(os.environ, **(environment or {})))


def summary(directory):
    """The rows of directory/summary.jsonl."""
    with open(os.path.join(directory, "summary.jsonl"), encoding="utf-8") as lines:
        return [json.loads(line) for line in lines]


def without_seconds(row):
    return {key: value for key, value in row.items() if not key.startswith("seconds")}


def write_broken_files(directory):
    """The broken inputs of BROKEN, and repaired.off: a grid with a face reversed and a vertex in
    no face, which read_mesh repairs."""
    with open(DATA / "three_peaks.off", encoding="utf-8") as mesh:
        lines = mesh.read().splitlines(keepends=True)
    (directory / "truncated.off").write_text("".join(lines[:3000]))  # 1091 of the 3671 faces
    (directory / "nonmanifold.off").write_text(  # three triangles on the edge 0-1
        "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n")
    (directory / "infinite.off").write_text("OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\ninf 1 0\n3 0 1 2\n3 1 3 2\n")
    shutil.copy(DATA / "pig.off", directory / "crash.off")  # good, but the hook crashes it
    n = 5
    vertices = [(i, j, 0.1 * (i * j % 3)) for j in range(n) for i in range(n)] + [(9, 9, 9)]
    faces = []
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            faces += [(a, a + 1, a + n + 1), (a, a + n + 1, a + n)]
    faces[5] = faces[5][::-1]
    (directory / "repaired.off").write_text(
        f"OFF\n{len(vertices)} {len(faces)} 0\n" + "".join("%g %g %g\n" % v for v in vertices)
        + "".join("3 %d %d %d\n" % f for f in faces))


@pytest.fixture(scope="module")
def work(tmp_path_factory):
    """A directory with the broken files, where the batches run; the inputs as given to them:
    the bundled meshes by absolute path, the others relative to it."""
    directory = tmp_path_factory.mktemp("batch")
    write_broken_files(directory)
    inputs = [str(mesh) for mesh in MESHES] + ["repaired.off"] + list(BROKEN)
    return directory, inputs


@pytest.fixture(scope="module")
def dask_run(work):
    """The inputs on a LocalCluster of 2 workers: half on the command line, half in a --list
    file with a comment and a blank line."""
    directory, inputs = work
    half = len(inputs) // 2
    (directory / "inputs.txt").write_text("# the second half\n\n" + "\n".join(inputs[half:]) + "\n")
    run = batch(*inputs[:half], "--list", "inputs.txt", "-O", "dask_out", "--workers", 2, cwd=directory,
                environment=CRASH)
    return run, summary(directory / "dask_out")


@pytest.fixture(scope="module")
def serial_run(work):
    directory, inputs = work
    run = batch(*inputs, "-O", "serial_out", "--serial", cwd=directory, environment=CRASH)
    return run, summary(directory / "serial_out")


@pytest.mark.parametrize("name", ["dask_run", "serial_run"])
def test_rows_status_and_progress(name, work, request):
    """Exit status 1 (some failed); one row per input, in input order; a progress line per
    mesh; the last line's counts."""
    directory, inputs = work
    run, rows = request.getfixturevalue(name)
    outdir = "dask_out" if name == "dask_run" else "serial_out"
    assert run.returncode == 1, run.stderr
    assert [row["input"] for row in rows] == inputs
    assert sum(line.startswith("icm.batch: [") for line in run.stderr.splitlines()) == len(inputs)
    last = run.stderr.splitlines()[-1]
    assert last.startswith(f"icm.batch: {len(inputs) - len(BROKEN)} of {len(inputs)} meshes written to {outdir}, "
                           f"{len(BROKEN)} failed ({outdir}/summary.jsonl), "), last


@pytest.mark.parametrize("name", ["dask_run", "serial_run"])
def test_good_written_broken_failed(name, work, request):
    """Every good mesh written to OUTDIR/STEM.obj; every broken one failed with its reason and
    no output."""
    directory, _ = work
    _, rows = request.getfixturevalue(name)
    outdir = "dask_out" if name == "dask_run" else "serial_out"
    for row in rows:
        stem = os.path.splitext(os.path.basename(row["input"]))[0]
        assert row["output"] == os.path.join(outdir, stem + ".obj")
        assert row["seconds"] > 0
        file_name = os.path.basename(row["input"])
        if file_name in BROKEN:
            assert row["status"] == "failed" and BROKEN[file_name] in row["error"], row
            assert "vertices" not in row
            assert not (directory / row["output"]).exists()
        else:
            assert row["status"] == "ok" and row["error"] == "", row
            assert (directory / row["output"]).stat().st_size > 0
            assert row["vertices"] > 0 and "log_area_distortion" in row


def test_dask_equals_serial(work, dask_run, serial_run):
    """The same rows (but the seconds and OUTDIR) and byte-identical output files."""
    directory, _ = work
    for dask_row, serial_row in zip(dask_run[1], serial_run[1]):
        assert dask_row["output"].replace("dask_out", "serial_out", 1) == serial_row["output"]
        dask_row = dict(without_seconds(dask_row), output=serial_row["output"])
        assert dask_row == without_seconds(serial_row)
        if serial_row["status"] == "ok":
            dask_file = directory / "dask_out" / os.path.basename(serial_row["output"])
            assert dask_file.read_bytes() == (directory / serial_row["output"]).read_bytes()


def test_rows_match_icm_param(work, dask_run, tmp_path):
    """Each row's figures are those of icm_param's --json line on the same input, its errors
    icm_param's (the inputs as given name the files alike); repaired.off's repairs too."""
    directory, _ = work
    for row in dask_run[1]:
        run = subprocess.run([ICM_PARAM, row["input"], "-o", str(tmp_path / "out.obj"), "--json", "--quiet"],
                             cwd=directory, capture_output=True, text=True, timeout=300)
        expected = json.loads(run.stdout)
        if row["input"] == "crash.off":
            assert "error" not in expected  # the crash is the hook's, not the mesh's
            continue
        if row["status"] == "failed":
            assert row["error"] == expected["error"]
            continue
        for key in KEY_FIGURES + ("repairs", "isolated_vertices_dropped", "vertices_split", "faces_reoriented"):
            assert row[key] == expected[key], (row["input"], key)
        assert row["log_area_distortion"] == pytest.approx(expected["log_area_distortion"], rel=1e-9, abs=1e-300)
        # every key of icm_param's line but the paths, which the row has as given
        assert set(expected) - {"input", "output"} <= set(row)
    repaired = next(row for row in dask_run[1] if row["input"] == "repaired.off")
    assert repaired["isolated_vertices_dropped"] == 1 and repaired["faces_reoriented"] == 1


def test_rows_match_icm_param_batch(work, serial_run):
    """icm_param's own batch (-O) on the same inputs: the same rows, key for key but the
    seconds and the output directory, and the same files."""
    directory, inputs = work
    run = subprocess.run([ICM_PARAM, *inputs, "-O", "cli_out", "-j", "2", "--quiet"], cwd=directory,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 1, run.stderr  # the broken files; crash.off is good to icm_param
    for cli_row, row in zip(summary(directory / "cli_out"), serial_run[1]):
        assert cli_row["input"] == row["input"]
        if row["input"] == "crash.off":
            continue
        assert dict(without_seconds(cli_row), output=row["output"]) == without_seconds(row)
        if row["status"] == "ok":
            cli_file = directory / "cli_out" / os.path.basename(row["output"])
            assert cli_file.read_bytes() == (directory / row["output"]).read_bytes()


def test_resume(work):
    """--resume skips an ok input whose output exists (its row kept as it was), runs the others
    again, ignores a row a killed batch cut short; without --resume the summary is replaced."""
    directory, _ = work
    inputs = [str(DATA / "three_peaks.off"), str(DATA / "eight.off"), "truncated.off"]
    assert batch(*inputs, "-O", "resume_out", "--serial", cwd=directory).returncode == 1
    first = summary(directory / "resume_out")
    kept = directory / first[0]["output"]
    written = kept.stat().st_mtime_ns
    (directory / first[1]["output"]).unlink()  # eight: to be run again
    with open(directory / "resume_out" / "summary.jsonl", "a", encoding="utf-8") as journal:
        journal.write('{"input": "' + inputs[1] + '", "status": "o')  # a line cut short

    run = batch(*inputs, "-O", "resume_out", "--serial", "--resume", cwd=directory)
    assert run.returncode == 1
    assert "3 meshes written to resume_out (1 done before, skipped), 1 failed" in run.stderr
    assert sum(line.startswith("icm.batch: [") for line in run.stderr.splitlines()) == 2
    again = summary(directory / "resume_out")
    assert [row["input"] for row in again] == inputs
    assert again[0] == first[0] and kept.stat().st_mtime_ns == written
    assert again[1]["status"] == "ok" and again[1]["seconds"] != first[1]["seconds"]
    assert (directory / again[1]["output"]).exists()
    assert again[2]["status"] == "failed"

    assert batch(inputs[0], "-O", "resume_out", "--serial", "--quiet", cwd=directory).returncode == 0
    assert [row["input"] for row in summary(directory / "resume_out")] == inputs[:1]


def test_timeout_and_memory(work):
    """A mesh past --timeout is killed and recorded as timed out; one past --max-memory as out of
    memory; neither leaves an output."""
    directory, _ = work
    mesh = str(DATA / "three_peaks.off")
    run = batch(mesh, "-O", "timeout_out", "--serial", "--timeout", 0.001, cwd=directory)
    assert run.returncode == 1
    row, = summary(directory / "timeout_out")
    assert row["status"] == "failed" and row["error"] == "timed out after 0.001 s"
    assert not (directory / row["output"]).exists()
    # 1 MB: less than the interpreter already holds, so the first allocation of the mesh fails.
    run = batch(mesh, "-O", "memory_out", "--serial", "--max-memory", 1, cwd=directory)
    assert run.returncode == 1
    row, = summary(directory / "memory_out")
    assert row["error"] == "out of memory (--max-memory 1 MB)"
    assert not (directory / row["output"]).exists()


def test_options_reach_the_child(work):
    """--energy, --cones, --atlas, --padding, --format, --metric and --boundary: the row is
    parameterize's with the same options, the file a PLY."""
    directory, _ = work
    mesh = DATA / "sphere966.off"
    run = batch(mesh, "-O", "options_out", "--serial", "--quiet", "--energy", "area", "--cones", 6, "--atlas", 256,
                "--padding", 2, "--format", "ply", cwd=directory)
    assert run.returncode == 0 and run.stderr == ""
    row, = summary(directory / "options_out")
    V, F, _ = icm.read_mesh(str(mesh))
    report = icm.parameterize(V, F, energy="area", cones=6, atlas=256, padding=2).report
    for key in ("energy", "cones", "atlas_size", "atlas_padding", "seam_edges", "log_area_distortion"):
        assert row[key] == report[key], key
    assert row["output"] == "options_out/sphere966.ply"
    assert (directory / row["output"]).read_bytes().startswith(b"ply")

    # --metric and --boundary on a disk: the figures of parameterize with the same options.
    mesh = DATA / "nefertiti.off"
    run = batch(mesh, "-O", "border_out", "--serial", "--quiet", "--metric", "circle-packing", "--boundary", "circle",
                cwd=directory)
    assert run.returncode == 0, run.stderr
    row, = summary(directory / "border_out")
    V, F, _ = icm.read_mesh(str(mesh))
    report = icm.parameterize(V, F, metric="circle-packing", boundary="circle").report
    for key in ("metric", "boundary", "circle_deviation", "log_area_distortion"):
        assert row[key] == report[key], key


def test_usage_errors(work, tmp_path):
    """Exit status 2 and the reason, before any work: two inputs on one output, no input, a
    missing --list file, one naming no input, --padding without --atlas."""
    directory, _ = work
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    shutil.copy(directory / "repaired.off", tmp_path / "a" / "x.off")
    shutil.copy(directory / "repaired.off", tmp_path / "b" / "x.off")
    run = batch("a/x.off", "b/x.off", "-O", "out", "--serial", cwd=tmp_path)
    assert run.returncode == 2
    assert "'a/x.off' and 'b/x.off' would both be written to 'out/x.obj'" in run.stderr
    assert not (tmp_path / "out").exists()

    (tmp_path / "comments.txt").write_text("# nothing\n\n")
    for args, reason in [((), "no input file"),
                         (("--list", "missing.txt"), "--list: cannot read 'missing.txt': no such file"),
                         (("--list", "comments.txt"), "--list 'comments.txt' names no input file"),
                         (("a/x.off", "--padding", 3), "--padding 3 needs --atlas SIZE"),
                         (("a/x.off", "--serial", "--workers", 2), "not allowed with argument")]:
        run = batch(*args, "-O", "out", cwd=tmp_path)
        assert run.returncode == 2 and reason in run.stderr, (args, run.stderr)
        assert not (tmp_path / "out").exists()


def test_crash_hook_is_inert_without_the_variable(work):
    """crash.off is a good mesh: without ICM_BATCH_TEST_CRASH it is written."""
    directory, _ = work
    environment = {key: value for key, value in os.environ.items() if key != "ICM_BATCH_TEST_CRASH"}
    run = subprocess.run([sys.executable, "-m", "icm.batch", "crash.off", "-O", "hook_out", "--serial", "--quiet"],
                         cwd=directory, capture_output=True, text=True, timeout=300, env=environment)
    assert run.returncode == 0, run.stderr
    assert summary(directory / "hook_out")[0]["status"] == "ok"


@pytest.fixture
def scheduler(tmp_path):
    """A Dask cluster as the deployment tools make one: `dask scheduler` and a `dask worker`
    (one process, one thread) joined to it; its address."""
    scheduler_file = tmp_path / "scheduler.json"
    common = ["--scheduler-file", str(scheduler_file), "--no-dashboard"]
    processes = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                                   "--port", "0", *common], cwd=tmp_path, stderr=subprocess.DEVNULL)]
    try:
        for _ in range(600):  # the scheduler writes its address once it listens
            if scheduler_file.exists() and scheduler_file.stat().st_size > 0:
                break
            time.sleep(0.05)
        address = json.loads(scheduler_file.read_text())["address"]
        processes.append(subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", "--nthreads", "1",
                                           *common], cwd=tmp_path, stderr=subprocess.DEVNULL))
        yield address
    finally:
        for process in processes:
            process.terminate()
            process.wait(timeout=60)


def test_existing_cluster(work, scheduler, serial_run):
    """--scheduler ADDRESS: the meshes run on that cluster's worker, the rows are the serial
    run's, a crash there is recorded too."""
    directory, inputs = work
    chosen = [inputs[0], "crash.off", "truncated.off"]
    run = batch(*chosen, "-O", "cluster_out", "--scheduler", scheduler, cwd=directory, environment=CRASH)
    assert run.returncode == 1, run.stderr
    serial_rows = {row["input"]: row for row in serial_run[1]}
    for row in summary(directory / "cluster_out"):
        expected = dict(without_seconds(serial_rows[row["input"]]), output=row["output"])
        assert without_seconds(row) == expected
