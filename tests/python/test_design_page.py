# SPDX-License-Identifier: BSD-3-Clause
"""The design page (camfollower.design) in a real browser: headless Chromium from Debian, driven by
Selenium. What it draws is checked against the library's own numbers for the same design; errors
must appear at the field that caused them; a saved config must load as the same mechanism.

Without Chromium, ChromeDriver or Selenium the browser tests are skipped, unless
CAMFOLLOWER_REQUIRE_BROWSER=1 (scripts/test.sh sets it: the set-up installs them, so CI runs them).
"""

from __future__ import annotations

import copy
import math
import os
import shutil
import threading
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("dash", reason="the design page needs the 'design' extra (dash)")

from camfollower import _core  # noqa: E402
from camfollower.config import config_from_dict, load_config  # noqa: E402
from camfollower.design import document as D  # noqa: E402
from camfollower.design import testing as T  # noqa: E402
from camfollower.design import views as V  # noqa: E402
from camfollower.design.app import DesignApp  # noqa: E402

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
ARTIFACTS = Path(os.environ.get("CAMFOLLOWER_TEST_ARTIFACTS", Path(__file__).resolve().parents[2] / "test-artifacts"))


def _browser_or_skip():
    why = T.browser_missing()
    if why:
        if os.environ.get("CAMFOLLOWER_REQUIRE_BROWSER") == "1":
            pytest.fail(f"the browser test must run here: {why}")
        pytest.skip(why)
    return T.chromium()


@pytest.fixture
def folder(tmp_path):
    shutil.copy(EXAMPLES / "translating_roller.toml", tmp_path / "cam.toml")
    return tmp_path


@pytest.fixture
def browser():
    b = _browser_or_skip()
    yield b
    b.quit()


def _same(drawn, truth, digits=1e-6):
    """The page draws numbers to 7 significant digits of each curve's peak (figures.DIGITS)."""
    truth = np.asarray(truth, float)
    assert drawn.shape == truth.shape
    assert np.max(np.abs(drawn - truth)) <= digits * np.max(np.abs(truth)), np.max(np.abs(drawn - truth))


def _lift_mm(program, theta):
    return 1e3 * np.asarray(program.evaluate(theta)["h"])


def _trace(browser, graph, name):
    for t in T.figure_data(browser, graph):
        if t["name"] == name:
            return np.asarray([np.nan if v is None else v for v in t["y"]], float), np.asarray(t["x"], float)
    raise AssertionError(f"{graph} has no trace {name!r}")


def _error_text(browser, path):
    return T.element(browser, T.field_id(path, "error")).text


def _wait_background(browser, timeout=240):
    T.wait(lambda: "..." not in T.element(browser, "bg-status").text, timeout, "the background work")


def test_page_edits_and_draws_the_librarys_numbers(folder, browser):
    """Load, change a lift and the speed, compare every drawn curve with the library, provoke an
    undercut, save, reload."""
    with T.running_page(str(folder / "cam.toml"), root=str(folder)) as (page, url):
        T.open_page(browser, url)
        expected = copy.deepcopy(load_config(folder / "cam.toml").data)

        # 1. A segment's lift: 12 -> 15 mm (the dwell after it keeps the new level).
        T.edit(browser, "program.feed.segments[1].h", "15 mm")
        expected = D.set_value(expected, "program.feed.segments[1].h", "15 mm")
        assert expected["program"]["feed"]["segments"][2]["h"] == "15 mm"
        # 2. The speed: 600 -> 750 rpm.
        T.edit(browser, "camshaft.speed", "750")
        expected = D.set_value(expected, "camshaft.speed", "750")
        case = config_from_dict(expected, str(folder))
        c = case.builder.contacts[0]
        theta = np.linspace(0.0, 2.0 * math.pi, V.ANGLES)

        lift, x = _trace(browser, "fig-svaj", "lift")
        np.testing.assert_allclose(x, np.degrees(theta), rtol=0, atol=1e-9)
        _same(lift, _lift_mm(c["program"], theta))
        assert lift.max() == pytest.approx(15.0, abs=1e-6)
        omega = 750 * math.pi / 30
        velocity, _ = _trace(browser, "fig-svaj", "velocity")
        _same(velocity, omega * np.asarray(c["program"].evaluate(theta)["dh"]))
        # The pressure angle against the follower's own profile (an independent call of the library).
        alpha, _ = _trace(browser, "fig-geometry", "pressure angle")
        _same(alpha, np.degrees(c["follower"].profile(c["program"], theta)["pressure_angle"]))

        # The response once refined, against a fresh steady state of the same design at that accuracy.
        _wait_background(browser)
        fresh = V.response(case, accuracy=V.REFINED_ACCURACY)
        drawn_force, force_x = _trace(browser, "fig-response", "contact force")
        _same(force_x, fresh["theta_deg"])
        _same(drawn_force, fresh["force"], 2e-6)  # the drawing's digits and the shooting's tolerance
        rigid, _ = _trace(browser, "fig-response", "rigid ω²h″")
        # At the drawn angles (7 digits of 360 deg): the acceleration moves by its slope times 4e-5 deg.
        _same(rigid, omega**2 * np.asarray(c["program"].evaluate(np.radians(force_x))["d2h"]), 1e-5)
        margin = next(t for t in T.figure_data(browser, "fig-margin") if t["name"] == "min contact force")
        assert len(margin["x"]) == 11 and min(margin["x"]) == pytest.approx(375.0)

        # 3. An undercut: a 30 mm roller on the 40 mm base circle with the rise squeezed into 40 deg.
        T.edit(browser, "program.feed.segments[1].end", "80 deg")
        broken = D.set_value(
            D.set_value(expected, "program.feed.segments[1].end", "80 deg"),
            "contact[0].follower.roller_radius",
            "30 mm",
        )
        box = T.element(browser, T.field_id("contact[0].follower.roller_radius"))
        from selenium.webdriver.common.keys import Keys

        box.send_keys(Keys.CONTROL, "a")
        box.send_keys("30 mm", Keys.ENTER)
        message = T.wait(lambda: _error_text(browser, "contact[0].follower.roller_radius"), 30, "the undercut message")
        with pytest.raises(ValueError) as library:
            config_from_dict(broken, str(folder))
        assert "undercuts" in message and message in str(library.value)
        assert "not updated" in T.element(browser, "status").text
        # Put it right: the message goes.
        T.edit(browser, "contact[0].follower.roller_radius", "10 mm")
        assert _error_text(browser, "contact[0].follower.roller_radius") == ""
        T.edit(browser, "program.feed.segments[1].end", "130 deg")
        expected = D.set_value(broken, "contact[0].follower.roller_radius", "10 mm")
        expected = D.set_value(expected, "program.feed.segments[1].end", "130 deg")

        # 4. Save, then load the file: the same mechanism as the edits describe.
        name = T.element(browser, "config-name")
        name.send_keys(Keys.CONTROL, "a")
        name.send_keys("saved.toml")
        T.element(browser, "save").click()
        T.wait(lambda: "saved" in T.element(browser, "file-message").text, 30, "the save")
        saved = load_config(folder / "saved.toml")
        assert saved.data == config_from_dict(expected, str(folder)).data
        a = V.response(saved, steps_per_revolution=1024)
        b = V.response(config_from_dict(expected, str(folder)), steps_per_revolution=1024)
        np.testing.assert_array_equal(a["force"], b["force"])
        # Reload it in the page: the fields show the saved values.
        T.element(browser, "open").click()
        T.wait(lambda: "opened" in T.element(browser, "file-message").text, 30, "the reload")
        T.wait(
            lambda: T.element(browser, T.field_id("camshaft.speed")).get_attribute("value") == "750",
            30,
            "the reloaded speed",
        )
        T.wait(
            lambda: (
                T.element(browser, T.field_id("contact[0].follower.roller_radius")).get_attribute("value") == "10 mm"
            ),
            30,
            "the reloaded roller",
        )
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        _wait_background(browser)
        browser.save_screenshot(str(ARTIFACTS / "design_page.png"))
        # Offline: everything the page loaded (scripts, styles, Plotly.js) came from this server.
        loaded = browser.execute_script("return performance.getEntriesByType('resource').map(e => e.name);")
        assert loaded and all(u.startswith(f"http://127.0.0.1:{page.port}/") for u in loaded), loaded
        assert any("plotly" in u for u in loaded)


def test_bad_values_are_shown_at_their_field(folder, browser):
    with T.running_page(str(folder / "cam.toml"), root=str(folder)) as (page, url):
        T.open_page(browser, url)
        from selenium.webdriver.common.keys import Keys

        for path, text, words, good in (
            ("dof[0].mass", "heavy", "is not a number", "0.25 kg"),
            ("camshaft.speed", "-5", "must be in", "600"),
            ("spring[1].stiffness", "8 N/kg", "unit", "8 N/mm"),
        ):
            box = T.element(browser, T.field_id(path))
            box.send_keys(Keys.CONTROL, "a")
            box.send_keys(text, Keys.ENTER)
            message = T.wait(lambda: _error_text(browser, path), 30, f"the message at {path}")
            assert words in message
            T.edit(browser, path, good)
            assert _error_text(browser, path) == ""
        assert not [e for e in browser.get_log("browser") if e["level"] == "SEVERE" and "favicon" not in e["message"]]


# ---------------------------------------------------------------------------------------------------
# Safety and bad input, without a browser


def _client(page, port=8123):
    page.port = port
    return page.app.server.test_client()


def test_requests_need_the_token_this_host_and_this_origin(folder):
    page = DesignApp(str(folder / "cam.toml"), root=str(folder))
    client = _client(page)
    host = {"Host": "127.0.0.1:8123"}
    assert client.get("/", headers=host).status_code == 403  # no token
    assert client.get("/?token=wrong", headers=host).status_code == 403
    r = client.get(f"/?token={page.token}", headers={"Host": "evil.example:8123"})
    assert r.status_code == 403  # DNS rebinding: another host name
    r = client.get(f"/?token={page.token}", headers=host)
    assert r.status_code == 303 and r.headers["Location"].endswith("/")
    assert "HttpOnly" in r.headers["Set-Cookie"] and "SameSite=Strict" in r.headers["Set-Cookie"]
    assert client.get("/", headers=host).status_code == 200  # the cookie now
    post = client.post("/_dash-update-component", json={}, headers={**host, "Origin": "http://evil.example"})
    assert post.status_code == 403
    other = page.app.server.test_client()  # another browser: no cookie
    assert other.get("/_dash-layout", headers=host).status_code == 403


def test_saving_outside_the_folder_or_over_other_files_is_refused(folder, tmp_path_factory):
    page = DesignApp(str(folder / "cam.toml"), root=str(folder))
    state = copy.deepcopy(page.initial)
    outside = tmp_path_factory.mktemp("outside")
    (folder / "link").symlink_to(outside, target_is_directory=True)
    for name, words in (
        ("../escape.toml", "outside the working folder"),
        (str(outside / "abs.toml"), "outside the working folder"),
        ("link/through.toml", "outside the working folder"),
        ("notes.txt", "must end in .toml"),
        ("", "give a file name"),
    ):
        message = _file_action(page, "save", name, state)
        assert message.startswith("not done") and words in message, (name, message)
    assert not list(outside.iterdir())
    (folder / "other.toml").write_text("# someone else's\n")
    assert "not the config this page opened" in _file_action(page, "save", "other.toml", state)
    assert (folder / "other.toml").read_text() == "# someone else's\n"
    # Its own config, changed on disk since it was loaded (another tab saved it): refused.
    original = (folder / "cam.toml").read_text()
    (folder / "cam.toml").write_text(original + "\n# edited elsewhere\n")
    assert "changed on disk" in _file_action(page, "save", "cam.toml", state)
    assert (folder / "cam.toml").read_text().endswith("# edited elsewhere\n")
    # Unchanged: saved over (the page's own file), and it loads.
    (folder / "cam.toml").write_text(original)
    assert _file_action(page, "save", "cam.toml", state).startswith("saved")
    assert load_config(folder / "cam.toml").data == load_config(EXAMPLES / "translating_roller.toml").data


def _file_action(page, action, name, state):
    """DesignApp.file_action outside a request (its set_props calls need Dash's context: stubbed)."""
    import dash

    saved = dash.set_props
    dash.set_props = lambda *a, **k: None
    try:
        return page.file_action(action, name, "cam", state)
    finally:
        dash.set_props = saved


def test_a_config_that_does_not_load(folder, capsys):
    bad = folder / "bad.toml"
    bad.write_text('[camshaft]\nspeed = "fast"\n')
    with pytest.raises(ValueError, match=r"bad.toml:2: camshaft.speed"):
        DesignApp(str(bad), root=str(folder))
    from camfollower import cli

    assert cli.main(["design", str(bad), "--no-browser"]) == 1
    assert "camshaft.speed" in capsys.readouterr().err
    page = DesignApp(str(folder / "cam.toml"), root=str(folder))
    message = _file_action(page, "open", "bad.toml", page.initial)
    assert message.startswith("not done") and "camshaft.speed" in message
    assert cli.main(["design", "--port", "70000"]) == 2


def test_two_tabs_edit_two_designs(folder):
    """Two tabs editing at once: each gets its own design's figures (the server keeps no shared
    document), and the background work of one does not end up in the other."""
    page = DesignApp(str(folder / "cam.toml"), root=str(folder))
    import dash

    dash.set_props, saved = (lambda *a, **k: None), dash.set_props
    try:
        ids = page.initial["paths"]
        results = {}

        def tab(name, lift):
            state = copy.deepcopy(page.initial)
            values = dict(state["shown"], **{"program.feed.segments[1].h": lift})
            out = page.edit(
                state, values, {"type": "field", "path": "program.feed.segments[1].h"}, "cam", 0.0, name, ids
            )
            results[name] = out

        threads = [threading.Thread(target=tab, args=(n, h)) for n, h in (("a", "11 mm"), ("b", "13 mm"))]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        dash.set_props = saved
    for name, lift in (("a", 11.0), ("b", 13.0)):
        state, errors, svaj = results[name][0], results[name][1], results[name][2]
        assert not any(errors)
        assert state["data"]["program"]["feed"]["segments"][1]["h"] == f"{lift:g} mm"
        assert max(svaj["data"][0]["y"]) == pytest.approx(lift, abs=1e-9)
    for name in ("a", "b"):
        page.jobs.cancel(name)


def test_document_round_trip_and_field_paths():
    """The page's TOML writer: every example config written back reads as the same dict."""
    from camfollower.design import toml_text

    for path in sorted(EXAMPLES.glob("*.toml")):
        data = load_config(path).data
        again = _core._parse_toml(toml_text.dumps(data).encode(), str(path))
        assert again == data, path.name
    assert D.split_path("contact[0].follower.pivot[1]") == ["contact", 0, "follower", "pivot", 1]
    paths = ["contact[0].follower.base_radius", "contact[0].follower.roller_radius", "camshaft.speed"]
    assert D.field_of_message("<dict>: contact[0]: ... must exceed roller_radius = 0.02 m", paths) == paths[1]
    assert D.field_of_message("<dict>: camshaft.speed: must be in ...", paths) == paths[2]
    assert (
        D.field_of_message("<dict>: contact[0]: the pressure angle reaches 90.2 deg at theta = 3 deg", paths)
        == paths[0]
    )
    segments = ["program.feed.segments[0].end", "program.feed.segments[1].end", "program.feed.segments[1].h"]
    message = (
        "<dict>: program.feed.segments: segments[1] spans -0.52 rad (-30 deg): span ... must be at least 1e-06 rad"
    )
    assert D.field_of_message(message, segments) == segments[1]


def test_law_and_emptied_fields_never_leave_the_design_stuck():
    """A dwell made a rise gets a lift to edit, a rise made a dwell takes its dwells along, and a key
    without a default cannot be emptied: each step builds, or is refused without changing the design."""
    data = load_config(EXAMPLES / "translating_roller.toml").data
    a = D.set_value(data, "program.feed.segments[0].law", "cycloidal")
    assert a["program"]["feed"]["segments"][0]["h"] == 0  # its start level: a lift to type, not a gap
    config_from_dict(a, str(EXAMPLES))
    b = D.set_value(data, "program.feed.segments[1].law", "dwell")
    assert "h" not in b["program"]["feed"]["segments"][1]
    assert b["program"]["feed"]["segments"][2]["h"] == 0  # the dwell after it, at the new level
    config_from_dict(b, str(EXAMPLES))
    c = D.set_value(
        D.set_value(b, "program.feed.segments[1].law", "modified_sine"), "program.feed.segments[1].h", "12 mm"
    )
    assert config_from_dict(c, str(EXAMPLES)).builder.contacts[0]["program"].max_lift() == pytest.approx(0.012)
    with pytest.raises(ValueError, match=r"segments\[1\]\.h: give a value"):
        D.set_value(data, "program.feed.segments[1].h", "")
    assert "preload" not in D.set_value(data, "spring[1].preload", "")["spring"][1]  # optional: its default


def test_a_grooved_cam_draws_both_flanks_and_a_config_without_contact_is_refused(folder):
    case = load_config(EXAMPLES / "grooved_cam.toml")
    r = V.response(case, steps_per_revolution=2048)
    assert r["outer_force"] is not None and np.max(r["outer_force"]) > 0  # the outer flank carries load
    # The roller is free only where it touches neither flank: never where either carries load, and on
    # less of the revolution than the lifting flank alone is unloaded.
    assert not np.any(r["lost"] & ((r["force"] > 0) | (r["outer_force"] > 0)))
    assert r["lost"].mean() < np.mean(r["force"] <= 0)
    (folder / "no_contact.toml").write_text(
        '[camshaft]\nspeed = 600\n\n[[dof]]\nname = "m"\nmass = 1.0\n\n[[spring]]\nname = "k"\na = "m"\nstiffness = 1000.0\n'
    )
    with pytest.raises(ValueError, match="no cam contact"):
        DesignApp(str(folder / "no_contact.toml"), root=str(folder))
    page = DesignApp(str(folder / "cam.toml"), root=str(folder))
    assert "no cam contact" in _file_action(page, "open", "no_contact.toml", page.initial)


def test_synthesize_then_use_the_lift(folder, browser):
    """The synthesis action: its before/after overlay, then the synthesized lift put in the design and
    drawn (the SVAJ is the new program's, as the library evaluates it)."""
    with T.running_page(str(folder / "cam.toml"), root=str(folder)) as (page, url):
        T.open_page(browser, url)
        T.element(browser, "synthesize").click()
        T.wait(lambda: "synthesis done" in T.element(browser, "bg-status").text, 240, "the synthesis")
        overlay = {t["name"]: t for t in T.figure_data(browser, "fig-synthesis")}
        assert {"before (design's lift)", "after (synthesized)"} <= set(overlay)
        drawn = T.computed(browser)["computed"]
        T.element(browser, "use-synthesis").click()
        T.wait(lambda: T.computed(browser).get("computed", 0) > drawn, 60, "the redraw with the new lift")
        assert "lift table" in T.element(browser, "form").text
        (tab,) = page.jobs._tabs.values()  # the one tab this test opened
        synthesized = tab.memo["synthesized"]
        theta = np.linspace(0.0, 2.0 * math.pi, V.ANGLES)
        lift, _ = _trace(browser, "fig-svaj", "lift")
        _same(lift, _lift_mm(synthesized, theta))


def test_a_profile_check_message_goes_to_the_geometry_it_names():
    """A follower's check (no key path in it) lands at the geometry key it names first."""
    paths = ["camshaft.speed", "preset.parameters.base_radius", "preset.parameters.roller_radius"]
    message = (
        "the cam profile undercuts at theta = 75 deg: ... must exceed roller_radius = 0.03 m (enlarge base_radius)"
    )
    assert D.field_of_message(message, paths) == paths[2]
    assert D.field_of_message("the cam surface has a cusp ... (enlarge base_radius ...)", paths) == paths[1]
