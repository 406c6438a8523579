"""The Python API against the command line and the scene schema."""

import json
import subprocess
import threading
import time

import numpy as np
import pytest

import modalbench as mb
from conftest import EXE, SCENES

# Numbers that depend on the clock, not on the model.
TIMING_KEYS = {"timing_s"}


def _strip(doc):
    doc = {k: v for k, v in doc.items() if k not in TIMING_KEYS and k != "scene_file"}
    # The process's peak memory is measured, like the timings: a Python process is not the CLI's;
    # so is the run-time plan (calibrated on the refinement's measured solves) and what is said of
    # a run that outlasts it.
    measured = ("process_peak_resident_bytes", "estimated_time_planned_s")
    if "diagnostics" in doc:
        doc["diagnostics"] = {k: v for k, v in doc["diagnostics"].items() if k not in measured}
    if "warnings" in doc:
        doc["warnings"] = [w for w in doc["warnings"] if "times the estimate" not in w]
    return doc


@pytest.mark.parametrize("path", sorted(SCENES.glob("*.toml")), ids=lambda p: p.stem)
def test_python_equals_the_command_line_json(path):
    scene = mb.load_scene(path)
    for backend in mb.backends():
        cli = subprocess.run([EXE, "solve", str(path), "--backend", backend, "--json"], capture_output=True, text=True)
        assert cli.returncode in (0, 2, 3), cli.stderr
        doc = json.loads(cli.stdout)
        if doc["status"] == "invalid-input":  # raised in Python, with the same message
            with pytest.raises(mb.InputError) as e:
                mb.solve(scene, backend)
            assert str(e.value) == doc["message"]
            continue
        r = mb.solve(scene, backend)
        # Every number bitwise (JSON round-trips doubles exactly), every string and status equal.
        assert _strip(r.as_dict) == _strip(doc), (path.name, backend)
        freqs = [f if f is not None else np.nan for f in doc["frequencies_rad_s"]]
        assert np.array_equal(r.frequencies_rad_s, np.array(freqs, dtype=float), equal_nan=True)


def test_a_scene_from_a_dict_is_the_scene_from_its_file():
    d = {
        "scene": {"name": "dict-beam", "kind": "beam", "physics": "bending", "theory": "euler-bernoulli"},
        "geometry": {"length": 2.0, "width": 0.05, "height": 0.1},
        "material": {"E": 2.0e11, "nu": 0.3, "rho": 7850.0},
        "supports": {"x0": "clamped", "xL": {"translational": float("inf"), "rotational": 0.0}},
        "loads": [{"x": 1.0, "Fz": -1000.0}],
        "request": {"modes": 4, "probes": [1.0, 2.0]},
    }
    s = mb.Scene.from_dict(d)
    r = mb.solve(s, "exact")
    assert r.ok, r.message
    # Clamped-pinned Euler-Bernoulli beam: beta L = 3.9266, 7.0686, 10.2102, 13.3518 (Blevins).
    EI, rhoA, L = 2.0e11 * 0.05 * 0.1**3 / 12, 7850.0 * 0.05 * 0.1, 2.0
    beta_l = np.array([3.92660231, 7.06858275, 10.21017612, 13.35176878])
    assert np.allclose(r.frequencies_rad_s, beta_l**2 * np.sqrt(EI / rhoA) / L**2, rtol=1e-8)


def _bad_pair(tmp_path, mutate):
    base = {
        "scene": {"name": "bad", "kind": "beam", "physics": "bending", "theory": "timoshenko"},
        "geometry": {"length": 1.0, "width": 0.1, "height": 0.1},
        "material": {"E": 2.0e11, "nu": 0.3, "rho": 7850.0},
        "supports": {"x0": "clamped", "xL": "free"},
        "request": {"modes": 3},
    }
    mutate(base)
    path = tmp_path / "bad.toml"
    path.write_text(mb._toml.to_toml(base))
    with pytest.raises(mb.InputError) as from_file:
        mb.load_scene(path)
    with pytest.raises(mb.InputError) as from_dict:
        mb.Scene.from_dict(base, source=str(path))
    return from_file.value, from_dict.value


@pytest.mark.parametrize(
    "mutate, key",
    [
        (lambda d: d["geometry"].update(length=-1.0), "geometry.length"),
        (lambda d: d["material"].update(nu=0.7), "material.nu"),
        (lambda d: d["supports"].update(x0="glued"), "supports.x0"),
        (lambda d: d["request"].update(modes="six"), "request.modes"),
        (lambda d: d["geometry"].update(depth=1.0), "geometry.depth"),
    ],
)
def test_a_bad_dict_gets_the_message_of_the_same_bad_toml(tmp_path, mutate, key):
    f, d = _bad_pair(tmp_path, mutate)
    assert str(f) == str(d)
    assert (f.source, f.key, f.reason) == (d.source, d.key, d.reason)
    assert f.key == key, str(f)
    # And the command line says the same.
    cli = subprocess.run([EXE, "solve", str(tmp_path / "bad.toml")], capture_output=True, text=True)
    assert cli.returncode == 2
    assert str(f) in cli.stderr


def test_invalid_mesh_and_backend_raise_input_error():
    s = mb.load_scene(SCENES / "paper_fixed_beam.toml")
    with pytest.raises(mb.InputError) as e:
        mb.solve(s, "rfem", mesh="ten")
    assert (e.value.source, e.value.key) == ("solve()", "mesh")
    assert "command line" not in str(e.value) and "--mesh" not in str(e.value)
    with pytest.raises(mb.InputError) as e:
        mb.solve(s, "rfem", options={"no_such_option": 1})
    assert (e.value.source, e.value.key) == ("solve()", "options.no_such_option")
    assert "unknown option" in e.value.reason and "command line" not in str(e.value)
    with pytest.raises(mb.InputError, match="backend"):
        mb.solve(s, "no-such-backend")
    with pytest.raises(mb.InputError, match="mass"):
        mb.solve(s, "rfem", mass="heavy")


def _steel_cantilever(name, request):
    """A 1 m steel Euler-Bernoulli cantilever, 0.1 x 0.1 m, with the given request."""
    return mb.Scene.from_dict({
        "scene": {"name": name, "kind": "beam", "physics": "bending", "theory": "euler-bernoulli"},
        "geometry": {"length": 1.0, "width": 0.1, "height": 0.1},
        "material": {"E": 2.1e11, "nu": 0.3, "rho": 7850.0},
        "supports": {"x0": "clamped", "xL": "free"},
        "request": request,
    })


def test_shapes_and_frf_come_as_arrays():
    r = mb.solve(_steel_cantilever("shapes", {
        "modes": 3, "shapes": {"nx": 11},
        "frf": {"excite": 1.0, "observe": 1.0, "omega_min": 10.0, "omega_max": 1000.0, "points": 5}}), "exact")
    assert r.ok, r.message
    w = r.shape("w")
    assert w.shape == (3, 11)
    assert np.all(w[:, 0] == 0.0)  # clamped at x = 0
    assert r.frf_receptance.dtype == complex and r.frf_receptance.shape == (5,)
    # Static tip compliance L^3 / (3 EI) is the receptance's limit at omega -> 0.
    EI = 2.1e11 * 0.1**4 / 12
    assert abs(r.frf_receptance[0].real * 3 * EI - 1) < 1e-3


def test_extrapolated_frequencies_come_as_an_array_within_their_estimate():
    # A cantilever Euler-Bernoulli beam: exact frequencies (beta L)^2 sqrt(EI / (rho A L^4)).
    r = mb.solve(_steel_cantilever("extrapolated", {"modes": 3}), "rfem", mesh="64")
    x = r.extrapolated_frequencies_rad_s
    assert x is not None and x.shape == (3,), r.extrapolation_note
    EI, rhoA = 2.1e11 * 0.1**4 / 12, 7850.0 * 0.01
    beta_l = np.array([1.8751040687119611, 4.6940911329741746, 7.8547574382376126])
    exact = beta_l**2 * np.sqrt(EI / rhoA)
    err = np.abs(x / exact - 1)
    errors = r.as_dict["extrapolated"]["frequency_errors"]
    assert np.all(err <= errors)
    assert np.max(err) < 0.1 * np.max(np.abs(r.frequencies_rad_s / exact - 1))
    assert r.extrapolated_frequency_error == max(errors)


def test_the_gil_is_released_while_a_backend_works():
    s = mb.load_scene(SCENES / "paper_ss_plate.toml")
    ticks = 0
    done = threading.Event()

    def solve():
        mb.solve(s, "rfem", mesh="60x36")
        done.set()

    t = threading.Thread(target=solve)
    t.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    t.join()
    # With the GIL held for the whole solve the main thread could not have run in between.
    assert ticks > 5


# The step-loaded beam of the transient tests: simply supported Euler-Bernoulli, L = 1 m, 0.1 x 0.1 m
# steel, a force F at midspan switched on at t = 0, sampled 100 times over the first period T1.
_STEP_L, _STEP_EI, _STEP_RHOA, _STEP_F = 1.0, 2.1e11 * 0.1**4 / 12, 7850.0 * 0.01, -1000.0
_STEP_T1 = 2 * np.pi / ((np.pi / _STEP_L) ** 2 * np.sqrt(_STEP_EI / _STEP_RHOA))


def _step_beam(probe, tolerance, moments):
    return mb.Scene.from_dict({
        "scene": {"name": "step", "kind": "beam", "physics": "bending", "theory": "euler-bernoulli"},
        "geometry": {"length": _STEP_L, "width": 0.1, "height": 0.1},
        "material": {"E": 2.1e11, "nu": 0.3, "rho": 7850.0},
        "supports": {"x0": "pinned", "xL": "pinned"},
        "loads": [{"x": 0.5, "Fz": _STEP_F}],
        "request": {"probes": [probe], "tolerance": tolerance,
                    "transient": {"duration": _STEP_T1, "step": _STEP_T1 / 100, "load": "step",
                                  "moments": moments}},
    })


def test_a_transient_comes_as_arrays_and_peaks_at_twice_the_statics():
    # Every mode the midspan force excites has omega_n = n^2 omega_1, so the midspan reaches twice
    # F L^3 / (48 EI) at T1 / 2.
    L, EI, F, T1 = _STEP_L, _STEP_EI, _STEP_F, _STEP_T1
    s = _step_beam(0.5, 1e-5, False)
    r = mb.solve(s, "exact")
    assert r.ok, r.message
    w = r.history("w")
    assert w.shape == (1, 101) and r.time_s.shape == (101,)
    twice = 2 * F * L**3 / (48 * EI)
    peak = r.transient["probes"][0]["peak"]
    est = r.transient["error_estimate"]
    assert abs(peak["w"] - twice) <= est * abs(peak["w"])
    assert abs(peak["time_s"] - T1 / 2) <= 1e-6 * T1
    assert abs(w[0, 50] - twice) <= est * abs(twice)  # t = T1 / 2 is on the output grid


def test_a_beam_s_moment_history_doubles_its_static_moment_at_half_the_period():
    # The same beam: each mode's moment is in phase with its deflection, so at T1 / 2 the moment at
    # x = L / 4 is twice the static one, -F x / 2 (sagging positive), within the moments' estimate.
    # (After a suddenly applied point load the moment series converges like 1 / modes in time, at
    # any x: a tolerance of 1e-2 takes a few dozen modes.)
    F = _STEP_F
    s = _step_beam(0.25, 1e-2, True)
    r = mb.solve(s, "exact")
    assert r.ok, r.message
    My = r.history("My")
    assert My.shape == (1, 101)
    est = r.transient["moment_error_estimate"]
    peak = r.transient["probes"][0]["moment_peak"]["My"]
    assert 0 < est <= 1e-2
    assert abs(My[0, 50] - 2 * (-F * 0.25 / 2)) <= est * abs(peak)


def test_a_reduced_model_has_the_static_flexibility_as_its_dc_gain():
    # A simply supported Euler-Bernoulli beam: w(x) under a unit force at a, x <= a:
    # b x (L^2 - b^2 - x^2) / (6 EI L), b = L - a (the outputs lie on that side of the input).
    L, EI = 1.0, 2.1e11 * 0.1**4 / 12
    s = mb.Scene.from_dict({
        "scene": {"name": "rom", "kind": "beam", "physics": "bending", "theory": "euler-bernoulli"},
        "geometry": {"length": L, "width": 0.1, "height": 0.1},
        "material": {"E": 2.1e11, "nu": 0.3, "rho": 7850.0},
        "supports": {"x0": "pinned", "xL": "pinned"},
    })
    m = mb.rom(s, "exact", inputs=[0.7], outputs=[0.2, 0.5], modes=6)
    assert m.ok, m.message
    assert m.A.shape == (12, 12) and m.B.shape == (12, 1) and m.C.shape == (6, 12) and m.D.shape == (6, 1)
    dc = m.D - m.C @ np.linalg.solve(m.A, m.B)
    b = L - 0.7
    for o, x in enumerate([0.2, 0.5]):
        ref = b * x * (L**2 - b**2 - x**2) / (6 * EI * L)
        assert abs(dc[o, 0] / ref - 1) < 1e-10
    with pytest.raises(mb.InputError):
        mb.rom(s, "exact", inputs=[1.5], outputs=[0.5])


def test_a_reduced_model_goes_to_scipy():
    signal = pytest.importorskip("scipy.signal")
    m = mb.rom(mb.load_scene(SCENES / "beam_step_load.toml"), "exact", inputs=[1.0], outputs=[0.5], modes=4)
    sys = m.to_scipy()
    assert isinstance(sys, signal.StateSpace) and sys.A.shape == (8, 8)


def test_a_rotor_s_campbell_diagram_splits_each_frequency_into_backward_and_forward_whirl():
    # The pinned Timoshenko shaft: at rest each bending frequency is a pair; spinning, the backward
    # whirl falls and the forward rises (the section's gyroscopic moment), and the first forward
    # critical speed lies between the first forward whirl at rest and at the highest spin.
    r = mb.solve(mb.load_scene(SCENES / "rotor_timoshenko_shaft.toml"), "exact")
    assert r.ok, r.message
    spins, freqs, growth, whirl = r.whirl()
    assert freqs.shape == (31, 4) and spins[0] == 0.0 and spins[-1] == 3000.0
    assert abs(freqs[0, 1] / freqs[0, 0] - 1) <= 1e-12
    assert all(w[:2] == ["backward", "forward"] for w in whirl[1:])
    assert np.all(np.diff(freqs[:, 0]) < 0) and np.all(np.diff(freqs[:, 1]) > 0)
    assert np.all(growth == 0)
    first = r.campbell["critical_speeds"]["forward"][0]
    assert freqs[0, 1] < first < freqs[-1, 1]
