# SPDX-License-Identifier: BSD-3-Clause
"""Hypothesis profiles of the property tests and the config fuzzer: "ci" (the default, a few hundred
examples per property) and "long" (``pytest --hypothesis-profile=long``: 10,000 per property)."""

try:
    from hypothesis import HealthCheck, settings
except ImportError:  # the property tests skip themselves
    pass
else:
    settings.register_profile("ci", max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
    settings.register_profile("long", max_examples=10_000, deadline=None, suppress_health_check=[HealthCheck.too_slow])
    settings.load_profile("ci")


import signal  # noqa: E402
import threading  # noqa: E402
import time  # noqa: E402

import pytest  # noqa: E402


@pytest.fixture
def ctrl_c():
    """ctrl_c(seconds) presses Ctrl-C that many seconds from now and returns the start time. A shell that
    starts the tests in the background (`cmd &` without job control) has SIGINT ignored, and Python then
    raises no KeyboardInterrupt at all: Ctrl-C's own handler is installed for the test."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timers = []

    def press(seconds: float) -> float:
        timers.append(threading.Timer(seconds, lambda: signal.raise_signal(signal.SIGINT)))
        timers[-1].start()
        return time.monotonic()

    try:
        yield press
    finally:
        for t in timers:
            t.cancel()
        signal.signal(signal.SIGINT, previous)
