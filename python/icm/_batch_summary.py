"""icm.batch's summary (OUTDIR/summary.jsonl: a row per mesh, read back by --resume) and its
progress lines. Private: icm.batch is the module to use.
"""

import contextlib
import json
import math
import os

from icm._batch_child import _json_safe
from icm._batch_command_line import PREFIX
from icm._batch_jobs import _json_object

SUMMARY = "summary.jsonl"


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
