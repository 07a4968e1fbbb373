# SPDX-License-Identifier: BSD-3-Clause
"""python -m camfollower: a config file to results and figures in one command (see docs/config.md).

    python -m camfollower figures CONFIG [-o DIR]    simulate, then CSV, figures and summary.json in DIR
"""

from .cli import main

raise SystemExit(main())
