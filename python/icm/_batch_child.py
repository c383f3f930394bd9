"""icm.batch's child (``python3 -m icm.batch --one INPUT OUTPUT ...``): one mesh read,
parameterized and written in a process of its own, its figures the last line of its stdout.
Private: icm.batch is the module to use.
"""

import json
import math
import os
import re
import signal
import time

import icm
from icm._batch_command_line import _cone_count, _Parser

CRASH_HOOK = "ICM_BATCH_TEST_CRASH"


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
