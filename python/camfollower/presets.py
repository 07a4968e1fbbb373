"""Ready-made mechanisms, built from the same parts as any user mechanism."""

from __future__ import annotations

from typing import Optional

from ._core import Mechanism, MotionProgram, Parameters, paper_preset


def paper(parameters: Optional[Parameters] = None, program: Optional[MotionProgram] = None) -> Mechanism:
    """The paper's 7-DOF cam-follower model (Tounsi et al.): camshaft on bearings (y1, x1), roller on
    its pin (y2, x2), follower rod in its guide (y3, x3), follower top on the preloaded return spring
    (y4); one contact named "cam" between a disk cam and the offset translating roller. ``parameters``
    as for CamFollowerModel (Table 2 defaults), ``program`` the cam's lift (Table 1 default)."""
    return paper_preset(parameters, program)


__all__ = ["paper"]
