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
