#!/usr/bin/env python3
"""Lists the functions of the C++ sources over a length (lines from the signature to the closing
brace, lambdas counted inside their enclosing function too), longest first, from universal-ctags.

Usage: tools/function_lengths.py [--over N] [DIR ...]   (default: every source folder but tests/)
Exit status 1 where a function exceeds --fail-over (the project's limit: 120)."""
import argparse
import json
import os
import pathlib
import subprocess
import sys

SOURCE_DIRS = ["core", "numerics", "rom", "exact", "rfem", "difference_eq", "dtfm", "solvers", "harness", "app",
               "python", "benchmarks"]


def functions(paths):
    out = subprocess.run(["ctags", "--output-format=json", "--languages=C++", "--c++-kinds=f", "--fields=+ne",
                          "-R", "-o", "-"] + paths, check=True, capture_output=True, text=True).stdout
    for line in out.splitlines():
        tag = json.loads(line)
        if tag.get("_type") != "tag" or "end" not in tag or tag["name"].startswith("__anon"):
            continue
        scope = tag.get("scope", "")
        name = tag["name"] if "__anon" in scope or not scope else scope.split("::")[-1] + "::" + tag["name"]
        yield tag["end"] - tag["line"] + 1, name, f'{tag["path"]}:{tag["line"]}'


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--over", type=int, default=80)
    ap.add_argument("--fail-over", type=int, default=0)
    ap.add_argument("dirs", nargs="*")
    a = ap.parse_args()
    root = pathlib.Path(__file__).resolve().parent.parent
    dirs = a.dirs or [str(root / d) for d in SOURCE_DIRS if (root / d).is_dir()]
    rows = sorted((f for f in functions(dirs) if f[0] > a.over), reverse=True)
    for n, name, where in rows:
        print(f"{n:5d}  {name:45s} {os.path.relpath(where, root) if where.startswith('/') else where}")
    worst = rows[0][0] if rows else 0
    return 1 if a.fail_over and worst > a.fail_over else 0


if __name__ == "__main__":
    sys.exit(main())
