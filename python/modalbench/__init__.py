"""modalbench from Python: load or build a scene, solve it with any back-end, run studies.

    import modalbench as mb
    scene = mb.load_scene("scenes/paper_fixed_beam.toml")
    r = mb.solve(scene, "rfem", mesh="64")
    print(r.status, r.frequencies_rad_s[:3])

Scenes built from dicts follow the TOML schema (README.md, "Scene format") and are validated by
the same code, with the same messages, as scene files. Errors in the user's input raise
InputError(source, key, reason); a solve that fails its own checks returns a Result whose
`status` says so (the numbers are still there).
"""

import json
import math

import numpy as np

from . import _modalbench
from ._toml import to_toml

__all__ = ["InputError", "Scene", "Result", "ReducedModel", "load_scene", "backends", "solve", "rom", "study"]


class InputError(ValueError):
    """Invalid input: the message names the source (file or dict), the key and the reason."""

    def __init__(self, message, source="", key="", reason=""):
        super().__init__(message)
        self.source = source
        self.key = key
        self.reason = reason


_modalbench._set_input_error(InputError)


class Scene:
    """A validated scene. `toml` is its text (what a study sends to other processes)."""

    def __init__(self, native, toml_text):
        self._native = native
        self.toml = toml_text

    @classmethod
    def from_dict(cls, d, source="<dict>"):
        """A scene from the TOML schema as nested dicts; `source` names it in messages."""
        if not isinstance(d, dict):
            raise InputError(f"{source}: a scene is a dict of tables, not {type(d).__name__}", source, "", "not a dict")
        text = to_toml(d)
        return cls(_modalbench._parse_scene(text, source), text)

    @classmethod
    def from_toml(cls, text, source="<toml>"):
        return cls(_modalbench._parse_scene(text, source), text)

    def __reduce__(self):
        return (Scene.from_toml, (self.toml, self.source))

    name = property(lambda self: self._native.name)
    source = property(lambda self: self._native.source)
    kind = property(lambda self: self._native.kind)
    physics = property(lambda self: self._native.physics)
    theory = property(lambda self: self._native.theory)
    notes = property(lambda self: list(self._native.notes))

    def __repr__(self):
        return f"Scene({self.name!r}, {self.kind} {self.physics}, {self.theory}, from {self.source!r})"


def load_scene(path):
    """Reads and validates a scene file (the checks and messages of the command line)."""
    native = _modalbench._load_scene(str(path))
    with open(path, encoding="utf-8") as f:
        return Scene(native, f.read())


def backends():
    """The back-ends built into this modalbench."""
    return list(_modalbench._backends())


def _num(v):
    return math.nan if v is None else float(v)


class Result:
    """One solve: the command line's JSON document (`as_dict`), with the numbers as NumPy arrays."""

    def __init__(self, doc):
        self.as_dict = doc
        self.status = doc["status"]
        self.message = doc["message"]
        self.backend = doc["backend"]
        self.mesh = doc["mesh"]
        self.method = doc["method"]
        self.unknowns = doc["unknowns"]
        self.threads = doc["threads"]
        self.max_backward_error = _num(doc["max_backward_error"])
        self.frequencies_rad_s = np.array([_num(f) for f in doc["frequencies_rad_s"]], dtype=float)
        self.families = list(doc["mode_families"])
        self.deflections = doc["deflections"]
        self.w = np.array([_num(d["w"]) for d in doc["deflections"]], dtype=float)
        frf = doc.get("frf", [])
        self.frf_omega_rad_s = np.array([s["omega_rad_s"] for s in frf], dtype=float)
        self.frf_receptance = np.array([complex(s["re"], s["im"]) for s in frf], dtype=complex)
        self.mode_shapes = doc.get("mode_shapes")
        self.timing_s = doc["timing_s"]
        # Each quantity's step (modes, shapes, statics, frf, campbell) with its own status and message.
        self.steps = doc.get("steps", [])
        self.diagnostics = doc["diagnostics"]
        self.warnings = doc["warnings"]
        # Richardson values from the error estimate's meshes (None where not made: see as_dict).
        x = doc.get("extrapolated") or {}
        self.extrapolation_note = x.get("note", "")
        self.extrapolated_frequencies_rad_s = (
            np.array([_num(f) for f in x["frequencies_rad_s"]], dtype=float) if x.get("frequencies_rad_s") else None)
        self.extrapolated_frequency_error = _num(x.get("frequency_error"))
        # Which values answer ("mesh" or "extrapolated", per quantity): on the default path the
        # extrapolated ones where their estimate meets the tolerance and the mesh's does not; the
        # mesh's own are then mesh_frequencies_rad_s (else None).
        self.values = doc.get("values", {"frequencies": "mesh", "deflections": "mesh"})
        self.mesh_frequencies_rad_s = (
            np.array([_num(f) for f in x["mesh_frequencies_rad_s"]], dtype=float)
            if x.get("mesh_frequencies_rad_s") else None)
        # The time history of [request.transient] (None where not asked: see as_dict["transient"]).
        tr = doc.get("transient")
        self.transient = tr
        self.time_s = np.array(tr["time_s"], dtype=float) if tr else None
        # A rotor's Campbell diagram ([rotor]; None where not asked or not computed: see as_dict).
        self.campbell = doc.get("campbell")

    @property
    def ok(self):
        return self.status == "success"

    def shape(self, component="w"):
        """Mode shapes of one component as an array [mode, point] (None without shapes)."""
        if not self.mode_shapes:
            return None
        return np.array(self.mode_shapes[component], dtype=float)

    def whirl(self):
        """The Campbell diagram as arrays: spins [spin], frequencies and growth rates [spin, root]
        (rad/s, 1/s) and the whirl senses [spin][root] (None without one)."""
        if not self.campbell or not self.campbell["points"]:
            return None
        pts = self.campbell["points"]
        return (np.array([p["spin_rad_s"] for p in pts], dtype=float),
                np.array([[_num(f) for f in p["frequencies_rad_s"]] for p in pts], dtype=float),
                np.array([[_num(g) for g in p["growth_rate_1_s"]] for p in pts], dtype=float),
                [list(p["whirl"]) for p in pts])

    def history(self, component="w"):
        """The transient's histories of one component as an array [probe, time] (None without one)."""
        if not self.transient:
            return None
        return np.array([[_num(v) for v in p[component]] for p in self.transient["probes"]], dtype=float)

    def __repr__(self):
        return f"Result({self.backend} {self.mesh}: {self.status}, {len(self.frequencies_rad_s)} frequencies)"


def solve(scene, backend, mesh=None, mass="consistent", options=None):
    """Solves `scene` with `backend` (mesh spec such as "64" or "100x60"; None: the back-end's
    default). `options`: the back-end's options as a dict (see `modalbench options NAME`).
    Invalid input raises InputError; every other outcome is a Result with its status."""
    if not isinstance(scene, Scene):
        raise TypeError("solve() takes a modalbench.Scene (load_scene or Scene.from_dict)")
    opts = [(str(k), _option_text(v)) for k, v in (options or {}).items()]
    text = _modalbench._solve(scene._native, str(backend), "" if mesh is None else str(mesh), str(mass), opts)
    doc = json.loads(text)
    if doc["status"] == "invalid-input":
        raise _input_error(doc["message"], scene.source)
    return Result(doc)


def _input_error(message, source):
    """The InputError of a solve's invalid-input message "SOURCE: KEY: reason", SOURCE being this
    call ("solve()": its arguments) or the scene's file (its [backend.NAME] table)."""
    for origin in ("solve()", source):
        prefix = f"{origin}: "
        if origin and message.startswith(prefix):
            key, _, reason = message[len(prefix):].partition(": ")
            return InputError(message, origin, key, reason)
    return InputError(message, source, "", message)


def _option_text(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v)


from .study import study  # noqa: E402  (needs the names above)


class ReducedModel:
    """A reduced-order state-space model (`rom`): A, B, C, D as NumPy arrays, with the labels and
    units of its states, inputs and outputs, and its H-infinity check (`as_dict["check"]`)."""

    def __init__(self, doc):
        self.as_dict = doc
        self.status = doc["status"]
        self.message = doc["message"]
        for k in "ABCD":
            rows = doc[k]
            setattr(self, k, np.array(rows, dtype=float) if rows else np.zeros((0, 0)))
        self.states, self.inputs, self.outputs = doc["states"], doc["inputs"], doc["outputs"]
        self.omega_rad_s = np.array(doc["omega_rad_s"], dtype=float)
        self.hinf_error = _num(doc["check"]["hinf_error_m_per_n"])
        self.note = doc["note"]

    @property
    def ok(self):
        return self.status == "success"

    def to_scipy(self):
        """scipy.signal.StateSpace(A, B, C, D) (SciPy needed)."""
        from scipy import signal
        return signal.StateSpace(self.A, self.B, self.C, self.D)

    def __repr__(self):
        return f"ReducedModel({len(self.states)} states, {len(self.inputs)} inputs, {len(self.outputs)} outputs: {self.status})"


def _point(p, scene, what):
    if isinstance(p, (int, float)):
        return (float(p), 0.0)
    p = tuple(float(v) for v in p)
    if len(p) == 1:
        return (p[0], 0.0)
    if len(p) != 2:
        raise _input_error(f"rom(): {what}: a point is x (beam) or (x, y) (plate), got {p}", scene.source)
    return p


def rom(scene, backend, inputs, outputs, modes=12, mesh=None, zeta=0.0, static_correction=True):
    """The reduced-order state-space model of `scene` (as `modalbench rom`): unit forces Fz at
    `inputs`, w, velocity and acceleration at `outputs` (points: x, or (x, y) on a plate), `modes`
    modes of `backend` on `mesh` (None: its default, refined to the scene's tolerance)."""
    if not isinstance(scene, Scene):
        raise TypeError("rom() takes a modalbench.Scene (load_scene or Scene.from_dict)")
    ins = [_point(p, scene, "inputs") for p in inputs]
    outs = [_point(p, scene, "outputs") for p in outputs]
    text = _modalbench._rom(scene._native, str(backend), "" if mesh is None else str(mesh), ins, outs, int(modes),
                            float(zeta), bool(static_correction))
    return ReducedModel(json.loads(text))
