# SPDX-License-Identifier: BSD-3-Clause
"""The README's Python examples run as written (they are documentation users copy)."""

import re
import subprocess
from pathlib import Path

README = Path(__file__).resolve().parents[2] / "README.md"


def test_readme_python_blocks_run(tmp_path, monkeypatch):
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), re.S)
    assert blocks, "the README should show Python usage"
    monkeypatch.chdir(tmp_path)  # the examples write files (cam.csv)
    exec(compile("\n".join(blocks), str(README), "exec"), {})
    assert (tmp_path / "cam.csv").exists()


def test_docstring_examples():
    import doctest

    import camfollower
    import camfollower.reference

    for module in (camfollower, camfollower.reference):
        result = doctest.testmod(module)
        assert result.attempted > 0 and result.failed == 0, module.__name__


def test_setup_refuses_an_unknown_mode_naming_the_modes():
    # scripts/setup.sh: a misspelt mode stops before installing anything.
    for mode in ("tests", "compiler"):
        done = subprocess.run(
            ["bash", str(README.parent / "scripts" / "setup.sh"), mode], capture_output=True, text=True
        )
        assert done.returncode == 2
        assert f"unknown mode '{mode}'" in done.stderr
        assert "study, test or compilers" in done.stderr
