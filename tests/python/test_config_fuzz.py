# SPDX-License-Identifier: BSD-3-Clause
"""A config fuzzer: every example config, mutated line by line (values replaced by hostile ones, lines
dropped or repeated, the text cut short, control characters and invalid UTF-8 inserted), read by the
Python package and by the command line. Oracle: the case builds, or the reader refuses it with a
ValueError (exit code 1 on the command line) whose message names the file, is short and carries no
raw control characters; never a crash, a hang or another exception. Profiles as in
test_properties.py ("ci" by default; ``--hypothesis-profile=long`` for many more)."""

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

hypothesis = pytest.importorskip("hypothesis")
import camfollower as cf  # noqa: E402
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))
# The sanitized build of scripts/test.sh first (the fuzzer then runs under ASan/UBSan), else a Release one.
CLI = next(
    (
        p
        for p in (ROOT / "build-sanitize" / "src" / "camfollower", ROOT / "build" / "src" / "camfollower")
        if p.exists()
    ),
    ROOT / "build-sanitize" / "src" / "camfollower",
)

HOSTILE = [
    "-1",
    "0",
    "1e300",
    "-1e300",
    "1e-320",
    "nan",
    "inf",
    "-inf",
    "2.5",
    "9223372036854775807",
    "-9223372036854775808",
    "true",
    "[]",
    "{}",
    "[1, 2]",
    '"x"',
    '""',
    '"nan"',
    '"1e999 mm"',
    '"10 parsec"',
    '"-3 mm"',
    '"1e308 rpm"',
    '"0 deg"',
    '"\\u0007\\u001b[2J"',
    '"' + "a" * 5000 + '"',
    "xnonex",
    '"none"',
    '"ground"',
    "1979-05-27",
]
ASSIGNMENT = re.compile(r"^(\s*[A-Za-z_][\w.\"-]*\s*=\s*)(.*)$")


def mutate(text: str, op: int, line_pick: int, token: int, cut: float) -> bytes:
    lines = text.splitlines()
    assignments = [i for i, l in enumerate(lines) if ASSIGNMENT.match(l)]
    i = assignments[line_pick % len(assignments)] if assignments else 0
    if op == 0:  # a value replaced by a hostile one
        lines[i] = ASSIGNMENT.sub(lambda m: m.group(1) + HOSTILE[token % len(HOSTILE)], lines[i])
    elif op == 1:  # a line dropped
        del lines[i]
    elif op == 2:  # a key repeated (last must not silently win)
        lines.insert(i + 1, lines[i])
    elif op == 3:  # the text cut short
        return "\n".join(lines)[: int(cut * len(text))].encode()
    elif op == 4:  # a control character or invalid UTF-8 in a line
        raw = "\n".join(lines).encode()
        k = int(cut * len(raw))
        return raw[:k] + [b"\x00", b"\x07", b"\xff\xfe", b"\x1b[31m"][token % 4] + raw[k:]
    elif op == 5:  # a table header repeated
        headers = [j for j, l in enumerate(lines) if l.startswith("[") and not l.startswith("[[")]
        if headers:
            lines.append(lines[headers[line_pick % len(headers)]])
    elif op == 6:  # a byte order mark (what Windows editors write), once or twice
        return b"\xef\xbb\xbf" * (1 + token % 2) + ("\n".join(lines) + "\n").encode()
    elif op == 7:  # a value nested deep: past the reader's 64 levels, or toml++'s 256
        depth = [65, 300, 5000][token % 3]
        lines[i] = ASSIGNMENT.sub(lambda m: m.group(1) + "[" * depth + "1" + "]" * depth, lines[i])
    elif op == 8:  # a key of many dotted parts
        lines.insert(i, ".".join(["k"] * [70, 10_000][token % 2]) + " = 1")
    return ("\n".join(lines) + "\n").encode()


def check_message(message: str, path: Path) -> None:
    assert str(path) in message or path.name in message, message
    assert len(message) < 2000, f"message of {len(message)} characters"
    assert not re.search(r"[\x00-\x08\x0b-\x1f\x7f]", message), repr(message)


mutation = st.tuples(
    st.sampled_from(EXAMPLES), st.integers(0, 8), st.integers(0, 500), st.integers(0, 100), st.floats(0.0, 1.0)
)


@settings(deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(mutation)
def test_mutated_configs_build_or_are_refused_naming_the_file(tmp_path, m):
    example, op, line_pick, token, cut = m
    for data in (example.parent / "data").glob("*") if (example.parent / "data").is_dir() else []:
        (tmp_path / "data").mkdir(exist_ok=True)
        shutil.copy(data, tmp_path / "data" / data.name)
    path = tmp_path / example.name
    path.write_bytes(mutate(example.read_text(), op, line_pick, token, cut))
    try:
        case = cf.load_config(path)
    except (ValueError, RuntimeError) as e:  # bad input, or a mechanism that cannot be solved
        check_message(str(e), path)
        return
    assert case.mechanism.size >= 1


@pytest.mark.skipif(not CLI.exists(), reason="the command line is built by scripts/test.sh (ctest)")
@settings(deadline=None, max_examples=60, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(mutation)
def test_the_command_line_never_crashes_on_mutated_configs(tmp_path, m):
    example, op, line_pick, token, cut = m
    if (example.parent / "data").is_dir():
        shutil.copytree(example.parent / "data", tmp_path / "data", dirs_exist_ok=True)
    path = tmp_path / example.name
    path.write_bytes(mutate(example.read_text(), op, line_pick, token, cut))
    r = subprocess.run(
        [str(CLI), "kinematics", str(path)], capture_output=True, timeout=60, env={**os.environ, "LC_ALL": "C"}
    )
    assert r.returncode in (0, 1), (r.returncode, r.stderr[-2000:])
    if r.returncode == 1:
        check_message(r.stderr.decode("utf-8", "replace").strip(), path)


@pytest.mark.skipif(not CLI.exists(), reason="the command line is built by scripts/test.sh (ctest)")
@settings(deadline=None, max_examples=40, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(mutation)
def test_python_and_the_command_line_give_one_answer(tmp_path, m):
    """One reader: a mutated config that Python refuses, the command line refuses with the same
    message; one Python reads, the command line reads too (a byte order mark, deep nesting)."""
    example, op, line_pick, token, cut = m
    if (example.parent / "data").is_dir():
        shutil.copytree(example.parent / "data", tmp_path / "data", dirs_exist_ok=True)
    path = tmp_path / example.name
    path.write_bytes(mutate(example.read_text(), op, line_pick, token, cut))
    try:
        cf.load_config(path)
        python = None
    except (ValueError, RuntimeError) as e:
        python = str(e)
    r = subprocess.run(
        [str(CLI), "kinematics", str(path)], capture_output=True, timeout=60, env={**os.environ, "LC_ALL": "C"}
    )
    if python is None:
        assert r.returncode == 0, r.stderr[-2000:]
    else:
        assert r.returncode == 1 and r.stderr.decode("utf-8", "replace").strip() == f"camfollower: error: {python}"


# Values a Python dict may hold that a TOML table cannot, or only by a bounded walk.
def _cyclic():
    d = {"a": 1}
    d["self"] = d
    return d


def _laughs():
    d = {"v": 1.0}
    for _ in range(40):
        d = {"a": d, "b": d}
    return d


def _deep(n):
    d = node = {}
    for _ in range(n):
        node["d"] = {}
        node = node["d"]
    return d


HOSTILE_VALUES = [
    _cyclic,
    _laughs,
    lambda: _deep(30_000),
    lambda: _deep(70),
    lambda: [[[]] * 3] * 3,
    lambda: {1: "x"},
    lambda: 2**70,
    lambda: -(2**63),
    lambda: None,
    lambda: b"bytes",
    lambda: {"x"},
    lambda: "\udc80",
    lambda: float("nan"),
    lambda: "\x1b[2J",
    lambda: object(),
]


@settings(deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.sampled_from(EXAMPLES), st.integers(0, 10_000), st.sampled_from(range(len(HOSTILE_VALUES))), st.booleans())
def test_mutated_dicts_build_or_are_refused_naming_the_key(tmp_path, example, pick, hostile, replace):
    """config_from_dict on an example's data with one value replaced (or one key added) by a value
    a TOML table cannot hold: a cycle, 2**40 values by shared sub-dicts, 30,000 levels, a non-string key, an integer beyond 64 bits, a
    lone surrogate, None, bytes, a set. Oracle: the case builds, or a ValueError naming the key path
    under "<dict>", short and printable; never a crash, a hang or another exception."""
    data = cf.load_config(example).data
    slots = []  # (container, key) of every value in the tree

    def walk(node):
        for k, v in node.items() if isinstance(node, dict) else enumerate(node):
            slots.append((node, k))
            if isinstance(v, (dict, list)):
                walk(v)

    walk(data)
    container, key = slots[pick % len(slots)]
    value = HOSTILE_VALUES[hostile]()
    if replace or not isinstance(container, dict):
        container[key] = value
    else:
        container["added"] = value
    try:
        case = cf.config_from_dict(data, base_dir=example.parent)
    except (ValueError, RuntimeError) as e:
        message = str(e)
        assert message.startswith("<dict>"), message
        assert len(message) < 2000 and not re.search(r"[\x00-\x08\x0b-\x1f\x7f]", message), repr(message)
        return
    assert case.mechanism.size >= 1


def test_names_with_control_characters_or_megabytes_are_refused():
    """Found by the fuzzer: a DOF named "\\a\\x1b[2J" was accepted and every later message listing the
    DOFs wrote the terminal escape; names are now 1-200 printable characters, and lists in messages
    are cut at 20 entries."""
    b = cf.MechanismBuilder()
    for bad in ("\x07\x1b[2J", "", "x" * 201):
        with pytest.raises(ValueError, match=r"DOF name must be 1 to 200 printable characters"):
            b.add_dof(bad, 1.0, (0, 1, 0))
    b.add_dof("ok", 1.0, (0, 1, 0))
    with pytest.raises(ValueError, match=r"element name must be 1 to 200 printable"):
        b.add_spring("s\n", "ok", "ground", stiffness=1.0)


def test_unknown_names_in_a_config_list_at_most_twenty_known_ones(tmp_path):
    text = (ROOT / "examples" / "camshaft.toml").read_text().replace('a = "valve1"', 'a = "valve9"', 1)
    assert 'a = "valve9"' in text
    path = tmp_path / "c.toml"
    path.write_text(text)
    with pytest.raises(ValueError) as e:
        cf.load_config(path)
    message = str(e.value)
    assert "unknown DOF 'valve9'" in message and "in all)" in message
    assert message.count(",") <= 21 and len(message) < 1000


@pytest.mark.skipif(not CLI.exists(), reason="the command line is built by scripts/test.sh (ctest)")
def test_kinematics_print_every_contact_when_the_force_closure_check_cannot_run(tmp_path):
    """Found by the test above: a valve spring of 2.5 N/m (meant as N/mm) leaves no static equilibrium
    at some cam angles, so the force-closure check reports no contact; both command lines still print
    every contact's kinematics (the C++ one indexed the empty report and failed)."""
    from camfollower import cli

    text = (ROOT / "examples" / "camshaft.toml").read_text()
    assert text.count('stiffness = "45 N/mm"') == 2
    path = tmp_path / "camshaft.toml"
    path.write_text(text.replace('stiffness = "45 N/mm"', "stiffness = 2.5", 1))
    r = subprocess.run([str(CLI), "kinematics", str(path)], capture_output=True, timeout=60)
    assert r.returncode == 0, r.stderr
    printed = re.findall(r"^contact '([^']+)'", r.stdout.decode(), re.M)
    case = cf.load_config(path)
    assert printed == [c["name"] for c in case.builder.contacts] and len(printed) == 2
    rows = cli.kinematics(str(path))
    assert [row["contact"] for row in rows] == printed
