#!/usr/bin/env python3
"""Seeded, deterministic scene fuzzer for `modalbench solve --json` (standard library only).

Each case starts from a built-in scene (scenes/*.toml), applies 1-3 mutations drawn from a
random.Random seeded by (seed, case), writes the scene to OUT/scenes/ and runs every selected
back-end on it in a subprocess with a wall-time cap and an address-space cap. Every run is
classified (success, clean-error, flagged, crash, timeout, invalid-json, bad-exit,
internal-error, bad-result) and the back-ends are cross-checked against each other on the
same scene. See README.md next to this file.

    fuzz.py --exe build/app/modalbench --cases 200 --seed 1 --out /tmp/fuzz
    fuzz.py --exe build-asan/app/modalbench --replay tests/fuzz/corpus --out /tmp/replay --mem-cap-mb 0
"""

from __future__ import annotations

import argparse
import concurrent.futures
import copy
import csv
import json
import math
import os
import re
import resource
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path
import random

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
DEFAULT_SCENES = REPO / "scenes"
ALL_BACKENDS = ["exact", "rfem", "difference_eq", "dtfm"]

# Classes of a run. FAILED_CLASSES count towards "failed" (the exit status).
FAILED_CLASSES = ["crash", "timeout", "invalid-json", "bad-exit", "internal-error", "bad-result"]
ALL_CLASSES = ["success", "clean-error", "flagged"] + FAILED_CLASSES
CLEAN_ERROR_STATUSES = {"invalid-input", "unsupported", "resource-limit"}
FLAGGED_STATUSES = {"not-converged", "numerical-issue", "resource-limit"}
KNOWN_STATUSES = {"success"} | CLEAN_ERROR_STATUSES | FLAGGED_STATUSES
XC_REFUSAL = "refusal-vs-success"
XC_CONTRA = "contradiction"
XC_CONTRA_NOEST = "contradiction (no estimate)"
XC_KINDS = [XC_REFUSAL, XC_CONTRA, XC_CONTRA_NOEST]
# Pairs of successes not compared because the two runs solve different models (a multi-prism dtfm
# section tends to 3D elasticity, the beam back-ends to the scene's beam theory): their difference
# is model error, which no discretization estimate covers. Counted, not findings.
XC_OTHER_MODEL = "not compared (different models)"
NO_ESTIMATE_TOL = 5e-2
ESTIMATE_SAFETY = 1.0  # the estimates are grid convergence indices (factors of safety inside): tolerance = their sum
LOW_MODES = 6  # contradictions among the first LOW_MODES paired modes are reported apart


# ----------------------------------------------------------------------------- TOML emitter

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def toml_key(k: str) -> str:
    return k if _BARE_KEY.match(k) else toml_string(k)


def toml_string(s: str) -> str:
    out = ['"']
    for ch in s:
        o = ord(ch)
        if ch == '"':
            out.append('\\"')
        elif ch == "\\":
            out.append("\\\\")
        elif ch == "\n":
            out.append("\\n")
        elif ch == "\t":
            out.append("\\t")
        elif ch == "\r":
            out.append("\\r")
        elif o < 0x20 or o == 0x7F:
            out.append("\\u%04X" % o)
        elif 0xD800 <= o <= 0xDFFF:  # lone surrogate: not a Unicode scalar value
            out.append("\\uFFFD")
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def toml_float(x: float) -> str:
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    r = repr(x)
    if "e" not in r and "." not in r:
        r += ".0"
    return r


def toml_value(v) -> str:
    """Inline form of a value (scalars, arrays, inline tables)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return toml_float(v)
    if isinstance(v, str):
        return toml_string(v)
    if isinstance(v, dict):
        if not v:
            return "{}"
        return "{ " + ", ".join(f"{toml_key(k)} = {toml_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    raise TypeError(f"cannot emit {type(v).__name__}")


def _is_table_array(v) -> bool:
    return isinstance(v, list) and len(v) > 0 and all(isinstance(x, dict) for x in v)


def _emit_table(lines: list[str], path: list[str], d: dict, header: bool) -> None:
    """Emits d as [path]: its scalars and inline values, then sub-tables whose values are all tables."""
    subtables = {k: v for k, v in d.items() if isinstance(v, dict) and v and (
        path == ["backend"] or all(isinstance(x, dict) for x in v.values()))}
    if header and (len(subtables) < len(d) or not d):
        lines.append("[" + ".".join(toml_key(p) for p in path) + "]")
    for k, v in d.items():
        if k in subtables:
            continue
        lines.append(f"{toml_key(k)} = {toml_value(v)}")
    for k, v in subtables.items():
        if lines and lines[-1] != "":
            lines.append("")
        _emit_table(lines, path + [k], v, True)


def emit_toml(doc: dict, header_comment: str = "") -> str:
    lines: list[str] = []
    if header_comment:
        lines += ["# " + ln if ln else "#" for ln in header_comment.splitlines()]
    # Top-level scalars (hostile: e.g. geometry = "x") come before any table header.
    for k, v in doc.items():
        if not isinstance(v, dict) and not _is_table_array(v):
            lines.append(f"{toml_key(k)} = {toml_value(v)}")
    for k, v in doc.items():
        if isinstance(v, dict):
            lines.append("")
            _emit_table(lines, [k], v, True)
    for k, v in doc.items():
        if _is_table_array(v):
            for item in v:
                lines.append("")
                lines.append(f"[[{toml_key(k)}]]")
                for kk, vv in item.items():
                    lines.append(f"{toml_key(kk)} = {toml_value(vv)}")
    return "\n".join(lines) + "\n"


def _same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return (math.isnan(a) and math.isnan(b)) or a == b
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return type(a) is type(b) and a == b


# ----------------------------------------------------------------------------- scene helpers


def load_builtin_scenes(folder: Path) -> list[tuple[str, dict]]:
    out = []
    for f in sorted(folder.glob("*.toml")):
        with open(f, "rb") as fh:
            out.append((f.name, tomllib.load(fh)))
    if not out:
        raise SystemExit(f"fuzz: no scenes in {folder}")
    return out


def num(x, default=1.0) -> float:
    return float(x) if isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(float(x)) else default


def sc_kind(s: dict) -> str:
    t = s.get("scene")
    return t.get("kind", "beam") if isinstance(t, dict) and isinstance(t.get("kind"), str) else "beam"


def sc_physics(s: dict) -> str:
    t = s.get("scene")
    return t.get("physics", "bending") if isinstance(t, dict) and isinstance(t.get("physics"), str) else "bending"


def sc_theory(s: dict) -> str:
    t = s.get("scene")
    return t.get("theory", "") if isinstance(t, dict) and isinstance(t.get("theory"), str) else ""


def geo(s: dict) -> tuple[float, float, float]:
    g = s.get("geometry") if isinstance(s.get("geometry"), dict) else {}
    return num(g.get("length")), num(g.get("width")), num(g.get("height"))


def table(s: dict, key: str) -> dict:
    t = s.get(key)
    if not isinstance(t, dict):
        t = {}
        s[key] = t
    return t


def support_keys(s: dict) -> list[str]:
    return ["x0", "xL"] if sc_kind(s) == "beam" else ["x0", "xL", "y0", "yB"]


def spring_keys(s: dict) -> list[str]:
    if sc_kind(s) != "beam":
        return ["translational", "rotational"]
    ph = sc_physics(s)
    if ph == "spatial":
        return ["translational", "rotational", "axial", "torsional"]
    if ph == "planar":
        return ["translational", "rotational", "axial"]
    return ["translational", "rotational"]


def load_components(s: dict) -> list[str]:
    if sc_kind(s) != "beam":
        return ["Fz"]
    return {"bending": ["Fz", "My"], "planar": ["Fx", "Fz", "My"]}.get(sc_physics(s), ["Fx", "Fy", "Fz", "Mx", "My", "Mz"])


def material_scales(s: dict) -> dict:
    """Reference stiffnesses for springs: EI/L^3, EI/L, EA/L, GJ/L (plates: D/a^3, D/a per length)."""
    try:
        return _material_scales(s)
    except ArithmeticError:
        return {"translational": 1.0, "rotational": 1.0, "axial": 1.0, "torsional": 1.0}


def _material_scales(s: dict) -> dict:
    L, b, h = geo(s)
    m = s.get("material") if isinstance(s.get("material"), dict) else {}
    E = num(m.get("E"), 2e11)
    nu = num(m.get("nu"), 0.3)
    if sc_kind(s) == "beam":
        EI = E * b * h ** 3 / 12.0
        return {"translational": EI / L ** 3, "rotational": EI / L, "axial": E * b * h / L,
                "torsional": E / 2.6 * 0.14 * min(b, h) ** 3 * max(b, h) / L}
    D = E * h ** 3 / (12.0 * (1.0 - nu * nu)) if abs(nu) < 1 else E * h ** 3
    return {"translational": D / L ** 3, "rotational": D / L, "axial": 1.0, "torsional": 1.0}


def point(s: dict, fx: float, fy: float = 0.5):
    """A point at fractions (fx, fy) of the body, in the scene's own form."""
    L, B, _ = geo(s)
    if sc_kind(s) == "beam":
        return fx * L
    return [fx * L, fy * B]


def rescale_positions(s: dict, fx: float, fy: float) -> None:
    """After scaling length by fx (and width by fy): move loads, probes, FRF points with the body."""
    beam = sc_kind(s) == "beam"

    def sc_point(p):
        if beam and isinstance(p, (int, float)) and not isinstance(p, bool):
            return p * fx
        if not beam and isinstance(p, list) and len(p) == 2 and all(isinstance(v, (int, float)) for v in p):
            return [p[0] * fx, p[1] * fy]
        return p

    if isinstance(s.get("loads"), list):
        for ld in s["loads"]:
            if isinstance(ld, dict):
                if isinstance(ld.get("x"), (int, float)) and not isinstance(ld.get("x"), bool):
                    ld["x"] = ld["x"] * fx
                if isinstance(ld.get("y"), (int, float)) and not isinstance(ld.get("y"), bool):
                    ld["y"] = ld["y"] * fy
    req = s.get("request")
    if isinstance(req, dict):
        if isinstance(req.get("probes"), list):
            req["probes"] = [sc_point(p) for p in req["probes"]]
        frf = req.get("frf")
        if isinstance(frf, dict):
            for k in ("excite", "observe"):
                if k in frf:
                    frf[k] = sc_point(frf[k])


def log_uniform(rng: random.Random, lo: float, hi: float) -> float:
    return 10.0 ** rng.uniform(math.log10(lo), math.log10(hi))


def extreme_factor(rng: random.Random) -> float:
    return rng.choice([1e-12, 1e-9, 1e-6, 1e-3, 1e-1, 10.0, 1e3, 1e6, 1e9, 1e12, 1e15, log_uniform(rng, 1e-12, 1e15)])


def leaf_paths(d, prefix=()) -> list[tuple]:
    """Every path to a scalar (or empty container) in the scene."""
    out = []
    if isinstance(d, dict):
        if not d and prefix:
            out.append(prefix)
        for k, v in d.items():
            out += leaf_paths(v, prefix + (k,))
    elif isinstance(d, list):
        if not d:
            out.append(prefix)
        for i, v in enumerate(d):
            out += leaf_paths(v, prefix + (i,))
    else:
        out.append(prefix)
    return out


def table_paths(d, prefix=()) -> list[tuple]:
    out = []
    if isinstance(d, dict):
        if prefix:
            out.append(prefix)
        for k, v in d.items():
            out += table_paths(v, prefix + (k,))
    elif isinstance(d, list):
        for i, v in enumerate(d):
            out += table_paths(v, prefix + (i,))
    return out


def get_path(d, path):
    for p in path:
        d = d[p]
    return d


def set_path(d, path, value):
    for p in path[:-1]:
        d = d[p]
    d[path[-1]] = value


def del_path(d, path):
    for p in path[:-1]:
        d = d[p]
    del d[path[-1]]


def is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


# ----------------------------------------------------------------------------- mutations
# Each mutation takes (scene, rng) and returns a short description. Valid-looking ones keep a
# scene that the parser should accept; hostile ones aim at the parser and the refusal paths.


def m_scale_geometry(s, rng):
    g = table(s, "geometry")
    keys = rng.choice([["length"], ["width"], ["height"], ["length", "width", "height"], ["length", "width"]])
    f = extreme_factor(rng)
    fx = fy = 1.0
    for k in keys:
        g[k] = num(g.get(k)) * f
    if "length" in keys:
        fx = f
    if "width" in keys and sc_kind(s) == "plate":
        fy = f
    rescale_positions(s, fx, fy)
    return f"geometry {'/'.join(keys)} x {f:.3g}"


def m_slenderness(s, rng):
    g = table(s, "geometry")
    L = num(g.get("length"))
    ratio = rng.choice([0.5, 1.0, 2.0, 10.0, 100.0, 1e3, 1e4, 1e5, log_uniform(rng, 0.5, 1e5)])
    g["height"] = L / ratio
    if sc_kind(s) == "beam" and rng.random() < 0.5:
        g["width"] = g["height"] * rng.choice([1.0, 0.5, 2.0, 10.0])
    return f"slenderness L/h = {ratio:.4g}"


def _fix_G(m: dict, rng=None):
    if "G" in m and "nu" in m and is_number(m.get("E")) and is_number(m.get("nu")):
        m["G"] = m["E"] / (2.0 * (1.0 + m["nu"]))


def m_scale_material(s, rng):
    m = table(s, "material")
    key = rng.choice(["E", "rho", "kappa", "E+rho", "kappa", "E"])
    f = extreme_factor(rng)
    if key == "E+rho":
        m["E"] = num(m.get("E"), 2e11) * f
        m["rho"] = num(m.get("rho"), 8000.0) * f
        if "G" in m:
            m["G"] = num(m.get("G"), 8e10) * f
        _fix_G(m)
        return f"E, rho (and G) x {f:.3g}"
    if key == "kappa":
        m["kappa"] = num(m.get("kappa"), 5 / 6) * rng.choice([1e-12, 1e-6, 1e-3, 0.5, 2.0, 1e3, 1e6, 1e15])
        return f"kappa = {m['kappa']:.3g}"
    base = {"E": 2e11, "rho": 8000.0}[key]
    m[key] = num(m.get(key), base) * f
    if key == "E":
        if "G" in m and "nu" not in m:
            m["G"] = num(m.get("G"), 8e10) * f  # keeps nu
        _fix_G(m)
    return f"{key} x {f:.3g}"


def m_set_nu(s, rng):
    m = table(s, "material")
    nu = rng.choice([-0.999999, -0.9, -0.5, 0.0, 0.1, 0.25, 0.3, 0.49, 0.4999999, rng.uniform(-0.99, 0.499)])
    m["nu"] = nu
    if "G" in m:
        if rng.random() < 0.5:
            del m["G"]
        else:
            _fix_G(m)
    return f"nu = {nu!r}"


def _spring_value(rng, ref):
    r = rng.random()
    if r < 0.2:
        return 0.0
    if r < 0.35:
        return math.inf
    return ref * log_uniform(rng, 1e-12, 1e15) if rng.random() < 0.5 else ref * rng.choice(
        [1e-12, 1e-9, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9, 1e12, 1e15])


def m_springs(s, rng):
    sup = table(s, "supports")
    ref = material_scales(s)
    ends = rng.sample(support_keys(s), rng.randint(1, len(support_keys(s))))
    for e in ends:
        sup[e] = {k: _spring_value(rng, ref[k]) for k in spring_keys(s)}
    return "springs at " + ",".join(ends)


def m_switch_supports(s, rng):
    sup = table(s, "supports")
    names = ["free", "pinned", "clamped", "guided"]
    out = []
    for e in support_keys(s):
        if rng.random() < 0.6:
            sup[e] = rng.choice(names)
            out.append(f"{e}={sup[e]}")
    return "supports " + (" ".join(out) if out else "unchanged")


def _eps(rng):
    return rng.choice([1e-7, 1e-9, 1e-12, 1e-15, 1e-5, 0.0])


def m_close_points(s, rng):
    L, B, _ = geo(s)
    beam = sc_kind(s) == "beam"
    req = table(s, "request")
    comps = load_components(s)
    variant = rng.choice(["load-near-probe", "load-at-end", "probe-at-end", "two-loads", "probe-pair", "third"])
    eps = _eps(rng)
    loads = s.get("loads") if isinstance(s.get("loads"), list) else []
    s["loads"] = loads

    def mk_load(fx, fy=0.5):
        d = {"x": fx * L}
        if not beam:
            d["y"] = fy * B
        c = rng.choice(comps)
        d[c] = rng.choice([-1000.0, 1000.0, -1.0, 10.0])
        return d

    probes = req.get("probes") if isinstance(req.get("probes"), list) else []
    req["probes"] = probes
    if variant == "load-near-probe":
        fx = rng.uniform(0.05, 0.95)
        loads.append(mk_load(fx))
        probes.append(point(s, min(1.0, fx + eps)))
    elif variant == "load-at-end":
        end = rng.choice([0.0, 1.0, eps, 1.0 - eps])
        loads.append(mk_load(end, rng.choice([0.0, 1.0, 0.5])))
    elif variant == "probe-at-end":
        probes.append(point(s, rng.choice([0.0, 1.0, eps, 1.0 - eps]), rng.choice([0.0, 1.0, eps])))
    elif variant == "two-loads":
        fx = rng.uniform(0.1, 0.9)
        loads.append(mk_load(fx))
        loads.append(mk_load(min(1.0, fx + eps)))
    elif variant == "probe-pair":
        fx = rng.uniform(0.0, 1.0)
        probes.append(point(s, fx))
        probes.append(point(s, min(1.0, fx + eps)))
    else:  # the decimal-vs-binary third of the issue
        loads.append(mk_load(1.0 / 3.0))
        probes.append(point(s, 0.333333))
    return f"{variant} eps={eps:g}"


def m_frf(s, rng):
    req = table(s, "request")
    base = req.get("frf") if isinstance(req.get("frf"), dict) else {}
    omax = num(base.get("omega_max"), 1e4)
    variant = rng.choice(["close", "same", "end", "wide", "narrow", "points"])
    eps = _eps(rng)
    fx = rng.uniform(0.05, 0.95)
    frf = {"excite": point(s, fx, 0.5), "observe": point(s, min(1.0, fx + eps), 0.5),
           "omega_min": 0.0, "omega_max": omax, "points": rng.choice([2, 3, 10, 50, 200, 400])}
    if variant == "same":
        frf["observe"] = copy.deepcopy(frf["excite"])
    elif variant == "end":
        frf["excite"] = point(s, rng.choice([0.0, 1.0]), rng.choice([0.0, 1.0]))
    elif variant == "wide":
        frf["omega_max"] = omax * rng.choice([1e2, 1e4, 1e6, 1e9])
    elif variant == "narrow":
        frf["omega_min"] = omax * 0.5
        frf["omega_max"] = omax * 0.5 * (1 + rng.choice([1e-15, 1e-12, 1e-9, 1e-6]))
    else:
        frf["points"] = rng.choice([2, 400, 399, 257])
    req["frf"] = frf
    return f"frf {variant} eps={eps:g} points={frf['points']}"


def m_modes(s, rng):
    req = table(s, "request")
    k = rng.choice([0, 1, 2, 3, 6, 12, 25, 50, 100, 150, 200])
    req["modes"] = k
    sh = req.get("shapes")
    if isinstance(sh, dict) and num(sh.get("nx"), 0) > 1000:
        req["modes"] = min(k, 8)
    return f"modes = {req['modes']}"


def m_shapes(s, rng):
    req = table(s, "request")
    beam = sc_kind(s) == "beam"
    v = rng.choice([True, False, "small", "fine"])
    if v == "small":
        req["shapes"] = {"nx": 2} if beam else {"nx": 2, "ny": 2}
    elif v == "fine":
        req["shapes"] = {"nx": 201} if beam else {"nx": 41, "ny": 21}
    else:
        req["shapes"] = v
    if isinstance(req.get("modes"), int) and req["modes"] > 50:
        req["modes"] = 50
    return f"shapes = {req['shapes']}"


def m_loss(s, rng):
    m = table(s, "material")
    m["loss_factor"] = rng.choice([0.0, 1e-12, 1e-3, 0.05, 1.0, 100.0])
    return f"loss_factor = {m['loss_factor']}"


def _convert_physics(s, ph):
    t = table(s, "scene")
    t["physics"] = ph
    keys = spring_keys(s)
    sup = table(s, "supports")
    ref = material_scales(s)
    for e, v in list(sup.items()):
        if isinstance(v, dict):
            nv = {k: v.get(k, ref.get(k, 1.0) if k in ("axial", "torsional") else 0.0) for k in keys}
            if "axial" in keys and "axial" not in v:
                nv["axial"] = math.inf
            if "torsional" in keys and "torsional" not in v:
                nv["torsional"] = math.inf
            sup[e] = nv
    comps = load_components(s)
    if isinstance(s.get("loads"), list):
        new = []
        for ld in s["loads"]:
            if isinstance(ld, dict):
                nd = {k: v for k, v in ld.items() if k in ("x", "y") or k in comps}
                if not any(c in nd for c in comps):
                    nd["Fz"] = -1000.0
                new.append(nd)
        s["loads"] = new


def m_theory(s, rng):
    t = table(s, "scene")
    if sc_kind(s) == "beam":
        choice = rng.choice(["euler-bernoulli", "timoshenko", "bending", "planar", "spatial"])
        if choice in ("bending", "planar", "spatial"):
            _convert_physics(s, choice)
            return f"physics = {choice}"
        t["theory"] = choice
        return f"theory = {choice}"
    t["theory"] = rng.choice(["kirchhoff", "mindlin"])
    return f"theory = {t['theory']}"


BACKEND_OPTIONS = {
    "exact": {"navier_static_terms": [10, 2000, 20000], "navier_frf_terms": [10, 300, 5000]},
    "rfem": {"eigen": ["auto", "dense", "shift-invert"], "dense_limit": [1, 40, 1000], "tolerance": [1e-15, 1e-10, 1e-3],
             "sturm_check": [True, False], "seed": [0, 1, 4294967295], "frf_modes": [0, 1, 20],
             "beam_rigid_shear": ["multipliers", "joint-coordinates"],
             "plate_rigid_shear": ["corner-coordinates", "multipliers"], "plate_bending_correction": [True, False]},
    "dtfm": {"layers": ["consistent", "staggered", "paper"], "kirchhoff_penalty": [1e-3, 1.0, 1e6],
             "rel_tol": [1e-15, 1e-10, 1e-3], "im_h": [1e-3, 1.0, 3.0], "re_h": [1e-3, 1.0, 20.0],
             "family_threshold": [0.0, 0.5, 1.0]},
    "difference_eq": {"static_method": ["piecewise-cubic", "eigenfunction-expansion"],
                      "residual_check_max_R": [0, 100, 10000000]},
}


def m_backend_options(s, rng):
    be = rng.choice(sorted(BACKEND_OPTIONS))
    key = rng.choice(sorted(BACKEND_OPTIONS[be]))
    val = rng.choice(BACKEND_OPTIONS[be][key])
    b = s.get("backend") if isinstance(s.get("backend"), dict) else {}
    s["backend"] = b
    b.setdefault(be, {})
    if isinstance(b[be], dict):
        b[be][key] = val
    return f"backend.{be}.{key} = {val!r}"


def m_load_magnitude(s, rng):
    f = rng.choice([0.0, 1e-300, 1e-12, 1e12, 1e100, 1e300, -1e300])
    loads = s.get("loads")
    if not isinstance(loads, list) or not loads:
        s["loads"] = loads = [{"x": point(s, 0.5)} if sc_kind(s) == "beam" else {"x": point(s, 0.5)[0], "y": point(s, 0.5)[1]}]
        loads[0]["Fz"] = -1000.0
    for ld in loads:
        if isinstance(ld, dict):
            for k in list(ld):
                if k not in ("x", "y") and is_number(ld[k]):
                    ld[k] = float(ld[k]) * f
    return f"loads x {f:g}"


def m_drop_parts(s, rng):
    what = rng.choice(["loads", "probes", "frf", "request", "kappa"])
    if what == "loads":
        s.pop("loads", None)
    elif what == "request":
        s.pop("request", None)
    elif what == "kappa":
        table(s, "material").pop("kappa", None)
    else:
        table(s, "request").pop(what, None)
    return f"drop {what}"


def m_tolerance(s, rng):
    req = table(s, "request")
    req["tolerance"] = rng.choice([1e-12, 1e-6, 1e-3, 1e-2, 0.5])
    return f"request.tolerance = {req['tolerance']!r}"


def m_structure(s, rng):
    """The structure's own keys: a support between the ends, a point mass, a distributed load,
    gravity, a round section or stepped pieces (beams); a pressure patch, gravity, a support or a
    mass at a point (plates)."""
    L, B, _ = geo(s)
    if sc_kind(s) != "beam":
        what = rng.choice(["pressure", "gravity", "point-support", "mass"])
        if what == "point-support":
            entry = {"x": rng.choice([0.5, 1e-9, 0.999]) * L, "y": rng.choice([0.5, 0.3, 1e-9]) * B,
                     "kind": rng.choice(["pinned", "clamped"])}
            table(s, "supports").setdefault("points", []).append(entry)
        elif what == "mass":
            s.setdefault("masses", []).append({"x": rng.choice([0.5, 0.0, 0.37]) * L, "y": rng.choice([0.5, 1.0]) * B,
                                               "mass": rng.choice([1e-9, 2.0, 1e6])})
        elif what == "pressure":
            x0 = rng.uniform(0.0, 0.8)
            s.setdefault("pressures", []).append({"p": rng.choice([-1000.0, 1e-12, 1e9]),
                                                  "x": [x0 * L, (x0 + rng.uniform(0.05, 0.2)) * L]})
        else:
            s["gravity"] = {"g": [0.0, 0.0, rng.choice([-9.81, 1e3, -1e-9])]}
        return f"plate {what}"
    what = rng.choice(["point-support", "mass", "line-load", "gravity", "circle", "tube", "segments"])
    if what == "segments":
        # Two or three pieces whose diameters span up to 1e3; geometry then gives only the length.
        g = table(s, "geometry")
        d = min(num(g.pop("width", None), 0.05), num(g.pop("height", None), 0.05))
        g.pop("section", None)
        cuts = sorted(rng.sample([0.1, 0.3, 0.5, 0.7, 1e-6], rng.choice([1, 2])))
        ends = [0.0] + cuts + [1.0]
        s["segments"] = [{"length": (ends[i + 1] - ends[i]) * L,
                          "section": {"shape": "circle", "diameter": d * rng.choice([1.0, 0.5, 2.0, 1e-3])}}
                         for i in range(len(ends) - 1)]
        s["segments"][-1]["length"] = L - sum(p["length"] for p in s["segments"][:-1])
    elif what == "point-support":
        sup = table(s, "supports")
        kind = rng.choice(["pinned", "clamped", "springs"])
        entry = {"x": rng.choice([0.5, 0.3, 1e-9, 1 - 1e-9, 0.999]) * L}
        if kind == "springs":
            ref = material_scales(s)
            for k in spring_keys(s):
                entry[k] = _spring_value(rng, ref.get(k, 1.0))
        else:
            entry["kind"] = kind
        sup.setdefault("points", []).append(entry)
    elif what == "mass":
        s.setdefault("masses", []).append({"x": rng.choice([0.0, 0.5, 1.0, 0.37]) * L,
                                           "mass": rng.choice([1e-9, 2.0, 1e6]), "Jy": rng.choice([0.0, 1e-3, 1e3])})
    elif what == "line-load":
        a = rng.uniform(0.0, 0.9)
        s.setdefault("line_loads", []).append({"qz": [rng.choice([-2000.0, 0.0, 1e9]), rng.choice([-2000.0, 5.0])],
                                               "x_from": a * L, "x_to": min(1.0, a + rng.uniform(1e-6, 0.5)) * L})
    elif what == "gravity":
        s["gravity"] = {"g": [0.0, 0.0, rng.choice([-9.81, 1e4, -1e-9])]}
    else:
        g = table(s, "geometry")
        d = min(num(g.pop("width", None), 0.05), num(g.pop("height", None), 0.05))
        g["section"] = ({"shape": "circle", "diameter": d} if what == "circle" else
                        {"shape": "tube", "outer_diameter": d, "inner_diameter": d * rng.choice([0.1, 0.9, 0.999])})
    return f"structure: {what}"


VALID_MUTATIONS = [
    (m_scale_geometry, 3), (m_slenderness, 3), (m_scale_material, 3), (m_set_nu, 2), (m_springs, 4),
    (m_switch_supports, 4), (m_close_points, 4), (m_frf, 3), (m_modes, 3), (m_shapes, 1), (m_loss, 1),
    (m_theory, 2), (m_backend_options, 1), (m_load_magnitude, 2), (m_drop_parts, 1), (m_tolerance, 1),
    (m_structure, 3),
]

# --- frames (scene kind "frame": nodes, members, supports by node id)


def _spatial(s) -> bool:
    return sc_physics(s) == "spatial"


def f_move_node(s, rng):
    n = rng.choice(s["nodes"])
    k = rng.choice(["x", "z"] + (["y"] if _spatial(s) else []))
    d = rng.choice([1e-9, 1e-4, 0.1, -0.5, 1.0, 10.0, 1e3])
    n[k] = num(n.get(k, 0.0), 0.0) + d
    return f"frame: node {n.get('id')}.{k} moved by {d:g}"


def f_release(s, rng):
    m = rng.choice(s["members"])
    end = rng.choice(m["nodes"])
    m["releases"] = sorted(set(m.get("releases", [])) | {end})
    return f"frame: member {m.get('id')} released at {end}"


def f_support(s, rng):
    node = rng.choice(s["nodes"])["id"]
    sup = s.setdefault("supports", {})
    if rng.random() < 0.4:
        sup[node] = rng.choice(["free", "pinned", "clamped"])
    else:
        keys = ["ux", "uy", "uz", "rx", "ry", "rz"] if _spatial(s) else ["ux", "uz", "ry"]
        sup[node] = {k: rng.choice([0.0, 1e-6, 1.0, 1e6, 1e12, float("inf")]) for k in rng.sample(keys, rng.randint(1, len(keys)))}
    return f"frame: support at {node} = {toml_value(sup[node])}"


def f_section(s, rng):
    m = rng.choice(s["members"])
    sec = m.get("section", {})
    dims = [k for k in ("width", "height", "diameter", "outer_diameter", "area", "Iy", "Iz", "J") if is_number(sec.get(k))]
    k = rng.choice(dims)
    f = 10.0 ** rng.choice([-3, -1, 1, 2])
    sec[k] = sec[k] * f
    if sec.get("shape") == "tube" and k == "outer_diameter":
        sec["inner_diameter"] = sec["outer_diameter"] * rng.choice([0.1, 0.9])
    return f"frame: member {m.get('id')} section.{k} x {f:g}"


def f_mass(s, rng):
    node = rng.choice(s["nodes"])["id"]
    entry = {"node": node, "mass": 10.0 ** rng.uniform(-3, 4)}
    if rng.random() < 0.5:
        entry["Jy"] = 10.0 ** rng.uniform(-4, 2)
    s.setdefault("masses", []).append(entry)
    return f"frame: mass {entry['mass']:.3g} kg at {node}"


def f_load(s, rng):
    mag = rng.choice([-1.0, 1.0]) * 10.0 ** rng.uniform(-3, 7)
    if rng.random() < 0.5:
        node = rng.choice(s["nodes"])["id"]
        comp = rng.choice(["Fx", "Fz", "My"] + (["Fy", "Mx", "Mz"] if _spatial(s) else []))
        s.setdefault("loads", []).append({"node": node, comp: mag})
        req = s.setdefault("request", {})
        req.setdefault("probes", [node])
        return f"frame: load {comp} = {mag:.3g} at {node}"
    m = rng.choice(s["members"])
    comp = rng.choice(["qx", "qz"] + (["qy"] if _spatial(s) else []))
    s.setdefault("line_loads", []).append({"member": m["id"], comp: [mag, rng.choice([mag, 0.0, -mag])]})
    s.setdefault("request", {}).setdefault("probes", [{"member": m["id"], "s": rng.choice([0.0, 0.3, 0.5, 1.0])}])
    return f"frame: line load {comp} ~ {mag:.3g} on {m['id']}"


def f_member(s, rng):
    ids = [n["id"] for n in s["nodes"]]
    a, b = rng.sample(ids, 2)
    first = s["members"][0]
    s["members"].append({"id": f"{a}{b}x", "nodes": [a, b], "section": copy.deepcopy(first.get("section", {}))})
    return f"frame: member {a}-{b} added"


def f_frame_request(s, rng):
    req = s.setdefault("request", {})
    what = rng.choice(["modes", "tolerance", "theory"])
    if what == "modes":
        req["modes"] = rng.choice([1, 2, 6, 20, 60])
    elif what == "tolerance":
        req["tolerance"] = rng.choice([1e-2, 1e-4, 1e-6])
    else:
        s["scene"]["theory"] = rng.choice(["euler-bernoulli", "timoshenko"])
        if s["scene"]["theory"] == "timoshenko" and any(m.get("section", {}).get("shape") == "general" for m in s["members"]):
            s.setdefault("material", {})["kappa"] = 0.5
    return f"frame: request {what}"


FRAME_MUTATIONS = [
    (f_move_node, 3), (f_release, 3), (f_support, 4), (f_section, 3), (f_mass, 2), (f_load, 3), (f_member, 2),
    (f_frame_request, 2), (m_scale_material, 2), (m_set_nu, 1), (m_drop_parts, 1),
]


# --- hostile


def h_wrong_type(s, rng):
    paths = leaf_paths(s)
    p = rng.choice(paths)
    v = rng.choice(["1.0", "", True, [1.0, 2.0], {"a": 1}, 7, 2.5, [], {}, -3, "clamped"])
    set_path(s, p, v)
    return f"wrong type at {'.'.join(map(str, p))} = {toml_value(v)[:40]}"


def h_missing_key(s, rng):
    if rng.random() < 0.3:
        k = rng.choice([k for k in s])
        del s[k]
        return f"missing table {k}"
    p = rng.choice(leaf_paths(s))
    del_path(s, p)
    return f"missing key {'.'.join(map(str, p))}"


UNKNOWN_KEYS = ["bogus", "Length", "E ", "\u0415", "length2", "x1", "Fz2", "theta", "", "a.b", "ü", "modes_"]


def h_unknown_key(s, rng):
    tabs = [()] + [p for p in table_paths(s) if isinstance(get_path(s, p), dict)]
    p = rng.choice(tabs)
    t = get_path(s, p) if p else s
    k = rng.choice(UNKNOWN_KEYS)
    t[k] = rng.choice([1.0, "x", True, {"y": 2}])
    return f"unknown key {toml_string(k)} in {'.'.join(map(str, p)) or '<root>'}"


def h_bad_number(s, rng):
    paths = [p for p in leaf_paths(s) if is_number(get_path(s, p))]
    if not paths:
        return h_wrong_type(s, rng)
    p = rng.choice(paths)
    v = rng.choice([math.nan, math.inf, -math.inf, -1.0, 0.0, -0.0, 5e-324, 1.7e308, -1e-300, 0, -1])
    set_path(s, p, v)
    return f"{'.'.join(map(str, p))} = {toml_value(v)}"


def h_huge_string(s, rng):
    n = rng.choice([1000, 100_000, 300_000, 1_100_000])
    ch = rng.choice(["x", "\u00e9", "\"", "\\", "\u0000", "\n", "\U0001F600"])
    width = len(toml_string(ch).encode("utf-8")) - 2  # bytes per character in the file
    text = ch * max(1, n // width)
    where = rng.choice(["name", "support", "theory", "option"])
    if where == "name":
        table(s, "scene")["name"] = text
    elif where == "support":
        table(s, "supports")[rng.choice(support_keys(s))] = text
    elif where == "theory":
        table(s, "scene")["theory"] = text
    else:
        s["backend"] = {"rfem": {"eigen": text}}
    return f"huge string ({n} x {ch!r}) in {where}"


def h_empty_table(s, rng):
    tabs = [p for p in table_paths(s) if isinstance(get_path(s, p), dict)]
    p = rng.choice(tabs)
    set_path(s, p, {})
    return f"empty table {'.'.join(map(str, p))}"


def h_outside(s, rng):
    L, B, _ = geo(s)
    beam = sc_kind(s) == "beam"
    bad = rng.choice([-1e-12, -1.0, L * (1 + 1e-9), L + 1e-300, 1e300, -0.0, 2 * L, math.nan, math.inf])
    where = rng.choice(["load", "probe", "excite", "observe", "arity"])
    req = table(s, "request")
    if where == "load":
        d = {"x": bad, "Fz": -1.0} if beam else {"x": rng.choice([bad, 0.5 * L]), "y": rng.choice([bad, B * 1.5]), "Fz": -1.0}
        s["loads"] = (s["loads"] if isinstance(s.get("loads"), list) else []) + [d]
    elif where == "probe":
        p = bad if beam else [0.5 * L, rng.choice([bad, B * (1 + 1e-12)])]
        req["probes"] = (req["probes"] if isinstance(req.get("probes"), list) else []) + [p]
    elif where in ("excite", "observe"):
        frf = req.get("frf") if isinstance(req.get("frf"), dict) else {
            "excite": point(s, 0.3), "observe": point(s, 0.6), "omega_min": 0.0, "omega_max": 1e4, "points": 10}
        frf[where] = bad if beam else [bad, 0.5 * B]
        req["frf"] = frf
    else:
        p = rng.choice([[0.5 * L], [0.5 * L, 0.5 * B, 0.0], [], "mid", [[0.1, 0.1]]]) if not beam else rng.choice(
            [[0.5 * L], [0.5 * L, 0.0], "mid", True])
        req["probes"] = [p]
    return f"{where} outside/misshapen: {toml_value(bad) if where != 'arity' else 'arity'}"


BAD_SUPPORT_NAMES = ["Clamped", " clamped", "clamped ", "clamp", "", "fixed", "simply-supported", "pinned\u0000",
                     "FREE", "guided\n", "hinged", "inf", "0"]


def h_bad_support(s, rng):
    sup = table(s, "supports")
    e = rng.choice(support_keys(s) + ["x1", "yL"])
    ref = material_scales(s)
    v = rng.choice(["name", "missing", "negative", "nan", "string", "extra", "empty"])
    if v == "name":
        sup[e] = rng.choice(BAD_SUPPORT_NAMES)
    else:
        d = {k: ref[k] for k in spring_keys(s)}
        if v == "missing":
            d.pop(rng.choice(list(d)))
        elif v == "negative":
            d[rng.choice(list(d))] = rng.choice([-1.0, -math.inf, -1e-300])
        elif v == "nan":
            d[rng.choice(list(d))] = math.nan
        elif v == "string":
            d[rng.choice(list(d))] = rng.choice(["inf", "rigid", "1e9"])
        elif v == "extra":
            d[rng.choice(["axial", "torsional", "shear", "Translational"])] = 1.0
        else:
            d = {}
        sup[e] = d
    return f"bad support {e}: {v}"


def h_broken_frf(s, rng):
    req = table(s, "request")
    frf = {"excite": point(s, 0.3), "observe": point(s, 0.6), "omega_min": 0.0, "omega_max": 1e4, "points": 10}
    v = rng.choice(["reversed", "empty", "negative", "points", "nan", "inf", "missing", "string"])
    if v == "reversed":
        frf["omega_min"], frf["omega_max"] = 2e4, 1e4
    elif v == "empty":
        frf["omega_min"] = frf["omega_max"] = 1e4
    elif v == "negative":
        frf["omega_min"] = -1.0
    elif v == "points":
        frf["points"] = rng.choice([0, 1, -5, 2.5, 1000001, 9223372036854775807, True])
    elif v == "nan":
        frf[rng.choice(["omega_min", "omega_max"])] = math.nan
    elif v == "inf":
        frf["omega_max"] = math.inf
    elif v == "missing":
        del frf[rng.choice(list(frf))]
    else:
        frf[rng.choice(["excite", "observe", "points"])] = "0.5"
    req["frf"] = frf
    return f"broken frf: {v}"


def h_bad_enum(s, rng):
    t = table(s, "scene")
    k = rng.choice(["kind", "physics", "theory"])
    t[k] = rng.choice(["shell", "plate", "beam", "spatial", "planar", "mindlin", "timoshenko", "kirchhoff",
                       "euler-bernoulli", "Euler-Bernoulli", "torsion", ""])
    return f"scene.{k} = {t[k]!r}"


def h_structure(s, rng):
    v = rng.choice(["loads-table", "loads-empty", "load-int", "probes-scalar", "request-string", "backend-string",
                    "backend-unknown", "option-bad", "modes-bad", "shapes-bad", "load-no-component", "deep-array"])
    req = table(s, "request") if v in ("probes-scalar", "modes-bad", "shapes-bad") else None
    if v == "loads-table":
        s["loads"] = {"x": 0.5, "Fz": 1.0}
    elif v == "loads-empty":
        s["loads"] = []
    elif v == "load-int":
        s["loads"] = (s["loads"] if isinstance(s.get("loads"), list) else []) + [3]
    elif v == "probes-scalar":
        req["probes"] = 0.5
    elif v == "request-string":
        s["request"] = "all"
    elif v == "backend-string":
        s["backend"] = "rfem"
    elif v == "backend-unknown":
        s["backend"] = {rng.choice(["fem", "Exact", "rfem2"]): {"eigen": "dense"}}
    elif v == "option-bad":
        be = rng.choice(sorted(BACKEND_OPTIONS))
        key = rng.choice(sorted(BACKEND_OPTIONS[be]) + ["bogus"])
        s["backend"] = {be: {key: rng.choice([-1, 1e300, "maybe", math.nan, 0.0, [1], 1e-300])}}
    elif v == "modes-bad":
        req["modes"] = rng.choice([-1, 100001, 2.5, "6", True, 1 << 40])
    elif v == "shapes-bad":
        req["shapes"] = rng.choice([{"nx": 1}, {"nx": 100002}, {"nx": 0}, {"nx": 1001, "ny": 1001}, {"ny": 3}, "yes",
                                    {"nx": 2.5}, {"nx": 3, "nz": 3}, []])
    elif v == "load-no-component":
        s["loads"] = [{"x": point(s, 0.5) if sc_kind(s) == "beam" else 0.0}]
    else:
        table(s, "request")["probes"] = [[[[0.1]]]]
    return f"structure: {v}"


def h_inconsistent_G(s, rng):
    m = table(s, "material")
    E = num(m.get("E"), 2e11)
    m["nu"] = rng.choice([0.3, 0.25])
    m["G"] = E / (2 * (1 + m["nu"])) * rng.choice([1 + 1e-5, 1 + 1e-7, 0.5, 2.0, 1e-300])
    return f"G vs E, nu: G = {m['G']!r}"


HOSTILE_MUTATIONS = [
    (h_wrong_type, 3), (h_missing_key, 3), (h_unknown_key, 2), (h_bad_number, 4), (h_huge_string, 1),
    (h_empty_table, 2), (h_outside, 3), (h_bad_support, 3), (h_broken_frf, 2), (h_bad_enum, 2),
    (h_structure, 3), (h_inconsistent_G, 1),
]


def weighted(rng, items):
    total = sum(w for _, w in items)
    r = rng.uniform(0, total)
    for f, w in items:
        r -= w
        if r <= 0:
            return f
    return items[-1][0]


def corrupt_syntax(text: str, rng) -> bytes:
    v = rng.choice(["truncate", "dup-table", "bracket", "bad-utf8", "bom", "dup-key", "nul"])
    b = text.encode("utf-8")
    if v == "truncate":
        return b[: rng.randint(0, max(0, len(b) - 1))]
    if v == "dup-table":
        return b + b"\n[geometry]\nlength = 1.0\n"
    if v == "bracket":
        return b.replace(b"[request]", b"[request", 1) if b"[request]" in b else b"[scene\n" + b
    if v == "bad-utf8":
        i = rng.randint(0, len(b))
        return b[:i] + b"\xff\xfe\xc3" + b[i:]
    if v == "bom":
        return b"\xef\xbb\xbf" + b
    if v == "dup-key":
        return b.replace(b"[geometry]\n", b"[geometry]\nlength = 2.0\n", 1)
    i = rng.randint(0, len(b))
    return b[:i] + b"\x00" + b[i:]


MESHES = {
    ("rfem", "beam"): ["1", "2", "8", "64", "256", "1024"],
    ("rfem", "plate"): ["1x1", "2x2", "4x4", "16x8", "8x16", "32x20"],
    ("difference_eq", "beam"): ["1", "2", "8", "64", "1000", "4096"],
    ("difference_eq", "plate"): ["8"],
    ("dtfm", "beam"): ["1x1", "2x2", "1x3", "4x4", "8"],
    ("dtfm", "plate"): ["1", "2", "4", "10", "20", "16x8"],
}
MESHES[("rfem", "frame")] = ["1", "2", "8", "64"]
HOSTILE_MESHES = ["0", "-1", "4x", "x4", "1e3", "abc", "99999999", "4x4x4", "8", "4x4", "16x8", " 8", "0x0"]


def make_case(builtins, seed: int, case: int, backends: list[str]):
    """Deterministic scene for (seed, case): (origin, mutation descriptions, bytes, meshes)."""
    rng = random.Random(f"modalbench-fuzz:{seed}:{case}")
    origin, base = rng.choice(builtins)
    s = copy.deepcopy(base)
    muts = []
    hostile_case = rng.random() < 0.35
    for _ in range(rng.randint(1, 3)):
        hostile = hostile_case and rng.random() < 0.6
        valid = FRAME_MUTATIONS if sc_kind(s) == "frame" else VALID_MUTATIONS
        f = weighted(rng, HOSTILE_MUTATIONS if hostile else valid)
        try:
            muts.append(f(s, rng))
        except (KeyError, IndexError, TypeError, AttributeError, ValueError, ArithmeticError) as e:
            muts.append(f"{f.__name__}: skipped ({type(e).__name__})")
    # bound the request sizes (a correct program answers in seconds)
    req = s.get("request")
    if isinstance(req, dict):
        if isinstance(req.get("modes"), int) and not isinstance(req.get("modes"), bool) and 200 < req["modes"] <= 100000:
            req["modes"] = 200
        frf = req.get("frf")
        if isinstance(frf, dict) and isinstance(frf.get("points"), int) and not isinstance(frf.get("points"), bool) \
                and 400 < frf["points"] <= 1000000:
            frf["points"] = 400
    # meshes: drawn for every back-end (so that --backends does not change the draw), used where selected
    meshes = {}
    if rng.random() < 0.25:
        kind = sc_kind(s) if sc_kind(s) in ("beam", "plate", "frame") else "beam"
        for be in ALL_BACKENDS:
            if be == "exact":
                continue
            if rng.random() < 0.1:
                meshes[be] = rng.choice(HOSTILE_MESHES)
            else:
                meshes[be] = rng.choice(MESHES.get((be, kind), ["8"]))
    meshes = {k: v for k, v in meshes.items() if k in backends}
    header = f"fuzz case seed={seed} case={case} origin={origin}\nmutations: " + " | ".join(muts)
    if meshes:
        header += "\nfuzz-mesh: " + " ".join(f"{k}={v}" for k, v in sorted(meshes.items()))
    text = emit_toml(s, header)
    data = text.encode("utf-8")
    if hostile_case and rng.random() < 0.08:
        data = corrupt_syntax(text, rng)
        muts.append("syntax corruption")
    else:
        # self-check of the emitter: the text must parse back to the same document
        try:
            back = tomllib.loads(text)
            if not _same(back, s):
                muts.append("EMITTER-MISMATCH")
        except tomllib.TOMLDecodeError as e:
            muts.append(f"EMITTER-INVALID({e})")
    return origin, muts, data, meshes, s


# ----------------------------------------------------------------------------- running


def _limits(mem_mb: int):
    def fn():
        if mem_mb > 0:
            b = mem_mb * 1024 * 1024
            resource.setrlimit(resource.RLIMIT_AS, (b, b))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return fn


def solve_command(exe: str, scene, backend: str, mesh: str | None, max_time: float) -> list[str]:
    cmd = [exe, "solve", str(scene), "--backend", backend, "--json"]
    if mesh is not None:
        cmd.append("--mesh=" + mesh)  # one argument: "-1" is a value, not an option
    if max_time > 0:
        cmd.append(f"--max-time={max_time:g}")
    return cmd


def run_one(exe: str, scene: Path, backend: str, mesh: str | None, time_cap: float, mem_mb: int, env: dict,
            max_time: float = 0.0) -> dict:
    cmd = solve_command(exe, scene, backend, mesh, max_time)
    t0 = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, env=env,
                            start_new_session=True, preexec_fn=_limits(mem_mb))
    timed_out = False
    try:
        out, err = proc.communicate(timeout=time_cap)
    except subprocess.TimeoutExpired:
        timed_out = True
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        out, err = proc.communicate()
    dt = time.monotonic() - t0
    return {"cmd": cmd, "rc": proc.returncode, "stdout": out, "stderr": err, "time_s": dt, "timed_out": timed_out}


def _reject_constant(name):
    raise ValueError(f"non-JSON constant {name}")


def parse_one_object(text: str):
    """The stdout must be exactly one JSON object (whitespace around it allowed)."""
    stripped = text.strip()
    if not stripped:
        return None, "empty stdout"
    if not stripped.startswith("{"):
        return None, "stdout does not start with a JSON object: " + stripped[:80].replace("\n", "\\n")
    dec = json.JSONDecoder(parse_constant=_reject_constant)
    try:
        obj, end = dec.raw_decode(stripped)
    except ValueError as e:
        return None, f"not JSON: {e}"
    if stripped[end:].strip():
        return None, "text after the JSON object: " + stripped[end:].strip()[:80].replace("\n", "\\n")
    if not isinstance(obj, dict):
        return None, "not a JSON object"
    return obj, ""


def _finite(v) -> bool:
    return is_number(v) and math.isfinite(v)


def not_computed(obj: dict) -> str:
    """The warnings by which a successful result says a requested quantity was not computed."""
    return " ".join(w for w in (obj.get("warnings") or []) if isinstance(w, str) and w.startswith("not computed"))


def check_success(obj: dict, scene: dict | None) -> list[str]:
    """Contract of a success: every reported number finite, frequencies ascending, counts honoured."""
    bad = []
    fr = obj.get("frequencies_rad_s")
    if not isinstance(fr, list):
        return ["frequencies_rad_s missing"]
    for i, f in enumerate(fr):
        if not _finite(f):
            bad.append(f"frequency {i + 1} is {f!r}")
        elif f < 0:
            bad.append(f"frequency {i + 1} negative ({f!r})")
    vals = [f for f in fr if _finite(f)]
    for i in range(1, len(vals)):
        if vals[i] < vals[i - 1]:
            bad.append(f"frequencies not ascending at {i + 1}: {vals[i - 1]!r} > {vals[i]!r}")
            break
    fams = obj.get("mode_families")
    if isinstance(fams, list) and len(fams) != len(fr):
        bad.append(f"{len(fams)} mode families for {len(fr)} frequencies")
    req = scene.get("request") if isinstance(scene, dict) else None
    skipped = not_computed(obj).lower()  # quantities the back-end says it does not compute
    if isinstance(req, dict):
        k = req.get("modes")
        if isinstance(k, int) and not isinstance(k, bool) and len(fr) != k and "frequenc" not in skipped \
                and "modes" not in skipped:
            # fewer is acceptable when the result says the model has no more ("3 of 8 requested modes computed")
            said = any(isinstance(w, str) and "requested" in w for w in (obj.get("warnings") or []))
            if len(fr) > k or not said:
                bad.append(f"{len(fr)} frequencies for modes = {k}")
        pr = req.get("probes")
        if isinstance(pr, list) and isinstance(obj.get("deflections"), list) and len(obj["deflections"]) != len(pr) \
                and "deflection" not in skipped and "statics" not in skipped:
            bad.append(f"{len(obj['deflections'])} deflections for {len(pr)} probes")
        frf = req.get("frf")
        if isinstance(frf, dict) and isinstance(frf.get("points"), int) and "frf" not in skipped:
            got = obj.get("frf")
            if not isinstance(got, list) or len(got) == 0:
                bad.append("frf requested but none reported")
            elif len(got) > frf["points"]:
                bad.append(f"{len(got)} FRF samples for points = {frf['points']}")
    for i, d in enumerate(obj.get("deflections") or []):
        if isinstance(d, dict):
            for k, v in d.items():
                if k == "probe" or (k == "forces" and isinstance(v, dict) and "axes" in v):  # a frame's labels
                    v = {kk: vv for kk, vv in v.items() if kk != "axes"} if k == "forces" else None
                    if v is None:
                        continue
                values = list(v.values()) if isinstance(v, dict) else v if isinstance(v, list) else [v]  # forces: a dict
                for x in values:
                    if not _finite(x):
                        bad.append(f"deflections[{i}].{k} is {x!r}")
    for i, d in enumerate(obj.get("frf") or []):
        if isinstance(d, dict):
            for k in ("omega_rad_s", "re", "im"):
                if not _finite(d.get(k)):
                    bad.append(f"frf[{i}].{k} is {d.get(k)!r}")
                    break
    ms = obj.get("mode_shapes")
    if isinstance(ms, dict):
        def walk(v, where):
            if isinstance(v, dict):
                for k, x in v.items():
                    if k not in ("note", "normalization"):
                        walk(x, f"{where}.{k}")
            elif isinstance(v, list):
                for j, x in enumerate(v):
                    walk(x, f"{where}[{j}]")
            elif not _finite(v):
                bad.append(f"{where} is {v!r}")
        walk(ms, "mode_shapes")
    t = obj.get("timing_s")
    if isinstance(t, dict):
        for k, v in t.items():
            if not _finite(v) or v < 0:
                bad.append(f"timing_s.{k} is {v!r}")
    if len(bad) > 6:
        bad = bad[:6] + [f"... {len(bad) - 6} more"]
    return bad


def classify(r: dict, scene: dict | None) -> dict:
    rc = r["rc"]
    out = r["stdout"].decode("utf-8", "replace")
    err = r["stderr"].decode("utf-8", "replace")
    last_err = err.strip().splitlines()[-1] if err.strip() else ""
    res = {"class": "", "status": "", "message": "", "obj": None, "rc": rc}
    if r["timed_out"]:
        res.update({"class": "timeout", "message": f"killed after {r['time_s']:.1f} s"})
        return res
    if rc < 0:
        try:
            name = signal.Signals(-rc).name
        except ValueError:
            name = f"signal {-rc}"
        res.update({"class": "crash", "message": f"killed by {name}; stderr: {last_err}"})
        return res
    if rc == 1:
        if "terminate" in err or "AddressSanitizer" in err or "runtime error:" in err:
            res.update({"class": "crash", "message": f"exit 1: {last_err}"})
        else:
            res.update({"class": "internal-error", "message": f"exit 1: {last_err or 'no message'}"})
        return res
    if rc > 3:
        res.update({"class": "bad-exit", "message": f"exit {rc}: {last_err}"})
        if "AddressSanitizer" in err or "runtime error:" in err or "LeakSanitizer" in err:
            res["class"] = "crash"
        return res
    obj, why = parse_one_object(out)
    if obj is None:
        res.update({"class": "invalid-json", "message": f"exit {rc}: {why}; stderr: {last_err}"})
        return res
    res["obj"] = obj
    status = obj.get("status")
    res["status"] = status if isinstance(status, str) else ""
    res["message"] = str(obj.get("message", ""))
    if "runtime error:" in err:  # UBSan reports without aborting
        res.update({"class": "crash", "message": "UBSan: " + err[err.index("runtime error:"):][:200]})
        return res
    if rc == 2:
        if status in CLEAN_ERROR_STATUSES or (status is None and "error" in obj):
            res["class"] = "clean-error"
        else:
            res.update({"class": "bad-exit", "message": f"exit 2 with status {status!r}: {res['message']}"})
        return res
    if rc == 3:
        if status in FLAGGED_STATUSES:
            res["class"] = "flagged"
        else:
            res.update({"class": "bad-exit", "message": f"exit 3 with status {status!r}: {res['message']}"})
        return res
    # rc == 0
    if status != "success":
        res.update({"class": "bad-exit", "message": f"exit 0 with status {status!r}: {res['message']}"})
        return res
    bad = check_success(obj, scene)
    if bad:
        res.update({"class": "bad-result", "message": "; ".join(bad)})
    else:
        res["class"] = "success"
    return res


# ----------------------------------------------------------------------------- cross-checks


def error_estimate(obj: dict):
    """The result's own relative error estimate of its frequencies, if it states one: a top-level
    "error_estimate" (a number, or an object with "frequencies") or a diagnostic named like
    "*error_estimate*"."""
    cands = []
    ee = obj.get("error_estimate")
    if isinstance(ee, dict):
        ee = ee.get("frequencies")
    if _finite(ee):
        cands.append(abs(ee))
    for k, v in (obj.get("diagnostics") or {}).items():
        if "error_estimate" in k and _finite(v):
            cands.append(abs(v))
    return max(cands) if cands else None


def _families(obj):
    fr = obj.get("frequencies_rad_s") or []
    fams = obj.get("mode_families") or []
    if len(fams) != len(fr):
        fams = ["unknown"] * len(fr)
    top = max([f for f in fr if _finite(f)], default=0.0)
    out = []
    for f, fam in zip(fr, fams):
        if not _finite(f) or f <= 0 or fam == "rigid" or f <= 1e-8 * top:
            continue
        out.append((fam, f))
    return out


def pair_frequencies(a: dict, b: dict, physics: str, a_bending_only: bool, b_bending_only: bool):
    """Pairs of (label, fa, fb): per family when both label every mode, else in order."""
    fa, fb = _families(a), _families(b)
    known = lambda lst: all(fam not in ("unknown",) for fam, _ in lst)
    if fa and fb and known(fa) and known(fb):
        pairs = []
        for fam in sorted(set(x for x, _ in fa) & set(x for x, _ in fb)):
            la = [f for x, f in fa if x == fam]
            lb = [f for x, f in fb if x == fam]
            pairs += [(f"{fam}#{i + 1}", p, q) for i, (p, q) in enumerate(zip(la, lb))]
        return pairs
    if physics in ("planar", "spatial") and (a_bending_only or b_bending_only):
        return []  # one models bending only and the other's modes are unlabelled: no pairing
    return [(f"#{i + 1}", p, q) for i, ((_, p), (_, q)) in enumerate(zip(fa, fb))]


def refusal_reasons(message: str, backend: str) -> list[str]:
    """The reasons of an invalid-input result that are about the scene itself: not about the back-end's
    own mesh (difference_eq's loads at nodes, a --mesh too coarse), its own [backend.NAME] options, or a
    discretization-error flag raised beside the refusal."""
    out = []
    for part in message.split("; "):
        if "--mesh" in part or "command line" in part or f"backend.{backend}." in part:
            continue
        if re.search(r"\bmesh\b", part) and "mechanism" not in part:
            continue
        out.append(part)
    return out


def cross_check(scene: dict | None, results: dict, meshes: dict) -> list[dict]:
    findings = []
    if not isinstance(scene, dict):
        return findings
    beam = sc_kind(scene) == "beam"
    theory = sc_theory(scene)
    physics = sc_physics(scene)
    ok = {be: r for be, r in results.items() if r["class"] == "success"}
    # (i) a back-end refuses the scene as invalid (a mechanism) while another solves it
    for be, r in results.items():
        obj = r.get("obj")
        if r["class"] != "clean-error" or r["status"] != "invalid-input" or not isinstance(obj, dict):
            continue
        if "backend" not in obj:
            # a load-time or command-line refusal: shared by all back-ends unless it is about --mesh
            continue
        reasons = refusal_reasons(r["message"], be)
        if not reasons:
            continue
        for be2, r2 in ok.items():
            if be2 == be or not_computed(r2["obj"]):
                continue  # a success that skipped a quantity does not contradict a refusal of it
            findings.append({"kind": XC_REFUSAL, "backends": (be, be2), "rank": (0, 0),
                             "message": f"{be} refuses (invalid-input: {'; '.join(reasons)[:200]}) but {be2} succeeds"})
    # (ii) frequencies of two successes
    names = sorted(ok)
    for i in range(len(names)):
        for j in range(i + 1, len(names)):
            a, b = names[i], names[j]
            if beam and theory == "timoshenko" and "difference_eq" in (a, b):
                continue
            oa, ob = ok[a]["obj"], ok[b]["obj"]
            tol_kind = XC_CONTRA_NOEST
            ea, eb = error_estimate(oa), error_estimate(ob)
            if ea is not None or eb is not None:
                tol = max(ESTIMATE_SAFETY * ((ea or 0.0) + (eb or 0.0)), 1e-9)
                tol_kind = XC_CONTRA
            else:
                tol = NO_ESTIMATE_TOL
            other_model = False
            for be, o in ((a, oa), (b, ob)):
                if be == "dtfm" and beam and str(o.get("mesh", meshes.get("dtfm", ""))) not in ("1x1", "1"):
                    other_model = True  # multi-prism sections tend to 3D elasticity
                elif (o.get("method") or {}).get("converges_to_scene_theory") is False:
                    other_model = True
            if other_model:
                findings.append({"kind": XC_OTHER_MODEL, "backends": (a, b), "rank": (0, 0), "message": ""})
                continue
            pairs = pair_frequencies(oa, ob, physics, a == "difference_eq", b == "difference_eq")
            worst = None
            first = None
            nbad = 0
            for idx, (label, p, q) in enumerate(pairs):
                rel = abs(p - q) / max(abs(p), abs(q))
                if rel > tol:
                    nbad += 1
                    if first is None:
                        first = (idx + 1, label, p, q, rel)
                    if worst is None or rel > worst[4]:
                        worst = (idx + 1, label, p, q, rel)
            if first is None:
                continue
            low = first[0] <= LOW_MODES
            findings.append({
                "kind": tol_kind, "backends": (a, b), "low": low, "rank": (first[0], -worst[4]),
                "message": (f"{a} vs {b} (mesh {oa.get('mesh')} / {ob.get('mesh')}): {nbad}/{len(pairs)} paired modes "
                            f"beyond tol {tol:.3g}; first at pair {first[0]} ({first[1]}): {first[2]:.9g} vs "
                            f"{first[3]:.9g} rad/s (rel {first[4]:.3g}); worst pair {worst[0]} ({worst[1]}): "
                            f"{worst[2]:.9g} vs {worst[3]:.9g} (rel {worst[4]:.3g})")})
    return findings


# ----------------------------------------------------------------------------- driver


def safe_name(s: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.+-]+", "-", s).strip("-")


def command_line(exe: str, scene: Path, backend: str, mesh: str | None, max_time: float = 0.0) -> str:
    args = solve_command(exe, scene, backend, mesh, max_time)
    quoted = [a if re.match(r"^[A-Za-z0-9_./=:+-]+$", a) else "'" + a.replace("'", "'\\''") + "'" for a in args]
    return f"MODALBENCH_SCENES={DEFAULT_SCENES} " + " ".join(quoted)


def keep_finding(folder: Path, cls: str, seed, case, backend: str, data: bytes, exe: str, meshes: dict,
                 message: str, max_time: float = 0.0) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{safe_name(cls)}-{seed}-{case}-{safe_name(backend)}.toml"
    be_list = backend.split("-vs-")
    cmds = [command_line(exe, path, be, meshes.get(be), max_time) for be in be_list]
    header = [f"# class: {cls}", f"# backend: {backend}"] + [f"# command: {c}" for c in cmds]
    header.append("# message: " + message.replace("\n", " ")[:400])
    if meshes and not MESH_LINE.search(data[:4096]):
        header.append("# fuzz-mesh: " + " ".join(f"{k}={v}" for k, v in sorted(meshes.items())))
    path.write_bytes(("\n".join(header) + "\n").encode("utf-8") + data)
    return path


MESH_LINE = re.compile(rb"^# fuzz-mesh: (.*)$", re.M)


def meshes_from_header(data: bytes) -> dict:
    m = MESH_LINE.search(data[:4096])
    if not m:
        return {}
    out = {}
    for tok in m.group(1).decode("utf-8", "replace").split():
        if "=" in tok:
            k, v = tok.split("=", 1)
            out[k] = v
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="seeded scene fuzzer for modalbench solve --json")
    ap.add_argument("--exe", required=True, help="the modalbench executable")
    ap.add_argument("--cases", type=int, default=100)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", required=True, help="output folder (runs.csv, summary.txt, scenes/)")
    ap.add_argument("--time-cap", type=float, default=20.0, help="wall seconds per run (default 20)")
    ap.add_argument("--mem-cap-mb", type=int, default=3000, help="address-space cap per run in MB; 0: none (ASan)")
    ap.add_argument("--solver-max-time", type=float, default=None,
                    help="passed as modalbench --max-time (its own estimate-based refusal); default: a quarter of "
                         "--time-cap; 0: not passed")
    ap.add_argument("--backends", default=",".join(ALL_BACKENDS))
    ap.add_argument("--replay", metavar="CORPUS_DIR", help="run every *.toml of CORPUS_DIR instead of mutating")
    ap.add_argument("--keep-findings", metavar="DIR", help="write each failed run and cross-check finding as a scene")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--strict", action="store_true", help="cross-check findings count as failures")
    ap.add_argument("--scenes", default=os.environ.get("MODALBENCH_SCENES", str(DEFAULT_SCENES)),
                    help="built-in scenes to mutate (default: $MODALBENCH_SCENES or the repo's scenes/)")
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)

    exe = os.path.abspath(args.exe)
    if not os.access(exe, os.X_OK):
        print(f"fuzz: {exe} is not an executable", file=sys.stderr)
        return 2
    backends = [b.strip() for b in args.backends.split(",") if b.strip()]
    max_time = args.time_cap / 4 if args.solver_max_time is None else args.solver_max_time
    out = Path(args.out)
    (out / "scenes").mkdir(parents=True, exist_ok=True)
    keep = Path(args.keep_findings) if args.keep_findings else None
    env = dict(os.environ)
    env.setdefault("MODALBENCH_SCENES", str(DEFAULT_SCENES))
    env.setdefault("ASAN_OPTIONS", "detect_leaks=1:abort_on_error=0")
    env.setdefault("UBSAN_OPTIONS", "print_stacktrace=1")

    # 1. the scenes (serial, deterministic)
    cases = []  # (case_id, origin, muts, path, data, meshes, doc)
    if args.replay:
        files = sorted(Path(args.replay).glob("*.toml"))
        if not files:
            print(f"fuzz: no *.toml in {args.replay}", file=sys.stderr)
            return 2
        for f in files:
            data = f.read_bytes()
            try:
                doc = tomllib.loads(data.decode("utf-8"))
            except (tomllib.TOMLDecodeError, UnicodeDecodeError):
                doc = None
            cases.append((f.stem, f.name, ["replay"], f.resolve(), data, meshes_from_header(data), doc))
        seed_label = "replay"
    else:
        builtins = load_builtin_scenes(Path(args.scenes))
        for i in range(args.cases):
            origin, muts, data, meshes, doc = make_case(builtins, args.seed, i, backends)
            path = (out / "scenes" / f"case-{args.seed}-{i:05d}.toml").resolve()
            path.write_bytes(data)
            try:
                parsed = tomllib.loads(data.decode("utf-8"))
            except (tomllib.TOMLDecodeError, UnicodeDecodeError):
                parsed = None
            cases.append((i, origin, muts, path, data, meshes, parsed))
        seed_label = str(args.seed)

    # 2. the runs
    t_start = time.monotonic()
    jobs = [(ci, be) for ci in range(len(cases)) for be in backends]

    def work(job):
        ci, be = job
        c = cases[ci]
        r = run_one(exe, c[3], be, c[5].get(be), args.time_cap, args.mem_cap_mb, env, max_time)
        r.update(classify(r, c[6]))
        return job, r

    results: dict = {}
    done = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        for job, r in pool.map(work, jobs):
            results[job] = r
            done += 1
            if not args.quiet and r["class"] in FAILED_CLASSES:
                c = cases[job[0]]
                print(f"  {r['class']}: case {c[0]} {job[1]}: {r['message'][:160]}", flush=True)
            if not args.quiet and done % 200 == 0:
                print(f"  ... {done}/{len(jobs)} runs, {time.monotonic() - t_start:.0f} s", flush=True)
    wall = time.monotonic() - t_start

    # 3. classification, cross-checks, files
    counts = {c: 0 for c in ALL_CLASSES}
    xc_counts = {k: 0 for k in XC_KINDS}
    xc_low = 0
    other_model_pairs = 0
    all_findings = []
    failures = []
    with open(out / "runs.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["case", "seed", "origin", "mutations", "backend", "mesh", "class", "exit_code", "status", "time_s",
                    "message"])
        for ci, c in enumerate(cases):
            per = {}
            for be in backends:
                r = results[(ci, be)]
                per[be] = r
                counts[r["class"]] = counts.get(r["class"], 0) + 1
                w.writerow([c[0], seed_label, c[1], " | ".join(c[2])[:500], be, c[5].get(be, ""), r["class"], r["rc"],
                            r["status"], f"{r['time_s']:.3f}", r["message"].replace("\n", " ")[:200]])
                if r["class"] in FAILED_CLASSES:
                    p = None
                    if keep:
                        p = keep_finding(keep, r["class"], seed_label, c[0], be, c[4], exe, c[5], r["message"], max_time)
                    failures.append((r["class"], c, be, r, p))
            for f in cross_check(c[6], per, c[5]):
                if f["kind"] == XC_OTHER_MODEL:
                    other_model_pairs += 1
                    continue
                xc_counts[f["kind"]] += 1
                if f.get("low"):
                    xc_low += 1
                p = None
                if keep:
                    p = keep_finding(keep, f["kind"], seed_label, c[0], "-vs-".join(f["backends"]), c[4], exe, c[5],
                                     f["message"], max_time)
                all_findings.append((f, c, p))

    failed_runs = sum(counts[c] for c in FAILED_CLASSES)
    failed = failed_runs + (sum(xc_counts.values()) if args.strict else 0)
    runs = len(jobs)
    passed = runs - failed_runs
    lines = [
        f"fuzz: {'replay ' + args.replay if args.replay else f'seed {args.seed}'}, cases {len(cases)}, runs {runs}, "
        f"backends {','.join(backends)}, wall {wall:.1f} s, time cap {args.time_cap:g} s, mem cap {args.mem_cap_mb} MB, "
        f"--max-time {max_time:g}",
        "classes: " + ", ".join(f"{c} {counts[c]}" for c in ALL_CLASSES),
        "cross-checks: " + ", ".join(f"{k} {xc_counts[k]}" for k in XC_KINDS)
        + f" (contradictions within the first {LOW_MODES} paired modes: {xc_low}); {XC_OTHER_MODEL}: "
        f"{other_model_pairs} pair(s)",
    ]
    if failures:
        lines.append("failures:")
        for cls, c, be, r, p in failures:
            scene_path = p if p else c[3]
            lines.append(f"  {cls}: case {c[0]} ({c[1]}) {be}: {r['message'][:160]}")
            lines.append(f"    {command_line(exe, scene_path, be, c[5].get(be), max_time)}")
    if all_findings:
        lines.append("cross-check findings (first-mode order, worst first):")
        srt = sorted(all_findings, key=lambda t: (t[0]["kind"] != XC_REFUSAL, t[0]["rank"]))
        for f, c, p in srt[:40]:
            lines.append(f"  {f['kind']}: case {c[0]} ({c[1]}; {' | '.join(c[2])[:120]}): {f['message']}")
            lines.append(f"    scene: {p if p else c[3]}")
        if len(srt) > 40:
            lines.append(f"  ... {len(srt) - 40} more in summary.txt of a --keep-findings run / runs.csv")
    lines.append(f"fuzz: {passed} passed, {failed} failed")
    text = "\n".join(lines) + "\n"
    (out / "summary.txt").write_text(text)
    print(text, end="")
    return 1 if failed > 0 else 0


if __name__ == "__main__":
    sys.exit(main())
