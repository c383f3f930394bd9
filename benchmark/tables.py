#!/usr/bin/python3
"""Regenerate the measured tables of doc/benchmarks.md.

    /usr/bin/python3 benchmark/tables.py [--sections a,b] [--meshes MESH...] [--from FILE...]

Runs the already built `compare` (and `icm_param` for the border shapes compare does not
have, and `scaling.sh` for a short scaling series), one process at a time, keeps the JSON
lines of every run in the cache directory, and rewrites each generated section of the
document: the text between

    <!-- BEGIN GENERATED: name -->
    <!-- END GENERATED: name -->

Each section starts with one line naming the machine, the date, the commit of the measured
code and the command that regenerates it. Nothing outside the markers is touched.

Runs (each one cache file, RUN.jsonl, whose first line records how it was made):
  all      compare, default methods, on the disks and on the surfaces that are not disks
           (meshes above --big-faces faces with --runs 1): sections disks, energies,
           nondisk and the circle domains of border
  icm      compare --methods icm,icm_free_boundary_opened on the disks and the largest
           surfaces: with the icm rows of `all`, section surfaces
  senergies  compare --methods icm,icm_u_square,... on small surfaces that are not disks:
           section surface-energies
  opened   compare --open on the closed genus-0 meshes: section opened
  border   icm_param --boundary circle|square --json on some disks: section border
  scaling  scaling.sh with KMAX=--scaling-kmax into the cache: section scaling-short
  summary  compare --methods icm,lscm,arap on a few disks and closed meshes:
           section summary, which goes into README.md (--readme), not doc/benchmarks.md
Section scaling renders a series written earlier by scaling.sh (--scaling-series), which
is too slow to rerun here, and so do sections scaling-bff and bff-disks (--scaling-bff-series,
--bff-disks-series: scaling.sh with BFF=, ICM and BFF side by side; BFF is built apart); section reading renders the reader's Google Benchmark figures
written earlier by icm_kernels (--reading-figures, the command in its header line).

--from FILE... reads cache files instead of running (a file without the first line is
taken to be the run its name says: all.jsonl, icm.jsonl, ...); runs it lacks are made. --meshes replaces the mesh
list of every compare run; each section shows the rows that apply to it.
"""


# This file is the command line; the work is in the modules beside it, by what they do:
# tables_plan.py (the meshes and methods of each run, the sections and the runs they read),
# tables_runs.py (running compare, icm_param and scaling.sh, the cache files),
# tables_render.py (the sections' tables and their header line) and tables_cones.py (the
# section cones and its figure). They are found from any working directory: benchmark/ goes
# first on the path.

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tables_cones import section_cones  # noqa: E402
from tables_plan import (BFF_DISKS_COMMAND, READING_COMMAND, README_SECTIONS, ROOT, SCALING_BFF_COMMAND,  # noqa: E402
                         SECTIONS, mesh_dirs, relative)
from tables_render import (header, replace_section, section_border, section_disks, section_energies,  # noqa: E402
                           section_nondisk, section_opened, section_reading, section_scaling,
                           section_scaling_short,
                           section_summary, section_surface_energies, section_surfaces)
from tables_runs import git, load, run  # noqa: E402

RENDER = {"disks": section_disks, "energies": section_energies, "nondisk": section_nondisk,
          "surfaces": section_surfaces, "surface-energies": section_surface_energies,
          "cones": section_cones,
          "opened": section_opened, "border": section_border,
          "scaling-short": section_scaling_short, "summary": section_summary}


def parse_arguments():
    """The options, and the sections asked for; exits 2 on an unknown section."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sections", default=",".join(SECTIONS),
                    help="comma-separated sections to regenerate (default: all: %(default)s)")
    ap.add_argument("--meshes", nargs="+", help="mesh files or names in the mesh directories, "
                    "replacing every run's list")
    ap.add_argument("--mesh-dir", action="append", default=[], help="look for meshes here first")
    ap.add_argument("--from", dest="sources", nargs="+", metavar="FILE",
                    help="read these cache files (RUN.jsonl) instead of running; the runs "
                    "they lack are made")
    ap.add_argument("--compare", default=os.path.join(ROOT, "build", "benchmark", "compare"),
                    help="the compare binary (default: build/benchmark/compare)")
    ap.add_argument("--icm-param", default=os.path.join(ROOT, "build", "examples", "icm_param"),
                    help="the icm_param binary (default: build/examples/icm_param)")
    ap.add_argument("--cache", default=os.path.join(ROOT, "build", "tables"),
                    help="where the runs' JSON lines go (default: build/tables)")
    ap.add_argument("--doc", default=os.path.join(ROOT, "doc", "benchmarks.md"),
                    help="the document to rewrite (default: doc/benchmarks.md)")
    ap.add_argument("--readme", default=os.path.join(ROOT, "README.md"),
                    help="the document of the README sections (default: README.md)")
    ap.add_argument("--time-limit", type=float, default=60, help="seconds per run (default 60)")
    ap.add_argument("--big-faces", type=int, default=15000,
                    help="meshes with more faces get --runs 1 (default 15000)")
    ap.add_argument("--nice", type=int, default=10, help="niceness of the runs (0: none)")
    ap.add_argument("--scaling-series", default=os.path.join(ROOT, "doc", "figures",
                                                             "scaling.jsonl"))
    figures = os.path.join(ROOT, "doc", "figures")
    ap.add_argument("--scaling-bff-series", default=os.path.join(figures, "scaling_bff.jsonl"))
    ap.add_argument("--bff-disks-series", default=os.path.join(figures, "bff_disks.jsonl"))
    ap.add_argument("--reading-figures", default=os.path.join(ROOT, "doc", "figures", "reading.json"))
    ap.add_argument("--scaling-kmax", type=int, default=1,
                    help="Loop subdivision levels 0..K of the short series (default 1)")
    ap.add_argument("--commit", help="the commit to name in the headers (default: HEAD of the "
                    "binary's git tree, for a binary copied out of its tree)")
    ap.add_argument("--print", action="store_true", help="print the sections, leave the doc")
    a = ap.parse_args()

    sections = [s for s in a.sections.split(",") if s]
    unknown = [s for s in sections if s not in SECTIONS]
    if unknown:
        ap.error(f"unknown sections {unknown}; known: {', '.join(SECTIONS)}")
    return a, sections


def runs_data(a, sections):
    """{run: (its record, its rows)} of every run the sections read: those of the --from
    files, then the others, made now."""
    needed = []
    for s in sections:
        needed += [r for r in SECTIONS[s] if r not in needed]

    data = {}
    for path in a.sources or []:
        meta, rows = load(path)
        data[meta["run"]] = (meta, rows)
    missing = [r for r in needed if r not in data]
    if missing:
        for tool in [a.compare] + ([a.icm_param] if "border" in missing else []):
            if not os.access(tool, os.X_OK):
                raise SystemExit(f"tables: {tool} is not an executable; build it (doc/benchmarks.md)")
        dirs = mesh_dirs(a.mesh_dir)
        for r in missing:
            data[r] = run(r, a, dirs)
    return data


def section_body(s, a, data):
    """Section `s` as it goes between its markers: the line that says how it was made, then
    its table."""
    hint = f"/usr/bin/python3 benchmark/tables.py --sections {s}"
    if a.meshes:
        hint += " --meshes " + " ".join(a.meshes)
    earlier = {"scaling": (a.scaling_series, "`bash benchmark/scaling.sh` (METHODS as in the table)",
                           "it takes long", section_scaling),
               "scaling-bff": (a.scaling_bff_series, f"`{SCALING_BFF_COMMAND}`", "it takes long and "
                               "needs BFF", section_scaling),
               "bff-disks": (a.bff_disks_series, f"`{BFF_DISKS_COMMAND}`", "it needs BFF", section_scaling),
               "reading": (a.reading_figures, f"`{READING_COMMAND}`", "it needs the benchmarks built",
                           section_reading)}
    if s in earlier:
        figures, command, why, render = earlier[s]
        made = git(["log", "-1", "--format=%h %cs", "--", relative(figures)], ROOT)
        line = ("_Read from `{}`: written by {} with the code of commit {} (the file's last "
                "commit), not remeasured here ({}); rerender with `{}`._").format(
                    relative(figures), command, made or "none: not committed", why, hint)
        body = line + "\n\n" + render(figures)
    else:
        metas = [data[r][0] for r in SECTIONS[s]]
        rendered = [relative(m["file"]) for m in metas if m.get("file")]
        body = header(s, metas, hint, rendered) + "\n\n" + RENDER[s](data)
    return body


def main():
    a, sections = parse_arguments()
    data = runs_data(a, sections)

    docs = {}  # path: its text, rewritten section by section
    for s in sections:
        path = a.readme if s in README_SECTIONS else a.doc
        if path not in docs:
            with open(path, encoding="utf-8") as f:
                docs[path] = f.read()
        body = section_body(s, a, data)
        if a.print:
            print(f"<!-- {s} -->\n{body}\n")
        else:
            docs[path] = replace_section(docs[path], s, body)
    if not a.print:
        for path, text in docs.items():
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        print(f"tables: rewrote {', '.join(sections)} in {', '.join(relative(p) for p in docs)}",
              file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
