#!/usr/bin/python3
"""Time a whole process: wall seconds and peak resident memory of one command, as a JSON row.

    whole_process.py --method NAME --obj MESH.obj [--mesh LABEL] [--time-limit S] [--runs N]
                     [--json-stdout] [--output FILE] -- COMMAND...

Runs COMMAND (a parameterizer's command line reading MESH.obj) and prints one JSON line with
the fields of `compare --json`'s rows that apply: mesh, vertices, faces (counted in MESH.obj),
method, status, seconds (wall time from the start of the process to its end, reading and
writing included; the median over the runs) and peak_rss_mb (the process's maximum resident
set as /usr/bin/time -f %M reports it, else from wait4; the largest over the runs). benchmark/scaling.sh appends these rows
beside compare's, for BFF's command line (method bff) and icm_param's (icm_param_whole).

  --runs N       timed runs, median reported (default: 3 if the first takes < 2 s, else 1,
                 as compare does)
  --time-limit S seconds per run (default 600); a slower run is killed: status "timeout"
  --json-stdout  the command prints JSON (icm_param --json): the numbers seconds_* of its last
                 JSON object are added to the row (the median over the runs), e.g.
                 seconds_parameterize, and its own "status" when it is not "ok"
  --output FILE  the file the command writes; its absence after exit code 0 is a failure

Status: ok; timeout; crashed (signal N); failed (exit code N): the last line of its stderr;
failed: no output file. Never raises for the command's failure: the row says it. The exit
code is 0 when the row was written, 2 on a wrong command line.
"""

import argparse
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time


def count_obj(path):
    """(vertices, faces) of an OBJ file: its v and f lines."""
    v = f = 0
    with open(path, "rb") as fh:
        for line in fh:
            if line.startswith(b"v "):
                v += 1
            elif line.startswith(b"f "):
                f += 1
    return v, f


def last_line(path):
    try:
        with open(path, errors="replace") as fh:
            lines = [ln.strip() for ln in fh if ln.strip()]
    except OSError:
        return ""
    return lines[-1][:200] if lines else ""


def last_json(path):
    """The last line of the file that is a JSON object, or None."""
    found = None
    try:
        with open(path, errors="replace") as fh:
            for ln in fh:
                ln = ln.strip()
                if ln.startswith("{"):
                    try:
                        found = json.loads(ln)
                    except json.JSONDecodeError:
                        pass
    except OSError:
        pass
    return found if isinstance(found, dict) else None


# GNU time measures the peak memory: a child forked from this interpreter and then exec'd
# would count the interpreter's pages it held before the exec in its peak (about 12 MB),
# /usr/bin/time's about 1 MB. Without it, the peak is wait4's, with that floor.
GNU_TIME = "/usr/bin/time"


def gnu_time_report(path):
    """(peak kB, signal or None) from GNU time's -o file: its last line is %M, a line before
    it says 'Command terminated by signal N' when the command was killed by one."""
    try:
        with open(path, errors="replace") as fh:
            lines = [ln.strip() for ln in fh if ln.strip()]
    except OSError:
        return None, None
    sig = None
    for ln in lines[:-1]:
        if ln.startswith("Command terminated by signal"):
            sig = int(ln.split()[-1])
    try:
        return float(lines[-1]), sig
    except (IndexError, ValueError):
        return None, sig


def run_once(cmd, time_limit, tmp):
    """One run: (status, seconds, peak MB, stdout file)."""
    out_path, err_path = os.path.join(tmp, "stdout"), os.path.join(tmp, "stderr")
    time_path = os.path.join(tmp, "time")
    if os.path.exists(time_path):
        os.remove(time_path)
    timer_cmd = [GNU_TIME, "-f", "%M", "-o", time_path] if os.access(GNU_TIME, os.X_OK) else []
    if timer_cmd and not shutil.which(cmd[0]):
        return "failed: cannot start: no such program", None, None, out_path
    with open(out_path, "wb") as out, open(err_path, "wb") as err:
        start = time.monotonic()
        try:  # its own session, so that a timeout kills GNU time and the command together
            proc = subprocess.Popen(timer_cmd + cmd, stdout=out, stderr=err, stdin=subprocess.DEVNULL,
                                    start_new_session=True)
        except OSError as e:
            return f"failed: cannot start: {e.strerror}", None, None, out_path
        timed_out = threading.Event()

        def kill():
            timed_out.set()
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass

        timer = threading.Timer(time_limit, kill)
        timer.start()
        try:
            _, wstatus, usage = os.wait4(proc.pid, 0)
        finally:
            timer.cancel()
        seconds = time.monotonic() - start
        proc.returncode = 0  # reaped here; keeps Popen from waiting again
    peak = usage.ru_maxrss / 1024.0  # kB on Linux
    if timed_out.is_set():
        return "timeout", None, None, out_path
    sig = os.WTERMSIG(wstatus) if os.WIFSIGNALED(wstatus) else None
    code = os.WEXITSTATUS(wstatus) if sig is None else None
    if timer_cmd:
        peak_kb, sig = gnu_time_report(time_path)
        peak = peak_kb / 1024.0 if peak_kb is not None else None
        if sig is not None:
            code = None
    if sig is not None:
        return f"crashed (signal {sig})", seconds, peak, out_path
    if code != 0:
        why = last_line(err_path) or last_line(out_path)
        return f"failed (exit code {code})" + (f": {why}" if why else ""), seconds, peak, out_path
    return "ok", seconds, peak, out_path


def measure(a, row):
    """Runs the command (--runs times, or 1 or 3), fills the row's status, seconds, peak and
    the command's own seconds_*."""
    times, peaks, inner = [], [], {}
    runs = a.runs
    with tempfile.TemporaryDirectory(prefix="icm_whole_") as tmp:
        k = 0
        while True:
            if a.output and os.path.exists(a.output):
                os.remove(a.output)
            status, seconds, peak, out_path = run_once(a.command, a.time_limit, tmp)
            if status == "ok" and a.output and not os.path.exists(a.output):
                status = "failed: no output file"
            report = last_json(out_path) if a.json_stdout else None
            if status == "ok" and report and report.get("status", "ok") != "ok":
                said = str(report["status"])
                status = said if said.startswith("failed") else "failed: " + said
            if peak is not None:
                peaks.append(peak)
            if status != "ok":
                row["status"] = status if k == 0 else f"{status} (run {k + 1})"
                if seconds is not None and k == 0:
                    times.append(seconds)
                break
            row["status"] = "ok"
            times.append(seconds)
            for key, value in (report or {}).items():
                if key.startswith("seconds_") and isinstance(value, (int, float)):
                    inner.setdefault(key, []).append(value)
            k += 1
            if runs is None:
                runs = 3 if seconds < 2.0 else 1
            if k >= runs:
                break
    row["seconds"] = statistics.median(times) if times and row["status"] == "ok" else None
    row["peak_rss_mb"] = max(peaks) if peaks else None
    row["runs"] = len(times)
    for key, values in inner.items():
        row[key] = statistics.median(values)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--method", required=True, help="the row's method (bff, icm_param_whole)")
    ap.add_argument("--obj", required=True, help="the OBJ the command reads (its counts go in the row)")
    ap.add_argument("--mesh", help="the row's mesh (default: the OBJ's file name)")
    ap.add_argument("--time-limit", type=float, default=600.0)
    ap.add_argument("--runs", type=int)
    ap.add_argument("--json-stdout", action="store_true")
    ap.add_argument("--output")
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    if a.command and a.command[0] == "--":
        a.command = a.command[1:]
    if not a.command:
        ap.error("no command given (after --)")
    if a.runs is not None and a.runs < 1:
        ap.error("--runs needs a positive integer")
    if a.time_limit <= 0:
        ap.error("--time-limit needs a positive number of seconds")

    row = {"mesh": a.mesh or os.path.splitext(os.path.basename(a.obj))[0],
           "vertices": None, "faces": None, "method": a.method, "status": ""}
    try:
        row["vertices"], row["faces"] = count_obj(a.obj)
    except OSError as e:
        row["status"] = f"failed: cannot read {a.obj}: {e.strerror}"
    else:
        measure(a, row)
    print(json.dumps(row), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
