"""Parameter studies: every combination of scenes, back-ends and meshes, one table of inputs,
outputs and timings. Runs in local processes by default, or on a Dask cluster given a scheduler
address; the table is the same either way (timings aside).

    rows = modalbench.study(scenes, ["exact", "rfem"], meshes={"rfem": ["32", "64"]})

`scenes` is an iterable of Scene or of (parameters, Scene) pairs; the parameters (a dict) become
the table's first columns.
"""

import concurrent.futures
import copy
import csv
import itertools
import math
import os
import tomllib

# Columns every row has, after the parameters; then the lists below, one column per entry.
COLUMNS = ["scene", "backend", "mesh", "status", "message", "unknowns", "max_backward_error", "estimate_frequencies",
           "estimate_deflections", "time_total_s", "time_build_s", "time_modes_s", "time_statics_s", "time_frf_s"]
# Per-entry columns: f1_rad_s, ... (frequencies), w1_m, ... (w at each probe), xf1_rad_s, ...
# (the extrapolated frequencies, where the back-end made them).
LISTS = [("frequencies_rad_s", "f{}_rad_s"), ("w_m", "w{}_m"), ("extrapolated_rad_s", "xf{}_rad_s")]
TIMING = [c for c in COLUMNS if c.startswith("time_")]


def _row(task):
    """One solve in whichever process runs it (the scene travels as TOML text)."""
    from . import Scene, InputError, solve

    params, toml_text, source, backend, mesh = task
    row = dict(params)
    row.update(backend=backend, mesh=mesh if mesh is not None else "default")
    try:
        scene = Scene.from_toml(toml_text, source)
        row["scene"] = scene.name
        r = solve(scene, backend, mesh=mesh)
        t = r.timing_s
        row.update(status=r.status, message=r.message, unknowns=r.unknowns, max_backward_error=r.max_backward_error,
                   time_total_s=t["total"], time_build_s=t["build"], time_modes_s=t["modes"],
                   time_statics_s=t["statics"], time_frf_s=t["frf"], mesh=r.mesh)
        row["frequencies_rad_s"] = [float(f) for f in r.frequencies_rad_s]
        row["w_m"] = [float(w) for w in r.w]
        x = r.extrapolated_frequencies_rad_s
        row["extrapolated_rad_s"] = [float(f) for f in x] if x is not None else []
        e = r.as_dict.get("error_estimate") or {}
        row.update(estimate_frequencies=_number(e.get("frequencies")), estimate_deflections=_number(e.get("deflections")))
    except InputError as e:
        row.update(status="invalid-input", message=str(e), frequencies_rad_s=[])
    return row


def _number(v):
    """A JSON number, or NaN for null (not estimated)."""
    return math.nan if v is None else float(v)


def _tasks(scenes, backends, meshes):
    for item in scenes:
        params, scene = item if isinstance(item, tuple) else ({}, item)
        for b in backends:
            ms = meshes.get(b, [None]) if isinstance(meshes, dict) else (meshes or [None])
            for m in ms:
                yield (dict(params), scene.toml, scene.source, b, m)


def study(scenes, backends, meshes=None, *, scheduler=None, workers=None, out=None):
    """Runs every combination and returns the rows (dicts) in a fixed order; with `out` (a
    folder) also writes study.csv (and study.parquet when pyarrow is importable). `scheduler`: a
    Dask scheduler address (tcp://host:port), else local processes (`workers` of them; 1: this
    process)."""
    tasks = list(_tasks(scenes, list(backends), meshes))
    if scheduler is not None:
        from distributed import Client

        with Client(scheduler) as client:
            # A task whose worker dies is rerun by the scheduler (allowed-failures); gather keeps order.
            futures = client.map(_row, tasks, pure=False, retries=2)
            rows = client.gather(futures)
    elif workers == 1:
        rows = [_row(t) for t in tasks]
    else:
        with concurrent.futures.ProcessPoolExecutor(max_workers=workers) as pool:
            rows = list(pool.map(_row, tasks, chunksize=max(1, len(tasks) // (8 * (os.cpu_count() or 1)))))
    table = _flatten(rows)
    if out is not None:
        write_table(table, out)
    return table


def _flatten(rows):
    counts = {key: max((len(r.get(key, [])) for r in rows), default=0) for key, _ in LISTS}
    table = []
    for r in rows:
        row = {k: v for k, v in r.items() if k not in counts}
        for k in COLUMNS:
            row.setdefault(k, "")
        for key, name in LISTS:
            values = r.get(key, [])
            for i in range(counts[key]):
                row[name.format(i + 1)] = values[i] if i < len(values) else math.nan
        table.append(row)
    return table


def write_table(table, out):
    """study.csv (and study.parquet with pyarrow) in the folder `out`; returns the CSV path."""
    os.makedirs(out, exist_ok=True)
    columns = []
    for row in table:
        for k in row:
            if k not in columns:
                columns.append(k)
    path = os.path.join(out, "study.csv")
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        for row in table:
            w.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in row.items()})
    try:
        import pyarrow
        import pyarrow.parquet

        pyarrow.parquet.write_table(pyarrow.Table.from_pylist(table), os.path.join(out, "study.parquet"))
    except ImportError:
        pass
    return path


def _values(spec, key):
    if isinstance(spec, list):
        return spec
    if isinstance(spec, dict) and {"from", "to", "num"} <= set(spec):
        a, b, n = float(spec["from"]), float(spec["to"]), int(spec["num"])
        if n < 1:
            raise ValueError(f"parameters.{key}.num: at least 1")
        if spec.get("scale", "linear") == "log":
            if a <= 0 or b <= 0:
                raise ValueError(f"parameters.{key}: a log scale needs positive bounds")
            return [a * (b / a) ** (i / max(n - 1, 1)) for i in range(n)]
        return [a + (b - a) * i / max(n - 1, 1) for i in range(n)]
    raise ValueError(f"parameters.{key}: a list of values or {{ from, to, num[, scale = \"log\"] }}")


def _set(d, dotted, value):
    keys = dotted.split(".")
    for k in keys[:-1]:
        if not isinstance(d.get(k), dict):
            # A value that is not a table (a named support, "clamped") becomes one; the scene's
            # validation then names whatever else that table needs.
            d[k] = {}
        d = d[k]
    d[keys[-1]] = value


def spec_scenes(spec_path):
    """The scenes, back-ends and meshes of a study spec (TOML):

        [study]
        base = "scenes/lasecka_elastic_beam.toml"     # relative to the spec file
        backends = ["exact", "difference_eq"]
        meshes = { difference_eq = ["32", "64"] }     # optional
        [parameters]                                   # dotted scene keys, every combination
        "geometry.length" = [1.0, 2.0]
        "supports.x0.translational" = { from = 1e3, to = 1e9, num = 4, scale = "log" }
    """
    from . import Scene

    with open(spec_path, "rb") as f:
        spec = tomllib.load(f)
    st = spec.get("study", {})
    if "base" not in st or "backends" not in st:
        raise ValueError(f"{spec_path}: [study] needs base and backends")
    base_path = os.path.join(os.path.dirname(os.path.abspath(spec_path)), st["base"])
    with open(base_path, "rb") as f:
        base = tomllib.load(f)
    params = spec.get("parameters", {})
    keys = list(params)
    grids = [_values(params[k], k) for k in keys]

    def scenes():
        for combo in itertools.product(*grids):
            d = copy.deepcopy(base)
            for k, v in zip(keys, combo):
                _set(d, k, v)
            p = dict(zip(keys, combo))
            yield p, Scene.from_dict(d, source=f"{base_path} with {p}")

    return scenes(), st["backends"], st.get("meshes")
