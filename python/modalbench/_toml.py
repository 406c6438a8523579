"""Nested dicts as TOML text (the scene schema), so that a dict goes through the same parser and
validation as a file."""

import json
import math
import re

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k):
    k = str(k)
    return k if _BARE.match(k) else json.dumps(k)


def _value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if hasattr(v, "item"):  # a NumPy scalar
        return _value(v.item())
    raise TypeError(f"cannot write a {type(v).__name__} into a scene")


def to_toml(d):
    """Top-level dicts become tables, lists of dicts arrays of tables, the rest plain keys."""
    plain, tables, arrays = [], [], []
    for k, v in d.items():
        if isinstance(v, dict):
            tables.append((k, v))
        elif isinstance(v, (list, tuple)) and v and all(isinstance(x, dict) for x in v):
            arrays.append((k, v))
        else:
            plain.append(f"{_key(k)} = {_value(v)}")
    out = plain[:]
    for k, t in tables:
        out.append(f"[{_key(k)}]")
        out.extend(f"{_key(kk)} = {_value(vv)}" for kk, vv in t.items())
    for k, items in arrays:
        for t in items:
            out.append(f"[[{_key(k)}]]")
            out.extend(f"{_key(kk)} = {_value(vv)}" for kk, vv in t.items())
    return "\n".join(out) + "\n"
