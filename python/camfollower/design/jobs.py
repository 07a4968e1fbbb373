# SPDX-License-Identifier: BSD-3-Clause
"""The design page's background work, per browser tab: a list of steps (refine the response, one
speed of the margin curve after another, the first contact loss, a synthesis) run on one worker
thread, the newest design's only.

A new design, or Cancel, starts a new generation: the running step finishes (a steady state in the
library cannot be interrupted) and its result is dropped; no further step of the old generation runs.
One step runs at a time over all tabs, so the other core stays free for the next edit's redraw.
"""

from __future__ import annotations

import threading
import time
import traceback
from collections import OrderedDict
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional

#: Tabs remembered (their last orbit and results); the oldest is forgotten beyond this.
MAX_TABS = 32

Step = Callable[[Dict[str, Any]], Optional[str]]


@dataclass
class TabState:
    generation: int = 0
    status: str = ""
    busy: bool = False
    version: int = 0  # bumped whenever results change: the page's poll redraws only then
    results: Dict[str, Any] = field(default_factory=dict)
    memo: Dict[str, Any] = field(default_factory=dict)  # survives generations: warm starts


class Jobs:
    """Per-tab generations of background steps. ``start(tab, steps)`` runs each step with the tab's
    generation's result dict (shared by its steps); a step returns a status text (or None); an exception ends the generation with its
    message as the status."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._one_at_a_time = threading.Lock()
        self._tabs: "OrderedDict[str, TabState]" = OrderedDict()
        self._threads: List[threading.Thread] = []

    def tab(self, tab: str) -> TabState:
        with self._lock:
            state = self._tabs.get(tab)
            if state is None:
                state = self._tabs[tab] = TabState()
                while len(self._tabs) > MAX_TABS:
                    self._tabs.popitem(last=False)
            self._tabs.move_to_end(tab)
            return state

    def start(self, tab: str, steps: List[Step], status: str = "computing ...") -> int:
        state = self.tab(tab)
        with self._lock:
            state.generation += 1
            generation = state.generation
            state.results = {}
            state.status = status
            state.busy = bool(steps)
            state.version += 1
        if steps:
            thread = threading.Thread(target=self._run, args=(state, generation, steps), daemon=True)
            with self._lock:
                self._threads = [t for t in self._threads if t.is_alive()] + [thread]
            thread.start()
        return generation

    def idle(self) -> bool:
        """No step is running (a cancelled one included)."""
        with self._lock:
            return not any(t.is_alive() for t in self._threads)

    def stop(self, timeout: float = 60.0) -> None:
        """End every tab's work and wait for the running steps (the server is stopping: a thread
        still inside the library when the interpreter exits would abort it)."""
        with self._lock:
            for state in self._tabs.values():
                state.generation += 1
                state.busy = False
            threads = list(self._threads)
        for t in threads:
            t.join(timeout)

    def cancel(self, tab: str) -> None:
        state = self.tab(tab)
        with self._lock:
            if state.busy:
                state.generation += 1
                state.busy = False
                state.status = "cancelled"
                state.version += 1

    def _run(self, state: TabState, generation: int, steps: List[Step]) -> None:
        results: Dict[str, Any] = {}  # the generation's: each step adds to it
        for step in steps:
            with self._one_at_a_time:
                if state.generation != generation:
                    return
                t0 = time.perf_counter()
                try:
                    text = step(results)
                except Exception as e:  # shown on the page; the server carries on
                    text = f"error: {e}"
                    results["error"] = str(e)
                    results["traceback"] = traceback.format_exc(limit=4)
                results["seconds"] = time.perf_counter() - t0
            with self._lock:
                if state.generation != generation:
                    return
                state.results = {k: list(v) if isinstance(v, list) else v for k, v in results.items()}
                if text:
                    state.status = text
                state.version += 1
                if "error" in results:
                    state.busy = False
                    return
        with self._lock:
            if state.generation == generation:
                state.busy = False
                state.version += 1

    def snapshot(self, tab: str) -> Dict[str, Any]:
        state = self.tab(tab)
        with self._lock:
            return {
                "version": state.version,
                "busy": state.busy,
                "status": state.status,
                "results": dict(state.results),
            }
