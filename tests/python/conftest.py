"""The build under test: PYTHONPATH holds build/python; MODALBENCH_EXE and MODALBENCH_SCENES_DIR
are set by CTest (tests/CMakeLists.txt)."""

import os
import pathlib

import pytest

SCENES = pathlib.Path(os.environ.get("MODALBENCH_SCENES_DIR", pathlib.Path(__file__).parents[2] / "scenes"))
EXE = os.environ.get("MODALBENCH_EXE", "modalbench")


@pytest.fixture
def scenes_dir():
    return SCENES


@pytest.fixture
def exe():
    return EXE
