# SPDX-License-Identifier: BSD-3-Clause
"""The unknowns of a lift synthesis: the lift at equally spaced stations inside each redesigned
segment, as fractions of the segment's lift, interpolated by the library's own spline
(``Segment.from_table`` of odd degree, every end derivative up to ``degree - 1`` zero).

The spline's control points are a fixed linear map of these station lifts, so the space is the
B-spline space of the segment with its end conditions clamped: a segment of degree d joins its dwells
C^(d-1) whatever the unknowns, and the lift, velocity, acceleration and jerk are linear in them.
Stations, not control points, because they keep the unknowns in lift units a designer can read.
"""

from __future__ import annotations

import math
import numbers
from typing import List, Optional, Sequence

import numpy as np

from . import _core

#: Degrees of the redesigned segments and the continuity each gives at the segment's ends.
DEGREES = {3: 2, 5: 4, 7: 6}
#: Fewer stations leave too little shape to move the spectrum; more make every gradient dearer.
MIN_NODES, MAX_NODES = 3, 40
#: Closest stations (rad): the spline's conditioning degrades below this.
MIN_NODE_SPACING = math.radians(0.5)


def degree_for(continuity: int) -> int:
    """The spline degree that joins the dwells with ``continuity`` continuous derivatives."""
    for degree, order in sorted(DEGREES.items()):
        if order >= continuity:
            return degree
    raise ValueError(f"continuity must be 2..6 (derivatives continuous at the segment ends), got {continuity}")


class LiftSpace:
    """Station lifts of the ``segments`` (indices into ``program.segments``) of ``program``."""

    def __init__(self, program, segments: Optional[Sequence[int]], nodes: int, degree: int):
        if not isinstance(program, _core.MotionProgram):
            raise TypeError(f"program must be a MotionProgram, got {type(program).__name__}")
        if isinstance(nodes, bool) or not isinstance(nodes, numbers.Integral) or not MIN_NODES <= nodes <= MAX_NODES:
            raise ValueError(
                f"nodes must be an integer in [{MIN_NODES}, {MAX_NODES}] (stations per redesigned segment), got {nodes!r}"
            )
        if degree not in DEGREES:
            raise ValueError(f"degree must be one of {sorted(DEGREES)} (C2, C4, C6 joins), got {degree!r}")
        all_segments = list(program.segments)
        if len(all_segments) == 1 and all_segments[0].law.is_custom and all_segments[0].law.definition.get("periodic"):
            raise ValueError(
                "program: a whole-revolution table has no rises and returns to reshape; the synthesis redesigns "
                "segments between dwells: describe the program as segments (docs/config.md)"
            )
        moving = [i for i, s in enumerate(all_segments) if s.h_end != s.h_start]
        chosen = moving if segments is None else list(segments)
        if not chosen:
            raise ValueError("the program has no rise or return to redesign (every segment is a dwell)")
        for i in chosen:
            if isinstance(i, bool) or not isinstance(i, numbers.Integral) or not 0 <= i < len(all_segments):
                raise ValueError(f"segments: index {i!r} is not a segment of the program (0..{len(all_segments) - 1})")
            if all_segments[i].h_end == all_segments[i].h_start:
                raise ValueError(f"segments: segment {i} is a dwell (no lift to shape); rises and returns: {moving}")
            span = all_segments[i].theta_end - all_segments[i].theta_start
            if span / (nodes + 1) < MIN_NODE_SPACING:
                raise ValueError(
                    f"nodes: {nodes} stations in segment {i} ({math.degrees(span):.4g} deg) are closer than "
                    f"{math.degrees(MIN_NODE_SPACING):g} deg; use at most {int(span / MIN_NODE_SPACING) - 1}"
                )
        if len(set(chosen)) != len(chosen):
            raise ValueError(f"segments: repeated index in {chosen}")
        self.base = program
        self.segments = sorted(int(i) for i in chosen)
        self.nodes = int(nodes)
        self.degree = int(degree)
        self._all = all_segments
        self._stations = {
            i: np.linspace(all_segments[i].theta_start, all_segments[i].theta_end, nodes + 2) for i in self.segments
        }

    @property
    def size(self) -> int:
        return self.nodes * len(self.segments)

    @property
    def continuity(self) -> int:
        return DEGREES[self.degree]

    def stations(self, i: int) -> np.ndarray:
        """Station angles (rad) of segment ``i``, its ends included."""
        return self._stations[i]

    def start(self, program=None) -> np.ndarray:
        """``program``'s (default: the base program's) lift at the stations (fractions of each
        segment's lift)."""
        program = self.base if program is None else program
        out = []
        for i in self.segments:
            s = self._all[i]
            h = np.asarray(program.evaluate(self._stations[i][1:-1])["h"], dtype=float)
            out.append((h - s.h_start) / (s.h_end - s.h_start))
        return np.concatenate(out)

    def program(self, p: Sequence[float]):
        """The program with the redesigned segments through the station lifts ``p``."""
        p = np.asarray(p, dtype=float)
        if p.shape != (self.size,):
            raise ValueError(f"expected {self.size} station lifts, got shape {p.shape}")
        segments: List = list(self._all)
        for k, i in enumerate(self.segments):
            s = self._all[i]
            fraction = p[k * self.nodes : (k + 1) * self.nodes]
            h = s.h_start + (s.h_end - s.h_start) * np.concatenate(([0.0], fraction, [1.0]))
            segments[i] = _core.Segment.from_table(self._stations[i], h, self.degree)
        program = _core.MotionProgram(segments)
        error = self.base.profile_error  # a measured cam's error stays with the cam
        return program.with_profile_error(error) if error is not None else program

    def grid(self, per_segment: int = 240) -> np.ndarray:
        """Cam angles (rad) inside the redesigned segments where the kinematic limits are checked."""
        return np.concatenate([np.linspace(*self._stations[i][[0, -1]], per_segment) for i in self.segments])

    def kinematic_basis(self, p: Sequence[float], theta: np.ndarray):
        """h and its derivatives at ``theta`` as value + matrix @ (p' - p): exact, the spline being linear
        in the station lifts. Returns ({'h', 'dh', 'd2h', 'd3h'}: values, same keys: matrices)."""
        p = np.asarray(p, dtype=float)
        base = {k: np.asarray(v, dtype=float) for k, v in self.program(p).evaluate(theta).items()}
        matrices = {k: np.empty((len(theta), self.size)) for k in base}
        for j in range(self.size):
            e = p.copy()
            e[j] += 1.0
            moved = self.program(e).evaluate(theta)
            for k in base:
                matrices[k][:, j] = np.asarray(moved[k], dtype=float) - base[k]
        return base, matrices
