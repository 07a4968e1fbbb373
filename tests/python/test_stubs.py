# SPDX-License-Identifier: BSD-3-Clause
"""The shipped type stubs (python/camfollower/_core.pyi, generated with pybind11-stubgen) must match
the compiled module: every public class, function and method in one exists in the other."""

import ast
import inspect
from pathlib import Path

import camfollower
from camfollower import _core


def stub_tree():
    stub = Path(camfollower.__file__).with_name("_core.pyi")
    assert stub.exists(), "the package must ship _core.pyi"
    return ast.parse(stub.read_text())


def test_stubs_cover_the_compiled_module_and_nothing_else():
    tree = stub_tree()
    stubbed = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            stubbed[node.name] = {
                n.name for n in node.body if isinstance(n, ast.FunctionDef) and not n.name.startswith("_")
            }
        elif isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
            stubbed[node.name] = set()
        elif isinstance(node, ast.AnnAssign) and not node.target.id.startswith("_"):  # module constants
            stubbed[node.target.id] = set()
    public = {n: obj for n, obj in vars(_core).items() if not n.startswith("_")}
    assert set(stubbed) == set(public)
    for name, obj in public.items():
        if inspect.isclass(obj):
            members = {
                m
                for m in vars(obj)
                if not m.startswith("_") and callable(getattr(obj, m, None)) and not isinstance(vars(obj)[m], property)
            }
            properties = {m for m in vars(obj) if isinstance(vars(obj)[m], property)}
            assert members <= stubbed[name] | properties, name
            assert stubbed[name] <= members | properties, name  # nothing stubbed that is not there
