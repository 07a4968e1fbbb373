# SPDX-License-Identifier: BSD-3-Clause
# Sphinx configuration of the documentation site: the Markdown pages of docs/ (MyST), the Python API
# from the docstrings (autodoc), the C++ headers from their leading comments and the examples, all
# generated here. Built and checked with warnings as errors by tests/python/test_docs.py:
#   .venv/bin/python -m sphinx -W --keep-going -b html docs build-docs
import re
from pathlib import Path

import camfollower

ROOT = Path(__file__).resolve().parents[1]
project = "camfollower"
author = "the camfollower developers"
copyright = "2026, the camfollower developers"
release = version = camfollower.__version__

extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.mathjax"]
source_suffix = {".md": "markdown"}
myst_heading_anchors = 3
exclude_patterns = ["_build"]
autodoc_member_order = "bysource"
autodoc_typehints = "none"
html_theme = "alabaster"
# Links from the pages to repository files outside docs/ (examples/*.toml, README.md) are links for
# readers of the repository; the site lists the examples itself (examples.md).
suppress_warnings = ["myst.xref_missing"]


def _leading_comment(text: str) -> str:
    lines = []
    for line in text.splitlines():
        if line.startswith("// SPDX") or line.startswith("# SPDX"):
            continue
        if line.startswith("//"):
            lines.append(line[2:].strip())
        elif line.startswith("#") and not line.startswith("#pragma") and not line.startswith("#include"):
            lines.append(line[1:].strip())
        else:
            break
    return "\n".join(lines).strip()


def _generate(app):
    out = Path(app.srcdir) / "_generated"
    out.mkdir(exist_ok=True)
    parts = ["# C++ headers\n", "The header-only core, `include/camfollower/`, one header per job; each header's own "
             "description follows (see the headers for the declarations).\n"]
    for folder in sorted((ROOT / "include" / "camfollower").rglob("*.hpp")):
        rel = folder.relative_to(ROOT / "include")
        parts.append(f"## `{rel}`\n\n```text\n{_leading_comment(folder.read_text()) or '(no description)'}\n```\n")
    (out / "cpp.md").write_text("\n".join(parts))
    parts = ["# Examples\n", "Every example runs in the tests. Config files (docs: [config](../config.md), "
             "[studies](../studies.md)) and Python scripts, in full:\n"]
    for f in sorted((ROOT / "examples").glob("*")):
        if f.suffix in (".toml", ".py"):
            lang = "toml" if f.suffix == ".toml" else "python"
            parts.append(f"## `examples/{f.name}`\n\n```{lang}\n{f.read_text().rstrip()}\n```\n")
    (out / "examples.md").write_text("\n".join(parts))


def _plain_bars(app, what, name, obj, options, lines):
    # The docstrings are plain text with ``code``: |x| is an absolute value, not a substitution.
    lines[:] = [re.sub(r"(?<!\\)\|", r"\\|", line) for line in lines]


def setup(app):
    app.connect("builder-inited", _generate)
    app.connect("autodoc-process-docstring", _plain_bars)
