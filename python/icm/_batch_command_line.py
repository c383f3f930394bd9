"""icm.batch's command line: the options of a batch, their checks, and its inputs and outputs
(the usage errors worded as icm_param's). Private: icm.batch is the module to use.
"""

import argparse
import math
import os
import re
import sys

import icm

FORMATS = ("obj", "ply", "gltf", "glb")
PREFIX = "icm.batch: "


class UsageError(Exception):
    """A wrong command line: the message is the reason; exit status 2."""



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
