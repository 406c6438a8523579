"""Parameter studies: in this process, in local processes, and on a local Dask cluster."""

import os
import signal
import subprocess
import sys
import time

import pytest

import modalbench as mb
from modalbench.study import TIMING, spec_scenes, study
from conftest import EXE, SCENES


def _sweep():
    """3 lengths x 3 support stiffnesses of the elastic beam, 2 back-ends: 18 runs."""
    base = mb.load_scene(SCENES / "lasecka_elastic_beam.toml")
    import tomllib

    d0 = tomllib.loads(base.toml)
    out = []
    for L in (1.0, 1.5, 2.0):
        for k in (1e4, 1e6, 1e8):
            d = dict(d0)
            d["geometry"] = dict(d0["geometry"], length=L)
            d["supports"] = dict(d0["supports"])
            d["supports"]["x0"] = dict(d0["supports"]["x0"], translational=k)
            d["loads"] = [dict(l, x=min(l["x"], L)) for l in d0.get("loads", [])]
            d["request"] = {"modes": 4, "probes": [0.5 * L]}
            out.append(({"length": L, "k0": k}, mb.Scene.from_dict(d)))
    return out


def _strip(table):
    """The rows without timings, NaN made comparable."""
    def norm(v):
        return "nan" if isinstance(v, float) and v != v else v
    return [{k: norm(v) for k, v in r.items() if k not in TIMING} for r in table]


def test_a_3x3x2_study_has_18_rows_with_its_inputs(tmp_path):
    table = study(_sweep(), ["exact", "difference_eq"], workers=1, out=tmp_path)
    assert len(table) == 18
    assert {(r["length"], r["k0"], r["backend"]) for r in table} == {
        (L, k, b) for L in (1.0, 1.5, 2.0) for k in (1e4, 1e6, 1e8) for b in ("exact", "difference_eq")}
    assert all(r["status"] == "success" for r in table), [r["message"] for r in table]
    # The two models agree (difference_eq at its default mesh: discretization error only).
    by = {(r["length"], r["k0"], r["backend"]): r for r in table}
    for L in (1.0, 1.5, 2.0):
        for k in (1e4, 1e6, 1e8):
            e, d = by[(L, k, "exact")], by[(L, k, "difference_eq")]
            assert abs(d["f1_rad_s"] / e["f1_rad_s"] - 1) < 1e-3
    # Beside the frequencies: w at the probe, the error estimate and the extrapolated values.
    for L in (1.0, 1.5, 2.0):
        for k in (1e4, 1e6, 1e8):
            e, d = by[(L, k, "exact")], by[(L, k, "difference_eq")]
            assert abs(d["w1_m"] / e["w1_m"] - 1) < 1e-3
            assert d["estimate_frequencies"] > 0 and d["estimate_frequencies"] < 1e-3
            # Extrapolated where the back-end made it (NaN: not made on that mesh family).
            if d["xf1_rad_s"] == d["xf1_rad_s"]:
                assert abs(d["xf1_rad_s"] / e["f1_rad_s"] - 1) < 1e-6
    assert any(r["xf1_rad_s"] == r["xf1_rad_s"] for r in table if r["backend"] == "difference_eq")
    lines = (tmp_path / "study.csv").read_text().splitlines()
    assert len(lines) == 19
    assert {"w1_m", "estimate_frequencies", "estimate_deflections", "xf1_rad_s"} <= set(lines[0].split(","))
    # Local processes give the same table (timings aside).
    assert _strip(study(_sweep(), ["exact", "difference_eq"], workers=2)) == _strip(table)


def test_a_study_spec_from_the_command_line(tmp_path):
    spec = tmp_path / "spec.toml"
    spec.write_text(
        f'[study]\nbase = "{SCENES / "lasecka_elastic_beam.toml"}"\nbackends = ["exact"]\n'
        '[parameters]\n"geometry.length" = [4.0, 5.0]\n"material.rho" = { from = 1000.0, to = 8000.0, num = 3 }\n')
    out = tmp_path / "out"
    r = subprocess.run([EXE, "study", str(spec), "--out", str(out), "--workers", "1"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    lines = (out / "study.csv").read_text().splitlines()
    assert len(lines) == 1 + 6
    assert lines[0].startswith("geometry.length,material.rho,")
    bad = tmp_path / "bad.toml"
    bad.write_text('[study]\nbackends = ["exact"]\n')
    r = subprocess.run([EXE, "study", str(bad), "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 2 and "base" in r.stderr


distributed = pytest.importorskip("distributed")


@pytest.fixture
def cluster():
    """A scheduler and two worker processes on the loopback interface only."""
    from distributed import LocalCluster

    c = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None)
    yield c
    c.close()


def test_the_dask_run_equals_the_local_run(cluster):
    local = study(_sweep(), ["exact", "difference_eq"], workers=1)
    remote = study(_sweep(), ["exact", "difference_eq"], scheduler=cluster.scheduler_address)
    assert _strip(remote) == _strip(local)


def test_a_killed_worker_loses_no_result(cluster):
    """A worker is killed while the study runs; the scheduler reruns its tasks elsewhere."""
    from distributed import Client

    with Client(cluster.scheduler_address) as client:
        pids = list(client.run(os.getpid).values())
    scenes = _sweep() * 4  # 36 scenes x 1 back-end
    import threading

    def kill_soon():
        time.sleep(0.5)
        os.kill(pids[0], signal.SIGKILL)

    killer = threading.Thread(target=kill_soon)
    killer.start()
    # rfem at a fine mesh keeps each task busy long enough for the kill to land mid-study.
    table = study(scenes, ["rfem"], meshes={"rfem": ["20000"]}, scheduler=cluster.scheduler_address)
    killer.join()
    assert len(table) == 36
    assert all(r["status"] == "success" for r in table), {r["message"] for r in table}
    with Client(cluster.scheduler_address) as client:
        alive = list(client.run(os.getpid).values())
    assert pids[0] not in alive  # the kill happened
