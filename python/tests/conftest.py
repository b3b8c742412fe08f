"""Shared settings: the command line to compare with (SHADOWREF_CLI, set by ctest; else build/shadowref)
and the repository root as the working directory (scene paths are relative to it)."""
import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(autouse=True)
def _at_root(monkeypatch):
    monkeypatch.chdir(ROOT)


@pytest.fixture
def cli():
    path = os.environ.get("SHADOWREF_CLI", str(ROOT / "build" / "shadowref"))
    if not os.path.exists(path):
        pytest.fail(f"no shadowref command at {path} (set SHADOWREF_CLI)")
    return path
