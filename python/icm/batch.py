"""Parameterize many meshes, each in a process of its own, on a Dask cluster or in this process.

    python3 -m icm.batch [INPUT ...] [--list FILE] -O OUTDIR
                         [--scheduler ADDRESS | --workers N | --serial]
                         [--format obj|ply|gltf|glb] [--cones auto|N] [--energy NAME]
                         [--metric NAME] [--boundary NAME] [--keep-overlaps]
                         [--atlas SIZE] [--padding PX] [--timeout SECONDS]
                         [--max-memory MB] [--resume] [--quiet]

Each INPUT is read, parameterized and written to OUTDIR/<its stem>.<format> by a child process
(``python3 -m icm.batch --one ...``, internal), so that a mesh that crashes, runs past --timeout
or past --max-memory fails alone. A row per mesh goes to OUTDIR/summary.jsonl. The children run
as tasks of a Dask cluster (``--scheduler`` joins one, ``--workers N`` starts a local one, the
default) or one after the other in this process (``--serial``, which needs no Dask). The
semantics are those of ``icm_param IN... -O OUTDIR -j N``; doc/batch.md has the details.

ICM_BATCH_TEST_CRASH (test-only): a child whose input has this file name kills itself with
SIGSEGV, so that the tests can check how a crash is recorded.
"""

import argparse
import contextlib
import dataclasses
import json
import math
import os
import re
import signal
import subprocess
import sys
import time

import icm

SUMMARY = "summary.jsonl"
FORMATS = ("obj", "ply", "gltf", "glb")
PREFIX = "icm.batch: "
CRASH_HOOK = "ICM_BATCH_TEST_CRASH"
# A child is one of several processes on the machine's cores, and BLAS threads of its own
# would also make its figures depend on the thread count: one thread each.
CHILD_ENVIRONMENT = {"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}


class UsageError(Exception):
    """A wrong command line: the message is the reason; exit status 2."""


@dataclasses.dataclass(frozen=True)
class Job:
    """One mesh to run, everything a Dask task needs (picklable: plain fields only)."""

    input: str  # the path as given: the row's "input"
    output: str  # OUTDIR/STEM.FORMAT with OUTDIR as given: the row's "output"
    directory: str  # the batch's working directory, where `input` and `output` are
    parameters: tuple  # the child's options: --cones, --energy, --atlas, --padding, --max-memory
    timeout: float  # seconds, 0 for none
    max_memory: float  # megabytes, 0 for none
    environment: tuple  # (name, value) pairs set in the child's environment


# --- the command line ------------------------------------------------------------------


class _Parser(argparse.ArgumentParser):
    """argparse, with the usage errors worded as icm_param's: the usage, then the reason."""

    def error(self, message):
        self.print_usage(sys.stderr)
        self.exit(2, PREFIX + message + "\n")


def _cone_count(text):
    """--cones: "auto" or a count from 0 to 100000, as icm_param takes."""
    if text == "auto":
        return text
    if re.fullmatch(r"[0-9]+", text) and int(text) <= 100000:
        return int(text)
    raise argparse.ArgumentTypeError(f"takes 'auto' or a count from 0 to 100000, not '{text}'")


def _whole(low, high, what):
    """An argparse type: a whole number from `low` to `high`."""

    def parse(text):
        if re.fullmatch(r"[0-9]+", text) and low <= int(text) <= high:
            return int(text)
        raise argparse.ArgumentTypeError(f"takes {what}, a whole number from {low} to {high}, not '{text}'")

    return parse


def _positive(what):
    """An argparse type: a finite number > 0."""

    def parse(text):
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if value > 0 and math.isfinite(value):
            return value
        raise argparse.ArgumentTypeError(f"takes {what} > 0, not '{text}'")

    return parse


def make_parser():
    """The command line of a batch."""
    parser = _Parser(
        prog="python3 -m icm.batch",
        description="Parameterize many meshes, each in a process of its own, on a Dask cluster "
        "(doc/batch.md). Exit status: 0 when every mesh is written, 1 when some failed "
        "(OUTDIR/summary.jsonl says why), 2 on a usage error.",
    )
    parser.add_argument("inputs", nargs="*", metavar="INPUT", help="a mesh: OFF, OBJ, PLY or STL")
    parser.add_argument("--list", metavar="FILE", help="also the inputs named in FILE, one path a line ('#' comments)")
    parser.add_argument("-O", "--output-dir", metavar="OUTDIR", required=True,
                        help="write each INPUT's output to OUTDIR/NAME.FORMAT, and OUTDIR/summary.jsonl")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS", help="join the Dask cluster of this scheduler (tcp://host:8786)")
    where.add_argument("--workers", metavar="N", type=_whole(1, 4096, "the number of workers"),
                       help="start a local Dask cluster of N single-threaded workers (the default, N = the cores)")
    where.add_argument("--serial", action="store_true", help="run the meshes one after the other, without Dask")
    parser.add_argument("--format", choices=FORMATS, default="obj", help="the outputs' format (default obj)")
    parser.add_argument("--cones", type=_cone_count, default="auto", metavar="auto|N", help="cones: auto or a count")
    parser.add_argument("--energy", default="entropy", metavar="NAME", help="one of " + ", ".join(icm.ENERGIES))
    parser.add_argument("--metric", choices=icm.METRICS, default=icm.METRICS[0], metavar="NAME",
                        help="the discrete conformal metric: " + ", ".join(icm.METRICS))
    parser.add_argument("--boundary", choices=icm.BOUNDARIES, default="free", metavar="NAME",
                        help="the border condition: " + ", ".join(icm.BOUNDARIES))
    parser.add_argument("--keep-overlaps", action="store_true", help="keep a chart that folds over itself")
    parser.add_argument("--atlas", type=_whole(1, 65536, "the texture size"), metavar="SIZE",
                        help="pack the charts in a SIZE x SIZE texture")
    parser.add_argument("--padding", type=_whole(0, 32767, "the padding"), metavar="PX",
                        help="with --atlas: texels between charts (default 4)")
    parser.add_argument("--timeout", type=_positive("seconds"), metavar="SECONDS",
                        help="a mesh still running after SECONDS is stopped and fails")
    parser.add_argument("--max-memory", type=_positive("megabytes"), metavar="MB",
                        help="a mesh's process may use at most MB megabytes of address space")
    parser.add_argument("--resume", action="store_true",
                        help="skip the inputs whose row in OUTDIR/summary.jsonl says ok and whose output exists")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress lines")
    return parser


def check_options(args):
    """The checks argparse cannot make alone; raises UsageError."""
    if args.energy not in icm.ENERGIES:
        raise UsageError(f"--energy takes one of {', '.join(icm.ENERGIES)}, not '{args.energy}'")
    if args.padding is not None and args.atlas is None:
        raise UsageError(f"--padding {args.padding} needs --atlas SIZE")
    if args.format in ("gltf", "glb") and not icm.HAS_GLTF:
        raise UsageError(f"--format {args.format}: this build of ICM writes no glTF (icm.HAS_GLTF is False)")


def read_input_list(path):
    """The input paths of a --list file: one a line, blank lines and '#' lines skipped."""
    if not os.path.isfile(path):
        raise UsageError(f"--list: cannot read '{path}': no such file")
    try:
        with open(path, encoding="utf-8") as lines:
            entries = [line.strip() for line in lines]
    except (OSError, UnicodeDecodeError) as error:
        raise UsageError(f"--list: cannot read '{path}': {error}") from None
    return [entry for entry in entries if entry and not entry.startswith("#")]


def output_path(output_dir, input, format):
    """OUTDIR/STEM.FORMAT: where the batch writes `input`'s output (the stem as C++'s
    std::filesystem::path::stem, which os.path.splitext agrees with)."""
    stem = os.path.splitext(os.path.basename(input))[0]
    return os.path.join(output_dir, stem + "." + format)


def batch_inputs(args):
    """The positional inputs, then those of --list, each once, in order; raises UsageError
    when there is none or when two would be written to one output."""
    inputs = list(args.inputs)
    if args.list is not None:
        inputs += read_input_list(args.list)
    inputs = list(dict.fromkeys(inputs))  # an input listed twice runs once
    if not inputs:
        raise UsageError("no input file" if args.list is None else f"--list '{args.list}' names no input file")
    input_of_output = {}
    for input in inputs:
        output = output_path(args.output_dir, input, args.format)
        other = input_of_output.setdefault(output, input)
        if other != input:
            raise UsageError(f"'{other}' and '{input}' would both be written to '{output}': "
                             "give them different names, or run them in two batches")
    return inputs


def make_output_dir(path):
    """Creates OUTDIR when missing; raises UsageError when it cannot be."""
    if os.path.exists(path) and not os.path.isdir(path):
        raise UsageError(f"-O: '{path}' is not a directory")
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as error:
        raise UsageError(f"-O: cannot create '{path}': {error.strerror}") from None


def child_parameters(args):
    """The options every child gets: the parameterization's, and the memory limit."""
    parameters = ["--cones", str(args.cones), "--energy", args.energy, "--metric", args.metric,
                  "--boundary", args.boundary]
    if args.keep_overlaps:
        parameters.append("--keep-overlaps")
    if args.atlas is not None:
        parameters += ["--atlas", str(args.atlas), "--padding", str(4 if args.padding is None else args.padding)]
    if args.max_memory is not None:
        parameters += ["--max-memory", repr(args.max_memory)]
    return tuple(parameters)


def child_environment():
    """The variables a child gets: one BLAS thread; the crash hook when the tests set it here
    (passed along so that it reaches children on any worker)."""
    environment = dict(CHILD_ENVIRONMENT)
    if os.environ.get(CRASH_HOOK):
        environment[CRASH_HOOK] = os.environ[CRASH_HOOK]
    return tuple(sorted(environment.items()))


def make_jobs(args, inputs):
    """A Job per input."""
    parameters, environment = child_parameters(args), child_environment()
    jobs = []
    for input in inputs:
        output = output_path(args.output_dir, input, args.format)
        jobs.append(Job(input, output, os.getcwd(), parameters, args.timeout or 0.0, args.max_memory or 0.0,
                        environment))
    return jobs


# --- one mesh: the child, and the task that runs it --------------------------------------


def _limit_memory(megabytes):
    """Caps this process's address space (the child's --max-memory)."""
    import resource

    size = int(megabytes * 1024 * 1024)
    resource.setrlimit(resource.RLIMIT_AS, (size, size))


def _crash_if_asked(input):
    """The test hook: SIGSEGV when ICM_BATCH_TEST_CRASH names this input's file (no core file)."""
    if os.environ.get(CRASH_HOOK) and os.environ[CRASH_HOOK] == os.path.basename(input):
        import resource

        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        os.kill(os.getpid(), signal.SIGSEGV)


# The counts of icm_param's --json line that read_mesh's repairs stand for: read_mesh repairs
# the file before parameterize sees it, so parameterize's report counts none of them.
_REPAIR_COUNTS = (
    ("isolated_vertices_dropped", re.compile(r"dropped (\d+) isolated vert")),
    ("vertices_split", re.compile(r"split \d+ non-manifold vert.*\((\d+) added\)")),
    ("faces_reoriented", re.compile(r"reoriented (\d+) face")),
)


def figures_of(report, repairs):
    """The row's figures: parameterize's report with the repairs read_mesh made to the file,
    as icm_param's --json line has them."""
    figures = dict(report)
    figures["repairs"] = list(repairs) + list(report.get("repairs", []))
    for key, pattern in _REPAIR_COUNTS:
        for repair in repairs:
            match = pattern.match(repair)
            if match and key in figures:
                figures[key] += int(match.group(1))
    return figures


def _json_safe(value):
    """`value` with the numbers JSON has no word for (NaN, infinities) as null, as
    icm_param's JSON writes them."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {key: _json_safe(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(item) for item in value]
    return value


def _print_json(value):
    print(json.dumps(_json_safe(value), allow_nan=False), flush=True)


def run_child(argv):
    """The child (``--one INPUT OUTPUT ...``): reads, parameterizes and writes one mesh, and
    prints its figures, or {"error": reason}, as the last line of stdout."""
    parser = _Parser(prog="python3 -m icm.batch --one")
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--cones", type=_cone_count, default="auto")
    parser.add_argument("--energy", default="entropy")
    parser.add_argument("--metric", default=icm.METRICS[0])
    parser.add_argument("--boundary", default="free")
    parser.add_argument("--keep-overlaps", action="store_true")
    parser.add_argument("--atlas", type=int)
    parser.add_argument("--padding", type=int, default=4)
    parser.add_argument("--max-memory", type=float)
    args = parser.parse_args(argv)
    if args.max_memory:
        _limit_memory(args.max_memory)
    _crash_if_asked(args.input)
    try:
        start = time.perf_counter()
        V, F, repairs = icm.read_mesh(args.input)
        read = time.perf_counter()
        result = icm.parameterize(V, F, cones=args.cones, energy=args.energy, metric=args.metric,
                                  boundary=args.boundary, keep_overlaps=args.keep_overlaps, atlas=args.atlas,
                                  padding=args.padding)
        parameterized = time.perf_counter()
        icm.write_mesh(args.output, V, F, result.uv, result.fuv)
        written = time.perf_counter()
    except icm.Error as error:
        _print_json({"error": str(error)})
        return 1
    except MemoryError:
        _print_json({"error": "out of memory", "out_of_memory": True})
        return 1
    figures = figures_of(result.report, repairs)
    # The keys of icm_param's line that parameterize cannot know: icm.batch reads no polygon
    # (no --triangulate) and times the reading and the writing here.
    figures.update(faces_triangulated=0, seconds_read=read - start, seconds_write=written - parameterized,
                   seconds_total=written - start)
    _print_json(figures)
    return 0


def _last_line(text):
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    return lines[-1] if lines else ""


def _json_object(line):
    try:
        value = json.loads(line)
    except ValueError:
        return None
    return value if isinstance(value, dict) else None


def signal_name(number):
    """SIGSEGV for 11."""
    try:
        return signal.Signals(number).name
    except ValueError:
        return "unknown signal"


def outcome(returncode, stdout, stderr, max_memory):
    """(figures, "") of a child that wrote its output, or (None, why it failed)."""
    line = _json_object(_last_line(stdout))
    limit = f" (--max-memory {max_memory:g} MB)" if max_memory else ""
    if returncode < 0:
        reason = f"crashed: signal {-returncode} ({signal_name(-returncode)})"
        # Some libraries do not check their allocations: under a limit, a crash is likely it.
        return None, reason + (", perhaps out of memory" + limit if max_memory else "")
    if returncode == 0:
        if line is not None and "error" not in line:
            return line, ""
        return None, "the process printed no figures"
    if line is not None and isinstance(line.get("error"), str):
        reason = line["error"]
    else:
        last = _last_line(stderr)
        reason = f"the process exited with status {returncode}" + (": " + last if last else "")
    # A MemoryError, an allocation refused in C++ (std::bad_alloc) or by numpy, or one that
    # Python met outside the guarded calls (its traceback ends in "MemoryError").
    if (line or {}).get("out_of_memory") or (max_memory and "memory" in reason.lower()):
        return None, "out of memory" + limit
    return None, reason


def make_row(job, reason, seconds, figures):
    """A summary row: what the batch knows, then (when ok) the child's figures."""
    row = {"input": job.input, "output": job.output, "status": "failed" if reason else "ok",
           "error": reason, "seconds": seconds}
    for key, value in (figures or {}).items():
        if key not in row:
            row[key] = value
    return row


def _paths_here(job):
    """(working directory, input, output) of the child on this machine: the batch's directory
    and the paths as given, so that the messages name the input as icm_param's do; absolute
    paths on a worker that has no such directory (a cluster whose workers share the files but
    not the batch's working directory)."""
    if os.path.isdir(job.directory):
        return job.directory, job.input, job.output
    return None, os.path.join(job.directory, job.input), os.path.join(job.directory, job.output)


def run_job(job):
    """Runs one mesh in a child process and returns its row; the task of a Dask worker. The
    child is killed when it runs past the job's timeout."""
    directory, input, output = _paths_here(job)
    command = [sys.executable, "-m", "icm.batch", "--one", input, output, *job.parameters]
    environment = dict(os.environ, **dict(job.environment))
    start = time.monotonic()
    try:
        done = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, text=True, errors="replace",
                              cwd=directory, env=environment, timeout=job.timeout or None)
    except subprocess.TimeoutExpired:  # subprocess.run killed it (SIGKILL) and waited
        return make_row(job, f"timed out after {job.timeout:g} s", time.monotonic() - start, None)
    except OSError as error:
        return make_row(job, f"cannot start a process: {error}", time.monotonic() - start, None)
    figures, reason = outcome(done.returncode, done.stdout, done.stderr, job.max_memory)
    return make_row(job, reason, time.monotonic() - start, figures)


# --- where the jobs run ----------------------------------------------------------------


def serial_rows(jobs):
    """(index, row) of each job, run one after the other in this process's loop."""
    for index, job in jobs:
        yield index, run_job(job)


def _largest_first(jobs):
    """The jobs by input size, largest first: a long mesh started last would keep the others'
    workers idle at the end. The rows do not depend on the order."""

    def size(item):
        try:
            return os.path.getsize(os.path.join(item[1].directory, item[1].input))
        except OSError:
            return 0

    return sorted(jobs, key=size, reverse=True)


def dask_rows(client, jobs):
    """(index, row) of each job as the cluster finishes it: each job a task of its own."""
    from distributed import as_completed

    futures = {client.submit(run_job, job, pure=False): (index, job) for index, job in _largest_first(jobs)}
    for future in as_completed(futures):
        index, job = futures[future]
        try:
            row = future.result()
        except Exception as error:  # the worker died, or cannot import icm: the mesh fails alone
            row = make_row(job, f"the Dask task failed: {type(error).__name__}: {error}", 0.0, None)
        future.release()
        yield index, row


@contextlib.contextmanager
def dask_client(scheduler, workers):
    """A distributed.Client of the scheduler at `scheduler`, or of a LocalCluster of
    `workers` single-threaded workers, closed on leaving."""
    import distributed

    if scheduler is not None:
        try:
            client = distributed.Client(scheduler)
        except OSError as error:
            raise OSError(f"cannot connect to the scheduler {scheduler}: {error}") from None
        with client:
            yield client
        return
    # No dashboard: its port may be taken, and a batch has its progress lines.
    with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        yield client


def check_dask():
    """The package distributed; raises UsageError when it is missing."""
    try:
        import distributed

        return distributed
    except ImportError as error:
        raise UsageError(f"a batch on Dask (--workers N, the default, or --scheduler) needs the package "
                         f"distributed ({error}): install it (Debian: python3-distributed), or run with --serial") from None


# --- the summary -----------------------------------------------------------------------


def earlier_rows(summary):
    """The rows of an earlier summary.jsonl by input (the last of each: a resumed batch
    appends); a line a killed batch cut short is not JSON and is ignored."""
    rows = {}
    try:
        with open(summary, encoding="utf-8", errors="replace") as lines:
            for line in lines:
                row = _json_object(line)
                if row is not None and isinstance(row.get("input"), str):
                    rows[row["input"]] = row
    except OSError:
        pass
    return rows


def was_done(row, job):
    """Whether `row` says `job` was done: ok, with its output, which exists."""
    return (row is not None and row.get("status") == "ok" and row.get("output") == job.output
            and os.path.isfile(job.output))


def _dump(row):
    return json.dumps(_json_safe(row), allow_nan=False)


def write_summary(summary, rows):
    """Replaces `summary` with `rows`, one a line, all or nothing."""
    temporary = f"{summary}.tmp-{os.getpid()}"
    try:
        with open(temporary, "w", encoding="utf-8") as out:
            for row in rows:
                out.write(_dump(row) + "\n")
        os.replace(temporary, summary)
    except OSError:
        with contextlib.suppress(OSError):
            os.remove(temporary)
        raise


# --- progress ---------------------------------------------------------------------------


def duration_text(seconds):
    """"12 s", "3 min 20 s", "1 h 5 min": a duration for the progress line."""
    s = int(math.floor(seconds + 0.5))
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60} s"
    return f"{s // 3600} h {s % 3600 // 60} min"


def seconds_text(seconds):
    return f"{seconds:.{2 if seconds < 10 else 1}f} s"


def progress_line(done, to_run, row, elapsed, running):
    """The line of a finished mesh: the count, its outcome, the time so far (`elapsed`) and the
    time left at the pace of the meshes so far (`running`: since they began, after the
    cluster's start)."""
    name = os.path.basename(row["input"])
    if row["status"] == "ok":
        text = f"[{done}/{to_run}] ok {name} ({seconds_text(row['seconds'])})"
    else:
        text = f"[{done}/{to_run}] failed {name}: {row['error']}"
    text += f", elapsed {duration_text(elapsed)}"
    if done < to_run:
        text += f", ETA {duration_text(running / done * (to_run - done))}"
    return PREFIX + text


def final_line(count, failed, skipped, output_dir, summary, elapsed):
    """The batch's last line: how many were written, skipped, failed, and the time."""
    text = f"{count - failed} of {count} meshes written to {output_dir}"
    if skipped:
        text += f" ({skipped} done before, skipped)"
    if failed:
        text += f", {failed} failed ({summary})"
    return PREFIX + text + f", {seconds_text(elapsed)}"


# --- the batch ----------------------------------------------------------------------------


def run_batch(args, jobs, start):
    """Runs the jobs not done before, a row per finished mesh appended to the summary; then
    the summary in input order. Returns the exit status: 0 all ok, 1 some failed."""
    summary = os.path.join(args.output_dir, SUMMARY)
    earlier = earlier_rows(summary) if args.resume else {}
    rows = [earlier.get(job.input) if was_done(earlier.get(job.input), job) else None for job in jobs]
    to_run = [(index, job) for index, job in enumerate(jobs) if rows[index] is None]
    skipped = len(jobs) - len(to_run)

    with contextlib.ExitStack() as stack:
        results = serial_rows(to_run)
        if not args.serial and to_run:
            client = stack.enter_context(dask_client(args.scheduler, args.workers or os.cpu_count() or 1))
            results = dask_rows(client, to_run)
        # Appended and flushed as they come, so that a killed batch keeps them (--resume).
        journal = stack.enter_context(open(summary, "a" if args.resume else "w", encoding="utf-8"))
        failed, started = 0, time.monotonic()
        for done, (index, row) in enumerate(results, start=1):
            rows[index] = row
            journal.write(_dump(row) + "\n")
            journal.flush()
            failed += row["status"] != "ok"
            if not args.quiet:
                now = time.monotonic()
                print(progress_line(done, len(to_run), row, now - start, now - started), file=sys.stderr, flush=True)

    write_summary(summary, [row for row in rows if row is not None])
    if not args.quiet or failed:
        print(final_line(len(jobs), failed, skipped, args.output_dir, summary, time.monotonic() - start),
              file=sys.stderr)
    return 1 if failed else 0


def parse(argv):
    """(the options, the inputs) of a batch's command line; SystemExit(2) after the usage and
    the reason on a usage error (SystemExit(0) after --help)."""
    parser = make_parser()
    args = parser.parse_args(argv)
    try:
        check_options(args)
        inputs = batch_inputs(args)
        if not args.serial:
            check_dask()
        make_output_dir(args.output_dir)
    except UsageError as error:
        parser.error(str(error))
    return args, inputs


def main(argv=None):
    """The command line (`argv`, sys.argv[1:] by default); returns the exit status, also on a
    usage error, so that a program that made its own cluster can run a batch on it."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["--one"]:
        return run_child(argv[1:])
    start = time.monotonic()
    try:
        args, inputs = parse(argv)
    except SystemExit as exit:
        return exit.code
    try:
        return run_batch(args, make_jobs(args, inputs), start)
    except OSError as error:  # the summary cannot be written, a scheduler cannot be reached
        print(PREFIX + str(error), file=sys.stderr)
        return 1


if __name__ == "__main__":
    # Through the module icm.batch, not __main__: Dask pickles the functions of __main__ by
    # value, those of a module by name, which the workers import.
    from icm import batch

    sys.exit(batch.main())
