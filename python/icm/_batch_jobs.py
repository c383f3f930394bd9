"""icm.batch's jobs: a Job per mesh, the task that runs it in a child process and reads the
child's outcome into a summary row, and where the tasks run (in this process, or on a Dask
cluster). Private: icm.batch is the module to use.
"""

import contextlib
import dataclasses
import json
import os
import signal
import subprocess
import sys
import time

from icm._batch_child import CRASH_HOOK
from icm._batch_command_line import UsageError, output_path

# A child is one of several processes on the machine's cores, and BLAS threads of its own
# would also make its figures depend on the thread count: one thread each.
CHILD_ENVIRONMENT = {"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}


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
