"""python3 -m modalbench study SPEC.toml --out DIR [--scheduler tcp://HOST:PORT] [--workers N]"""

import argparse
import sys

from . import InputError
from .study import spec_scenes, study


def main(argv=None):
    ap = argparse.ArgumentParser(prog="modalbench", description="modalbench parameter studies")
    sub = ap.add_subparsers(dest="command", required=True)
    s = sub.add_parser("study", help="run every combination of a study spec and write study.csv")
    s.add_argument("spec", help="study spec (TOML)")
    s.add_argument("--out", required=True, help="output folder")
    s.add_argument("--scheduler", help="Dask scheduler address (default: local processes)")
    s.add_argument("--workers", type=int, help="local processes (default: one per core)")
    a = ap.parse_args(argv)
    try:
        scenes, backends, meshes = spec_scenes(a.spec)
        table = study(scenes, backends, meshes, scheduler=a.scheduler, workers=a.workers, out=a.out)
    except (InputError, ValueError, OSError) as e:
        print(f"modalbench: {e}", file=sys.stderr)
        return 2
    bad = sum(1 for r in table if r["status"] != "success")
    print(f"{len(table)} runs ({bad} not success) written to {a.out}/study.csv")
    return 0


if __name__ == "__main__":
    sys.exit(main())
