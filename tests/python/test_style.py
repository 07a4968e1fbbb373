# SPDX-License-Identifier: BSD-3-Clause
"""The repository's own style: C++ as .clang-format says (clang-format 14, Debian's), Python as ruff's
settings in pyproject.toml say. A failure lists the files; `git ls-files '*.hpp' '*.cpp' | xargs
clang-format -i` and `ruff format python tests/python bench && ruff check --fix ...` repair them."""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PYTHON_TREES = ["python", "tests/python", "bench", "examples"]


def tracked(*patterns):
    if not (ROOT / ".git").exists():
        pytest.skip("not a git checkout (the style test reads the tracked files)")
    out = subprocess.run(["git", "ls-files", *patterns], cwd=ROOT, capture_output=True, text=True, check=True)
    return out.stdout.split()


def test_cpp_follows_clang_format():
    tool = shutil.which("clang-format")
    assert tool, "clang-format is missing: scripts/setup.sh installs it (apt install clang-format)"
    files = tracked("*.hpp", "*.cpp")
    assert len(files) > 50
    r = subprocess.run([tool, "--dry-run", "--Werror", *files], cwd=ROOT, capture_output=True, text=True)
    unformatted = sorted({line.split(":")[0] for line in r.stderr.splitlines() if ": error:" in line})
    assert r.returncode == 0, f"not clang-formatted: {unformatted or r.stderr[:2000]}"


@pytest.mark.parametrize("command", [["format", "--check"], ["check"]])
def test_python_follows_ruff(command):
    trees = [t for t in PYTHON_TREES if (ROOT / t).exists()]
    r = subprocess.run([sys.executable, "-m", "ruff", *command, *trees], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-1000:]
