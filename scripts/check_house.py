#!/usr/bin/python3
"""Checks the plan of the house (issue 52): every include points down, every file and function fits a reader.

    scripts/check_house.py [--root DIR] [--self-test]

1. Layers. The stage order is the table of doc/design.md headed "stages"; every header under
   include/ICM/ belongs to exactly one stage (its folder, or its own name at the top), and
   every `#include <ICM/...>` must name an existing header of the same stage or of a stage
   above it in the table. A header of the table headed "moved" is a forwarding header: it
   may hold nothing but comments, the CGAL deprecation warning and the include of its new path.
2. Sizes. No source file (C++ or Python) under include/, examples/, benchmark/, python/ or tools/ is
   over MAX_FILE_LINES lines, and no function over MAX_FUNCTION_LINES, counted from the line
   of its opening brace (C++) or of its `def` (Python) to the line that ends it, comments
   included. C++ functions are found by matching braces after comments and literals are
   blanked out: a brace block whose head ends in a parameter list (or a constructor's
   initializers) and that is not inside another function is a function, so lambdas and
   local classes count towards the function around them.
Prints every violation with its file and line, and exits 1 if there is any. --self-test checks
the check: on a copy of the tree with an upward include planted in the ground, and a function
and a file grown too long, it must find exactly those three.
"""

import argparse
import ast
import os
import re
import shutil
import sys
import tempfile

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 100
SIZE_FOLDERS = ("include", "examples", "benchmark", "python", "tools")
CPP_SUFFIXES = (".h", ".hpp", ".cpp")


def markdown_table(text, heading):
    """Rows (lists of cells) of the table after the comment `<!-- HEADING: ... -->`."""
    match = re.search(r"<!-- " + heading + r":[^>]*-->\s*\n", text)
    if not match:
        sys.exit(f"check_house: doc/design.md has no table headed <!-- {heading}: ... -->")
    rows = []
    for line in text[match.end():].splitlines():
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not all(re.fullmatch(r":?-+:?", c) for c in cells):
            rows.append(cells)
    return rows[1:]  # the first row names the columns


def read_stages(design):
    """{folder/ or top-level file: rank} from the stage table, and {old path: new path}."""
    rank = {}
    for i, row in enumerate(markdown_table(design, "stages")):
        for item in re.findall(r"`([^`]+)`", row[1]):
            if item in rank:
                sys.exit(f"check_house: {item} is in two stages of doc/design.md")
            rank[item] = i
    moved = {}
    for row in markdown_table(design, "moved"):
        old, new = (re.findall(r"`([^`]+)`", cell)[0] for cell in row[:2])
        moved[old] = new
    return rank, moved


def stage_of(header, rank):
    """The stage rank of a header path relative to include/ICM/, or None."""
    folder = header.split("/")[0] + "/" if "/" in header else header
    return rank.get(folder)


def blank_comments_and_literals(text):
    """The text with comments, strings and characters blanked, keeping its line breaks."""
    pattern = re.compile(r'//[^\n]*|/\*.*?\*/|R"([^(\s]*)\(.*?\)\1"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'', re.S)
    return pattern.sub(lambda m: "\n" * m.group(0).count("\n") + " ", text)


def includes(path):
    """(line number, included path) of every `#include <ICM/...>` of a file."""
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            m = re.match(r"\s*#\s*include\s*<ICM/([^>]+)>", line)
            if m:
                yield number, m.group(1)


def check_forwarding(path, new, problems):
    """A forwarding header holds only comments, the deprecation warning and one include of `new`."""
    with open(path, encoding="utf-8") as f:
        code = [l.strip() for l in blank_comments_and_literals(f.read()).splitlines() if l.strip()]
    allowed = re.compile(r"#(ifndef|define|endif)\b.*|#define CGAL_(DEPRECATED_HEADER|REPLACEMENT_HEADER)\b.*|"
                         r"#include <CGAL/Installation/internal/deprecation_warning.h>|#include <ICM/" +
                         re.escape(new) + ">")
    for line in code:
        if not allowed.fullmatch(line):
            problems.append(f"{path}: a forwarding header (to {new}) holds more than the forwarding: {line}")


def check_layers(root, problems):
    with open(os.path.join(root, "doc", "design.md"), encoding="utf-8") as f:
        rank, moved = read_stages(f.read())
    base = os.path.join(root, "include", "ICM")
    headers = sorted(os.path.relpath(os.path.join(d, n), base).replace(os.sep, "/")
                     for d, _, names in os.walk(base) for n in names if n.endswith(CPP_SUFFIXES))
    for header in headers:
        path = os.path.join(base, header)
        if header in moved:
            check_forwarding(path, moved[header], problems)
            continue
        own = stage_of(header, rank)
        if own is None:
            problems.append(f"{path}: in no stage of doc/design.md")
            continue
        for number, target in includes(path):
            if target not in headers:
                problems.append(f"{path}:{number}: includes <ICM/{target}>, which does not exist")
            elif target in moved:
                problems.append(f"{path}:{number}: includes <ICM/{target}>, which moved to <ICM/{moved[target]}>")
            elif stage_of(target, rank) is not None and stage_of(target, rank) > own:
                problems.append(f"{path}:{number}: includes <ICM/{target}>, of a later stage than its own")
    return len(headers)


def cpp_functions(text):
    """(first line, last line, head) of every function body of a C++ text, outermost only."""
    code = blank_comments_and_literals(text)
    stack, head, line = [], "", 1
    scope = re.compile(r"\b(namespace|struct|class|enum|union)\b[^()]*$|extern\s*$")
    parameters = re.compile(r"\)\s*(const|noexcept|override|final|mutable|->\s*[\w:<>,\s*&]+|\s)*$|\)\s*:[^;]*$")
    for ch in code:
        if ch == "\n":
            line += 1
        if ch == "{":
            h = head.strip()
            in_function = any(kind == "function" for kind, _, _ in stack)
            kind = "scope" if scope.search(h) else "function" if parameters.search(h) and not in_function else "block"
            stack.append((kind, line, h.splitlines()[-1] if h else ""))
            head = ""
        elif ch == "}":
            if stack:
                kind, first, h = stack.pop()
                if kind == "function":
                    yield first, line, h
            head = ""
        elif ch == ";":
            head = ""
        else:
            head += ch


def python_functions(text):
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield node.lineno, node.end_lineno, "def " + node.name


def check_sizes(root, problems):
    count = 0
    for folder in SIZE_FOLDERS:
        for d, _, names in os.walk(os.path.join(root, folder)):
            for name in sorted(names):
                path = os.path.join(d, name)
                if name.endswith(CPP_SUFFIXES):
                    functions = cpp_functions
                elif name.endswith(".py"):
                    functions = python_functions
                else:
                    continue
                count += 1
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                lines = text.count("\n")
                if lines > MAX_FILE_LINES:
                    problems.append(f"{path}: {lines} lines, over {MAX_FILE_LINES}")
                for first, last, head in functions(text):
                    if last - first + 1 > MAX_FUNCTION_LINES:
                        problems.append(f"{path}:{first}: a function of {last - first + 1} lines, over "
                                        f"{MAX_FUNCTION_LINES}: {head.strip()[:80]}")
    return count


def self_test(root):
    """The problems found on a copy of `root` with three planted: they must be exactly those."""
    with tempfile.TemporaryDirectory() as copy:
        shutil.copytree(os.path.join(root, "include"), os.path.join(copy, "include"))
        os.mkdir(os.path.join(copy, "doc"))
        shutil.copy(os.path.join(root, "doc", "design.md"), os.path.join(copy, "doc"))
        ground = os.path.join(copy, "include", "ICM", "internal", "Vector_geometry.h")
        with open(ground, encoding="utf-8") as f:
            text = f.read()
        with open(ground, "w", encoding="utf-8") as f:
            f.write(text.replace("#include", "#include <ICM/pipeline/Surface_component.h>\n#include", 1))
        with open(os.path.join(copy, "include", "ICM", "internal", "Planted.h"), "w", encoding="utf-8") as f:
            f.write("namespace ICM {\nint planted(int a)\n{\n" + "  ++a;\n" * (MAX_FILE_LINES - 3) + "  return a;\n}\n}\n")
        problems = []
        check_layers(copy, problems)
        check_sizes(copy, problems)
    expected = ["Vector_geometry.h:", "Planted.h: ", "Planted.h:3: a function of"]
    found = all(any(e in p for p in problems) for e in expected) and len(problems) == len(expected)
    print("check_house --self-test: " + ("found the three planted problems" if found else "wrong findings:"))
    for p in problems:
        print("  " + p)
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    parser.add_argument("--self-test", action="store_true", help="check the check on planted problems")
    args = parser.parse_args()
    root = os.path.relpath(args.root)
    if args.self_test:
        sys.exit(0 if self_test(root) else 1)
    problems = []
    headers = check_layers(root, problems)
    sources = check_sizes(root, problems)
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        sys.exit(f"check_house: {len(problems)} problems")
    print(f"check_house: {headers} headers, every include points to its own stage or an earlier one; {sources} sources within "
          f"{MAX_FILE_LINES} lines and functions within {MAX_FUNCTION_LINES}")


if __name__ == "__main__":
    main()
