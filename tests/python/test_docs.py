# SPDX-License-Identifier: BSD-3-Clause
"""The documentation site builds with Sphinx without a single warning (warnings are errors), and it
carries the API reference, the C++ headers and the examples."""

import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("sphinx")
pytest.importorskip("myst_parser")

DOCS = Path(__file__).resolve().parents[2] / "docs"


def test_sphinx_site_builds_without_warnings(tmp_path):
    r = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-E", "-q", "-b", "html", str(DOCS), str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert r.returncode == 0, r.stderr[-5000:]
    api = (tmp_path / "api.html").read_text()
    for name in ("periodic_steady_state", "monte_carlo", "jump_speed", "MechanismBuilder", "run_cases"):
        assert name in api, name
    assert "solver/shooting.hpp" in (tmp_path / "_generated" / "cpp.html").read_text()
    assert "paper_studies.toml" in (tmp_path / "_generated" / "examples.html").read_text()
    for page in ("studies", "camshaft", "benchmarks", "model", "study"):
        assert (tmp_path / f"{page}.html").is_file()
