#!/usr/bin/env python3
"""Old build against new: every built-in scene on every back-end, on its default path
(`modalbench solve NAME --backend B --json`), the two JSON documents compared field by field.

A restructuring that changes no arithmetic must give the same numbers bit for bit, the same
statuses, messages and warnings. Fields that measure the run rather than the answer are left out
(wall times, peak memory, the run-time plan calibrated on them, the warning that compares the two);
fields present in only one build are listed apart (a new field is not a changed number).

Usage:
  benchmarks/regression/compare_builds.py --old OLD/build/app/modalbench --new build/app/modalbench
      [--scenes DIR] [--out DIR] [--jobs 1] [--only NAME ...] [--backends B ...]
Exit status 0 when every pair agrees (fields in both builds), 1 otherwise."""
import argparse
import concurrent.futures
import json
import math
import pathlib
import re
import subprocess
import sys

# Fields that measure the run, not the answer.
RUN_FIELDS = re.compile(r"(^|_)(time|times|timing|timings|seconds)(_|$)|resident|time_s$|planned_s")
RUN_WARNING = re.compile(r"^run time .* times the estimate")


def backends(exe):
    out = subprocess.run([exe, "list"], check=True, capture_output=True, text=True).stdout
    names = []
    for line in out.splitlines():
        m = re.match(r"\s+(exact|rfem|dtfm|difference_eq)\b", line)
        if m and m.group(1) not in names:
            names.append(m.group(1))
    return names or ["exact", "rfem", "dtfm", "difference_eq"]


def run(exe, scene, backend, timeout):
    try:
        p = subprocess.run([exe, "solve", str(scene), "--backend", backend, "--json"], capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"_exit": "timeout"}
    try:
        doc = json.loads(p.stdout) if p.stdout.strip() else {}
    except json.JSONDecodeError:
        doc = {"_stdout": p.stdout[:2000]}
    doc["_exit"] = p.returncode
    return doc


def strip(doc):
    """The document without the fields that measure the run."""
    if isinstance(doc, dict):
        return {k: strip(v) for k, v in doc.items() if not RUN_FIELDS.search(k)}
    if isinstance(doc, list):
        return [strip(v) for v in doc if not (isinstance(v, str) and RUN_WARNING.match(v))]
    return doc


def differences(old, new, path="", out=None, added=None):
    out = [] if out is None else out
    added = [] if added is None else added
    if isinstance(old, dict) and isinstance(new, dict):
        for k in old:
            if k not in new:
                added.append(f"removed {path}/{k}")
            else:
                differences(old[k], new[k], f"{path}/{k}", out, added)
        for k in new:
            if k not in old:
                added.append(f"added {path}/{k}")
    elif isinstance(old, list) and isinstance(new, list):
        if len(old) != len(new):
            out.append((path, f"length {len(old)} -> {len(new)}", math.inf))
        for i, (a, b) in enumerate(zip(old, new)):
            differences(a, b, f"{path}[{i}]", out, added)
    elif isinstance(old, (int, float)) and isinstance(new, (int, float)) and not isinstance(old, bool):
        if old != new:
            rel = abs(old - new) / max(abs(old), abs(new)) if max(abs(old), abs(new)) > 0 else math.inf
            out.append((path, f"{old!r} -> {new!r}", rel))
    elif old != new:
        out.append((path, f"{str(old)[:160]!r} -> {str(new)[:160]!r}", math.inf))
    return out, added


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--old", required=True)
    ap.add_argument("--new", required=True)
    ap.add_argument("--scenes", default=str(pathlib.Path(__file__).resolve().parents[2] / "scenes"))
    ap.add_argument("--out", default="")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=600)
    ap.add_argument("--only", nargs="*", default=[], help="scene names (default: every built-in scene)")
    ap.add_argument("--backends", nargs="*", default=[], help="back-ends (default: every one the new build lists)")
    a = ap.parse_args()
    scenes = sorted(pathlib.Path(a.scenes).glob("*.toml"))
    if a.only:
        scenes = [s for s in scenes if s.stem in a.only]
    pairs = [(s, b) for s in scenes for b in (a.backends or backends(a.new))]
    out = pathlib.Path(a.out) if a.out else None
    if out:
        out.mkdir(parents=True, exist_ok=True)

    def both(pair):
        s, b = pair
        return pair, run(a.old, s, b, a.timeout), run(a.new, s, b, a.timeout)

    bad = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as ex:
        for (s, b), old, new in ex.map(both, pairs):
            if out:
                for tag, doc in (("old", old), ("new", new)):
                    (out / f"{s.stem}.{b}.{tag}.json").write_text(json.dumps(doc, indent=1))
            diffs, added = differences(strip(old), strip(new))
            status = old.get("status", old.get("_exit"))
            label = f"{s.stem:32s} {b:14s} {str(status):16s}"
            if not diffs:
                print(f"{label} identical" + (f" ({'; '.join(added)})" if added else ""))
                continue
            bad += 1
            finite = [d for d in diffs if math.isfinite(d[2])]
            worst = max(finite, key=lambda d: d[2]) if finite else None
            print(f"{label} {len(diffs)} difference(s)" +
                  (f", largest relative {worst[2]:.2e} at {worst[0]}" if worst else ""))
            for path, what, _ in diffs[:8]:
                print(f"    {path}: {what}")
    print(f"{len(pairs) - bad} of {len(pairs)} identical")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
