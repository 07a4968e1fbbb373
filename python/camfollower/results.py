# SPDX-License-Identifier: BSD-3-Clause
"""Typed simulation results: named channels as NumPy views on the C++ buffers, statistics, NPZ files."""

from __future__ import annotations

import io
import json
import math
import os
from pathlib import Path
from typing import Any, Dict, List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from . import _files, _text

_FORMAT = "camfollower.Result/1"
_STAT_TYPES = {
    "steps": int,
    "newton_iterations": int,
    "max_iterations_in_a_step": int,
    "halvings": int,
    "decimation": int,
    "cancelled": bool,
}


def _settle_from_json(text: str) -> Optional[Dict[str, Any]]:
    """The settle report as saved: strict JSON writes a non-finite change as null; read it back as NaN."""
    settle = json.loads(text)
    if isinstance(settle, dict):
        for key in ("change", "change_absolute", "tolerance"):
            if key in settle and settle[key] is None:
                settle[key] = math.nan
        if isinstance(settle.get("history"), list):
            settle["history"] = [math.nan if h is None else h for h in settle["history"]]
    return settle


class Event(NamedTuple):
    """A contact event located within a step: (time in s, name, "lost" | "made"), a plain tuple that
    prints its time to the picosecond (an event at the start prints at 0, not at 8.2e-294 s)."""

    time: float
    name: str
    kind: str

    def __repr__(self) -> str:
        return f"Event(time={_text.seconds(self.time)}, name={self.name!r}, kind={self.kind!r})"


class Result:
    """Time histories of one run.

    ``t`` (s), ``q``, ``v``, ``a`` (rows x DOFs, SI units of each DOF: m or rad) and every channel of the
    system by name (``r["cam.force"]``, ``r.channel("cam.force")``; ``r.channels`` lists them).
    ``stats`` holds the solver statistics, ``contact_loss`` maps each contact's name to the (start, end)
    times in s of its intervals without contact (checked at every step, not only at recorded rows).
    ``events`` lists the contact losses and re-contacts located within the steps, in time order, as
    ``Event(time in s, name, "lost" | "made")`` tuples; the name is the contact's ``<contact>.contact`` (a
    clearance's ``<clearance>.wall``). Arrays are read-only views on the run's buffer; ``save(path)`` /
    ``Result.load(path)`` round-trip through an NPZ file.
    ``settle`` is None, or (after ``simulate(..., settle=True)``) a dict: ``settled`` (bool),
    ``revolutions`` simulated to settle, ``change`` (the last revolution-to-revolution change of the
    watched accelerations relative to their peak), ``change_absolute`` (m/s^2), ``tolerance``,
    ``history`` (the change per revolution) and ``dofs`` (the watched DOFs).
    """

    def __init__(
        self,
        names: Sequence[str],
        dofs: Sequence[str],
        data: np.ndarray,
        stats: Dict[str, Any],
        contact_loss: Dict[str, Sequence[Tuple[float, float]]],
        settle: Optional[Dict[str, Any]] = None,
        events: Sequence[Tuple[float, str, str]] = (),
    ):
        self._names: List[str] = list(names)
        self._index = {n: i for i, n in enumerate(self._names)}
        self.dof_names: List[str] = list(dofs)
        data = np.asarray(data)
        if data.shape[0] != len(self._names):
            raise ValueError(f"data has {data.shape[0]} channels, names {len(self._names)}")
        data.flags.writeable = False
        self._data = data
        self.stats: Dict[str, Any] = dict(stats)
        self.contact_loss: Dict[str, List[Tuple[float, float]]] = {
            str(name): [(float(a), float(b)) for a, b in intervals] for name, intervals in dict(contact_loss).items()
        }
        self.settle: Optional[Dict[str, Any]] = None if settle is None else dict(settle)
        self.events: List[Event] = [Event(float(t), str(n), str(k)) for t, n, k in events]

    # --- channels ---
    @property
    def channels(self) -> List[str]:
        """Names of the recorded channels: t, q.<dof>, v.<dof>, a.<dof>, then the system's own."""
        return list(self._names)

    @property
    def rows(self) -> int:
        return int(self._data.shape[1])

    def channel(self, name: str) -> np.ndarray:
        try:
            return self._data[self._index[name]]
        except KeyError:
            raise KeyError(f"unknown channel {name!r}; recorded channels: {', '.join(self._names)}") from None

    def _block(self, prefix: str) -> np.ndarray:
        first = self._index[f"{prefix}.{self.dof_names[0]}"]
        return self._data[first : first + len(self.dof_names)].T  # rows x DOFs, a view

    @property
    def t(self) -> np.ndarray:
        return self.channel("t")

    @property
    def q(self) -> np.ndarray:
        """Displacements, rows x DOFs (view)."""
        return self._block("q")

    @property
    def v(self) -> np.ndarray:
        return self._block("v")

    @property
    def a(self) -> np.ndarray:
        return self._block("a")

    @property
    def time_step(self) -> float:
        return float(self.stats["time_step"])

    @property
    def decimation(self) -> int:
        return int(self.stats["decimation"])

    def __getitem__(self, key: str) -> Any:
        """Channels by name; also "q", "v", "a" (2-D), "stats", "contact_loss"; boolean channels
        (``in_contact`` and ``<contact>.in_contact``) come back as bool arrays."""
        if key in ("q", "v", "a"):
            return self._block(key)
        if key == "stats":
            return self.stats
        if key == "contact_loss":
            return self.contact_loss
        values = self.channel(key)
        return values.astype(bool) if key == "in_contact" or key.endswith(".in_contact") else values

    def __contains__(self, key: str) -> bool:
        return key in self._index or key in ("q", "v", "a", "stats", "contact_loss")

    def __repr__(self) -> str:
        t = self.channel("t") if "t" in self._index and self.rows else ()
        span = f"t = {_text.seconds(t[0])} to {_text.seconds(t[-1])} s, " if len(t) else ""
        lost = sum(b - a for intervals in self.contact_loss.values() for a, b in intervals)
        return (
            f"Result({self.rows} rows, {span}{len(self.dof_names)} DOFs, {len(self.events)} contact events, "
            f"contact lost {_text.seconds(lost)} s, channels: "
            f"{', '.join(n for n in self._names if '.' not in n or not n.startswith(('q.', 'v.', 'a.')))})"
        )

    # --- files ---
    def save(self, path: os.PathLike | str) -> Path:
        """Write an NPZ file atomically (camfollower._files: a temporary in the same folder, then renamed)."""
        path = Path(path)
        if path.suffix != ".npz":
            raise ValueError(f"path must end in .npz, got {str(path)!r}")
        _files.check_target(path)  # refused before the archive is built
        numbers = {k: v for k, v in self.stats.items() if not isinstance(v, str)}
        texts = {k: v for k, v in self.stats.items() if isinstance(v, str)}  # e.g. "backend"
        buffer = io.BytesIO()
        np.savez(
            buffer,
            format=np.array(_FORMAT),
            names=np.array(self._names),
            dofs=np.array(self.dof_names),
            data=np.ascontiguousarray(self._data),
            stats_keys=np.array(list(numbers)),
            stats_values=np.array([float(v) for v in numbers.values()]),
            stats_text=np.array(_files.json_text(texts, indent=None)),
            contact_names=np.array(list(self.contact_loss), dtype=str),
            settle=np.array(_files.json_text(self.settle, indent=None)),
            events=np.array(_files.json_text(self.events, indent=None)),
            **{
                f"contact_loss_{i}": np.array(v, dtype=float).reshape(-1, 2)
                for i, v in enumerate(self.contact_loss.values())
            },
        )
        _files.write_bytes(path, buffer.getvalue())
        return path

    @classmethod
    def load(cls, path: os.PathLike | str) -> "Result":
        with np.load(Path(path), allow_pickle=False) as z:
            if "format" not in z or str(z["format"]) != _FORMAT:
                raise ValueError(f"{str(path)!r} is not a camfollower Result file ({_FORMAT})")
            stats: Dict[str, Any] = {}
            for k, v in zip(z["stats_keys"], z["stats_values"]):
                stats[str(k)] = _STAT_TYPES.get(str(k), float)(v)
            if "stats_text" in z:
                stats.update(json.loads(str(z["stats_text"])))
            losses = {str(n): [tuple(x) for x in z[f"contact_loss_{i}"]] for i, n in enumerate(z["contact_names"])}
            settle = _settle_from_json(str(z["settle"])) if "settle" in z else None
            events = json.loads(str(z["events"])) if "events" in z else []
            return cls(
                [str(n) for n in z["names"]], [str(d) for d in z["dofs"]], z["data"], stats, losses, settle, events
            )

    def __reduce__(self):
        return (
            Result,
            (
                self._names,
                self.dof_names,
                np.array(self._data),
                self.stats,
                self.contact_loss,
                self.settle,
                self.events,
            ),
        )
