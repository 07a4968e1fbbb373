# SPDX-License-Identifier: BSD-3-Clause
"""Driving the design page from a program: the page on a background thread and headless Chromium
(Debian's ``chromium`` and ``chromium-driver``, through Selenium). The tests and
``bench/design_latency.py`` use it; so can a user's own checks of a design.

>>> with running_page("examples/translating_roller.toml") as (page, url):   # doctest: +SKIP
...     browser = chromium()
...     browser.get(url)
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import threading
import time
from typing import Any, Dict, Iterator, List, Optional, Tuple

CHROMIUM = ("/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome")
CHROMEDRIVER = ("/usr/bin/chromedriver",)


def _first(paths, name: str) -> Optional[str]:
    for p in paths:
        if os.path.exists(p):
            return p
    return shutil.which(name)


def browser_missing() -> Optional[str]:
    """Why no headless browser can run here (None: it can)."""
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "selenium is not installed (pip install selenium)"
    if not _first(CHROMIUM, "chromium"):
        return "Chromium is not installed (Debian: apt-get install chromium chromium-driver)"
    if not _first(CHROMEDRIVER, "chromedriver"):
        return "ChromeDriver is not installed (Debian: apt-get install chromium-driver)"
    return None


def chromium(width: int = 1600, height: int = 2300):
    """Headless Chromium driven by Selenium (window `width` x `height` pixels)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service

    options = Options()
    options.binary_location = _first(CHROMIUM, "chromium")
    for arg in (
        "--headless=new",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-dev-shm-usage",
        f"--window-size={width},{height}",
    ):
        options.add_argument(arg)
    return webdriver.Chrome(service=Service(_first(CHROMEDRIVER, "chromedriver")), options=options)


@contextlib.contextmanager
def running_page(config: Optional[str] = None, *, root: str = ".") -> Iterator[Tuple[Any, str]]:
    """The page serving `config` from the working folder `root` on a free port: (DesignApp, url with
    the token); stopped on exit."""
    from werkzeug.serving import make_server

    from .app import DesignApp

    page = DesignApp(config, root=root)
    server = make_server("127.0.0.1", 0, page.app.server, threaded=True)
    page.port = server.server_port
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield page, f"http://127.0.0.1:{page.port}/?token={page.token}"
    finally:
        server.shutdown()
        server.server_close()
        page.jobs.stop()


def field_id(path: str, kind: str = "field") -> str:
    """The DOM id Dash gives a pattern-matching component (its id dict as JSON, keys sorted)."""
    return json.dumps({"path": path, "type": kind}, separators=(",", ":"), sort_keys=True)


def element(browser, dom_id: str):
    from selenium.webdriver.common.by import By

    return browser.find_element(By.XPATH, f"//*[@id='{dom_id}']")


def choose(browser, path: str, value: str, timeout: float = 30.0) -> None:
    """Pick `value` in the list of the field at `path` (a law, a follower type); wait until the page
    answered (a redraw, or a message)."""
    from selenium.webdriver.common.by import By

    before = computed(browser).get("computed", 0)
    status = element(browser, "status").text
    element(browser, field_id(path)).click()
    options = wait(lambda: browser.find_elements(By.CSS_SELECTOR, "label.dash-dropdown-option"), timeout, "the list")
    hit = [o for o in options if o.text.strip() == value]
    if not hit:
        raise ValueError(f"{path}: no option {value!r} in {[o.text for o in options]}")
    browser.execute_script("arguments[0].click();", hit[0])
    wait(
        lambda: computed(browser).get("computed", 0) > before or element(browser, "status").text != status,
        timeout,
        f"the page's answer to {path} = {value!r}",
    )


def figure_data(browser, graph: str) -> List[Dict[str, Any]]:
    """The traces a graph on the page draws (name, x, y), as Plotly holds them (an evenly spaced x sent
    as x0 and dx made an array)."""
    return browser.execute_script(
        "const gd = document.querySelector('#' + arguments[0] + ' .js-plotly-plot');"
        "return gd && gd.data ? gd.data.map(t => ({name: t.name, y: t.y,"
        "  x: t.x || (t.y ? t.y.map((_, i) => t.x0 + t.dx * i) : null)})) : null;",
        graph,
    )


def computed(browser) -> Dict[str, Any]:
    """The last edit's server timings and count (``computed``: how many designs this tab drew)."""
    text = browser.execute_script("const e = document.getElementById('computed'); return e ? e.textContent : '';")
    return json.loads(text) if text else {}


def wait(predicate, timeout: float = 30.0, what: str = "the page") -> Any:
    end = time.monotonic() + timeout
    last = None
    while time.monotonic() < end:
        try:
            last = predicate()
            if last:
                return last
        except Exception as e:  # an element not there yet
            last = e
        time.sleep(0.05)
    raise TimeoutError(f"{what} did not happen within {timeout:g} s (last: {last!r})")


def open_page(browser, url: str, timeout: float = 60.0) -> None:
    """Load the page and wait until its first design is drawn in all four figures (Dash loads the
    plotting code after the page: a figure's element is replaced once)."""
    browser.get(url)
    wait(lambda: computed(browser).get("computed", 0) >= 1, timeout, "the first drawing")
    wait(
        lambda: browser.execute_script(
            "return ['fig-svaj','fig-profile','fig-geometry','fig-response'].every(id => {"
            "  const gd = document.querySelector('#' + id + ' .js-plotly-plot');"
            "  return gd && gd.data && gd.data.length > 0 && gd._fullLayout; });"
        ),
        timeout,
        "the four figures",
    )


def watch_redraws(browser) -> None:
    """Record, per graph, when Plotly first finished drawing it after ``window.__drawn`` was emptied
    (performance.now(), ms): the redraw an edit caused, not the background's later ones."""
    browser.execute_script(
        "window.__drawn = window.__drawn || {};"
        "for (const id of ['fig-svaj','fig-profile','fig-geometry','fig-response']) {"
        "  const gd = document.querySelector('#' + id + ' .js-plotly-plot');"
        "  if (gd && !gd.__watched) { gd.__watched = true;"
        "    gd.on('plotly_afterplot', () => { if (!(id in window.__drawn)) window.__drawn[id] = performance.now(); });"
        " } }"
    )


def edit(browser, path: str, text: str, timeout: float = 30.0) -> Dict[str, Any]:
    """Type `text` into the field at `path` and press Enter; wait for the page to redraw. Returns the
    server's timings and ``latency_ms``: from the key press to the last figure drawn (in the
    browser's clock) to the last figure's first drawing. A figure the edit did not change (the profile
    when only the speed changed) is not drawn again: the redraw is over when no other figure has been
    drawn for ``QUIET`` seconds."""
    from selenium.webdriver.common.keys import Keys

    before = computed(browser).get("computed", 0)
    watch_redraws(browser)
    box = element(browser, field_id(path))
    box.send_keys(Keys.CONTROL, "a")
    box.send_keys(text)
    t0 = browser.execute_script("window.__drawn = {}; return performance.now();")
    box.send_keys(Keys.ENTER)
    wait(lambda: computed(browser).get("computed", 0) > before, timeout, f"the redraw after {path} = {text!r}")
    end = time.monotonic() + timeout
    last, since = None, time.monotonic()
    while time.monotonic() < end:
        drawn = browser.execute_script("return Object.assign({}, window.__drawn);")
        if drawn != last:
            last, since = drawn, time.monotonic()
        elif drawn and time.monotonic() - since > QUIET:
            break
        time.sleep(0.02)
    else:
        raise TimeoutError(f"no figure was drawn again within {timeout:g} s of {path} = {text!r}")
    out = computed(browser)
    out["latency_ms"] = max(last.values()) - t0
    out["figures_drawn"] = sorted(last)
    return out


#: Seconds without a figure drawn after which a redraw is over (edit).
QUIET = 0.3
