# SPDX-License-Identifier: BSD-3-Clause
"""python -m camfollower: the ``camfollower`` command (every verb; see camfollower.cli and docs/config.md)."""

from .cli import main

raise SystemExit(main())
