# SPDX-License-Identifier: BSD-3-Clause
"""Numbers as printed for a reader (reprs, the command line's lines, study tables): significant
digits, not the float's last bits. 349.99999999999994 rpm prints as 350; a time is rounded to the
picosecond first, so an event at 8.2e-294 s (the rounding noise of 0) prints as 0. Files (CSV, JSON,
NPZ) keep full precision: this is for text only."""

from __future__ import annotations

import math
import numbers


def g(x, digits: int = 6) -> str:
    """`x` with `digits` significant digits (%g), integers and non-numbers as they are."""
    if isinstance(x, bool) or not isinstance(x, numbers.Real):
        return repr(x) if isinstance(x, str) else str(x)
    if isinstance(x, numbers.Integral):
        return str(int(x))
    return f"{float(x):.{digits}g}"


def seconds(t, digits: int = 6) -> str:
    """A time in s: rounded to 1e-12 s (below any time step, above rounding noise), then %g."""
    t = float(t)
    return g(round(t, 12) + 0.0 if math.isfinite(t) else t, digits)  # + 0.0: no "-0"


def values(mapping, digits: int = 6) -> str:
    """'k=v, ...' of a mapping, each number with `digits` significant digits."""
    return ", ".join(f"{k}={g(v, digits)}" for k, v in mapping.items())
