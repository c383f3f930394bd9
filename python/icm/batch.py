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

import contextlib
import os
import sys
import time

# The parts of a batch, by what they do (icm/_batch_*.py): their public names are icm.batch's,
# also those this file does not use.
from icm._batch_child import CRASH_HOOK, figures_of, run_child  # noqa: F401
from icm._batch_command_line import (  # noqa: F401
    FORMATS, PREFIX, UsageError, batch_inputs, check_options, make_output_dir, make_parser, output_path,
    read_input_list)
from icm._batch_jobs import (  # noqa: F401
    CHILD_ENVIRONMENT, Job, check_dask, child_environment, child_parameters, dask_client, dask_rows, make_jobs,
    make_row, outcome, run_job, serial_rows, signal_name)
from icm._batch_summary import (  # noqa: F401
    SUMMARY, _dump, duration_text, earlier_rows, final_line, progress_line, seconds_text, was_done, write_summary)

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
