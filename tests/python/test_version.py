# SPDX-License-Identifier: BSD-3-Clause
"""The version is stated once (pyproject.toml); the package, its metadata and CMake follow it."""

import importlib.metadata
import re
from pathlib import Path

import camfollower as cf
import tomllib

ROOT = Path(__file__).resolve().parents[2]


def test_version_comes_from_pyproject():
    stated = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    assert re.fullmatch(r"\d+\.\d+\.\d+", stated)
    assert cf.__version__ == stated
    assert importlib.metadata.version("camfollower") == stated


def test_no_other_file_states_the_version():
    stated = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    for path in [ROOT / "CMakeLists.txt", *sorted((ROOT / "python" / "camfollower").glob("*.py"))]:
        assert f'"{stated}"' not in path.read_text() and f"VERSION {stated}" not in path.read_text(), path
