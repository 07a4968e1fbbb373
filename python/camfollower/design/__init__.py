# SPDX-License-Identifier: BSD-3-Clause
"""The design page: ``camfollower design [CONFIG]`` (docs/design.md).

A local web page (127.0.0.1 only, a random token in its address) to edit a cam and its mechanism
with the figures redrawn at each edit: SVAJ, the profile coloured by pressure angle with the
follower at a cursor, pressure angle and radius of curvature, the flexible response at the camshaft's
speed (periodic steady state), the margin curve and the first contact loss over a speed range, and a
synthesis of the lift. It needs the ``design`` extra (Dash; Plotly.js ships inside it, so the page
works with no internet access): ``pip install 'camfollower[design]'``.

>>> from camfollower.design import serve
>>> serve("examples/translating_roller.toml")        # doctest: +SKIP

The computations behind the figures are plain functions (``camfollower.design.views``), the
document's fields and edits ``camfollower.design.document``.
"""

from __future__ import annotations

from .app import DesignApp, serve

__all__ = ["DesignApp", "serve"]
