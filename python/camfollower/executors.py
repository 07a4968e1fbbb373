# SPDX-License-Identifier: BSD-3-Clause
"""Run the cases of a study on any executor, with the same code: serially, on a process pool, on any
``concurrent.futures.Executor`` or on a Dask cluster (``dask.distributed``, optional extra).

:func:`run_cases` maps a picklable function over the cases and returns one :class:`Outcome` per case,
in the cases' order, whatever order they finished in: the value, or the error the case raised (with
its traceback text). A case that kills its worker process is reported as failed with its inputs; the
other cases' results are kept. A progress bar (tqdm, optional) counts finished cases; Ctrl-C (or
``cancel.set()``) cancels the pending cases and raises KeyboardInterrupt (resp. returns the finished
ones with the others marked cancelled).

``executor`` is one of

- ``None`` or ``"processes"``: a process pool of ``workers`` processes (default: the CPU count);
- ``"serial"``: in this process, one case after the other (debugging, tiny studies);
- a ``concurrent.futures.Executor`` (used as is, not shut down);
- a ``dask.distributed.Client`` (used as is);
- a string ``"tcp://host:port"`` (or ``"dask"``/``"dask:N"`` for a LocalCluster of N processes): a
  Dask scheduler to connect to; an unreachable address fails within ``connect_timeout`` seconds.
"""

from __future__ import annotations

import concurrent.futures as cf_futures
import os
import threading
import traceback
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from typing import Any, Callable, List, Optional, Sequence


@dataclass(frozen=True)
class Outcome:
    """One case's outcome: ``ok`` and ``value``, or ``error`` (the exception's type and message) and
    ``detail`` (its traceback, or what happened to the worker)."""

    index: int
    ok: bool
    value: Any = None
    error: Optional[str] = None
    detail: Optional[str] = None


class _Failure:
    """A case's exception, carried back as data (exceptions of extension types may not pickle)."""

    def __init__(self, error: str, detail: str):
        self.error, self.detail = error, detail


def _guarded(fn: Callable, item) -> Any:
    try:
        return fn(item)
    except Exception as e:  # noqa: BLE001 - every case error becomes data; the study goes on
        return _Failure(f"{type(e).__name__}: {e}", traceback.format_exc())


def _outcome(index: int, value) -> Outcome:
    if isinstance(value, _Failure):
        return Outcome(index, False, error=value.error, detail=value.detail)
    return Outcome(index, True, value=value)


def _progress_bar(total: int, desc: str, enabled: bool):
    if not enabled:
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return tqdm(total=total, desc=desc, unit="case", smoothing=0.1)


def _is_dask_client(obj) -> bool:
    return type(obj).__name__ == "Client" and type(obj).__module__.startswith("distributed")


def connect(address: str, timeout: float = 5.0):
    """A Dask client for a scheduler address ("tcp://host:8786"), or a LocalCluster for "dask" /
    "dask:N" (N worker processes, one thread each). Raises RuntimeError within ``timeout`` seconds
    when the scheduler cannot be reached, and ImportError when dask.distributed is not installed."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise ImportError("Dask executors need the optional extra: pip install 'camfollower[dask]' "
                          "(dask[distributed])") from None
    if address == "dask" or address.startswith("dask:"):
        n = address.partition(":")[2]
        workers = int(n) if n else (os.cpu_count() or 1)
        if workers < 1:
            raise ValueError(f"dask:N needs N >= 1 worker processes, got {workers}")
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
        return Client(cluster)
    if "://" not in address:
        raise ValueError(f"scheduler address must look like tcp://host:port, got {address!r}")
    try:
        return Client(address, timeout=f"{timeout}s")
    except (OSError, TimeoutError) as e:
        raise RuntimeError(f"cannot reach the Dask scheduler at {address} within {timeout:g} s: {e}") from None


def run_cases(fn: Callable[[Any], Any], items: Sequence[Any], *, executor=None, workers: Optional[int] = None,
              progress: bool = True, desc: str = "cases", cancel: Optional[threading.Event] = None,
              connect_timeout: float = 5.0) -> List[Outcome]:
    """``[fn(item) for item in items]`` on ``executor`` (module docstring), as Outcomes in order.

    ``fn`` must be picklable for processes and Dask (a module-level function, or a functools.partial of
    one). Results are bit-identical whatever the executor: each case is computed from its own inputs.
    """
    items = list(items)
    if workers is not None and (not isinstance(workers, int) or workers < 1):
        raise ValueError(f"workers must be an integer >= 1, got {workers!r}")
    if not items:
        return []
    bar = _progress_bar(len(items), desc, progress)
    try:
        if executor == "serial":
            return _serial(fn, items, bar, cancel)
        if executor is None or executor == "processes":
            return _pool(fn, items, workers or os.cpu_count() or 1, bar, cancel)
        if isinstance(executor, str):
            client = connect(executor, connect_timeout)
            try:
                return _dask(client, fn, items, bar, cancel)
            finally:
                cluster = getattr(client, "cluster", None)
                client.close()
                if cluster is not None and executor.startswith("dask"):
                    cluster.close()
        if _is_dask_client(executor):
            return _dask(executor, fn, items, bar, cancel)
        if isinstance(executor, cf_futures.Executor):
            return _futures(executor, fn, items, bar, cancel)
        raise TypeError("executor must be None, 'serial', 'processes', a scheduler address, a "
                        f"concurrent.futures.Executor or a dask.distributed.Client, got {type(executor).__name__}")
    finally:
        if bar is not None:
            bar.close()


def _cancelled(index: int) -> Outcome:
    return Outcome(index, False, error="cancelled", detail="the study was cancelled before this case ran")


def _serial(fn, items, bar, cancel) -> List[Outcome]:
    out = []
    for i, item in enumerate(items):
        if cancel is not None and cancel.is_set():
            out.extend(_cancelled(j) for j in range(i, len(items)))
            break
        out.append(_outcome(i, _guarded(fn, item)))
        if bar is not None:
            bar.update(1)
    return out


def _collect(futures: dict, n: int, bar, cancel, on_cancel) -> List[Optional[Outcome]]:
    """Wait for {future: index}; returns outcomes by index (None where the future broke)."""
    out: List[Optional[Outcome]] = [None] * n
    pending = set(futures)
    try:
        while pending:
            done, pending = cf_futures.wait(pending, timeout=0.2, return_when=cf_futures.FIRST_COMPLETED)
            for f in done:
                i = futures[f]
                try:
                    out[i] = _outcome(i, f.result())
                except BrokenProcessPool:
                    out[i] = None
                except cf_futures.CancelledError:
                    out[i] = _cancelled(i)
                except Exception as e:  # noqa: BLE001 - e.g. the case's result did not pickle
                    out[i] = Outcome(i, False, error=f"{type(e).__name__}: {e}", detail="raised by the executor")
                if bar is not None:
                    bar.update(1)
            if cancel is not None and cancel.is_set():
                on_cancel(pending)
                for f in pending:
                    out[futures[f]] = _cancelled(futures[f])
                return out
    except KeyboardInterrupt:
        on_cancel(pending)
        raise
    return out


def _pool(fn, items, workers, bar, cancel) -> List[Outcome]:
    """A process pool; when a worker dies (BrokenProcessPool) the unfinished cases are retried in a
    fresh pool, and those that break it again alone, one per pool: a case that kills its worker on
    its own is reported as failed, the others complete."""
    out: List[Optional[Outcome]] = [None] * len(items)
    todo = list(range(len(items)))
    for attempt in range(2):
        with cf_futures.ProcessPoolExecutor(max_workers=min(workers, len(todo))) as pool:
            def stop(pending):
                for f in pending:
                    f.cancel()
                pool.shutdown(wait=False, cancel_futures=True)
            futures = {pool.submit(_guarded, fn, items[i]): i for i in todo}
            got = _collect(futures, len(items), bar, cancel, stop)
        for i in todo:
            out[i] = got[i]
        todo = [i for i in todo if out[i] is None]
        if not todo:
            return out  # type: ignore[return-value]
        if bar is not None:
            bar.update(-len(todo))
    for i in todo:  # alone: the crash is this case's
        with cf_futures.ProcessPoolExecutor(max_workers=1) as pool:
            got = _collect({pool.submit(_guarded, fn, items[i]): i}, len(items), bar, cancel, lambda p: None)
        out[i] = got[i] or Outcome(i, False, error="worker crashed",
                                   detail="the worker process running this case died (killed, out of memory or a crash "
                                          "in compiled code); rerun it with executor='serial' to see where")
    return out  # type: ignore[return-value]


def _futures(executor, fn, items, bar, cancel) -> List[Outcome]:
    futures = {executor.submit(_guarded, fn, item): i for i, item in enumerate(items)}

    def stop(pending):
        for f in pending:
            f.cancel()

    got = _collect(futures, len(items), bar, cancel, stop)
    return [o or Outcome(i, False, error="worker crashed", detail="the executor's worker died running this case")
            for i, o in enumerate(got)]


def _dask(client, fn, items, bar, cancel) -> List[Outcome]:
    from distributed import as_completed

    futures = client.map(_guarded, [fn] * len(items), items, pure=False)
    index = {f.key: i for i, f in enumerate(futures)}
    out: List[Optional[Outcome]] = [None] * len(items)
    try:
        for f in as_completed(futures):
            i = index[f.key]
            try:
                out[i] = _outcome(i, f.result())
            except Exception as e:  # noqa: BLE001 - KilledWorker: the case took its worker down (repeatedly)
                out[i] = Outcome(i, False, error=f"{type(e).__name__}: {e}",
                                 detail="the Dask worker running this case died (KilledWorker) or the task failed")
            if bar is not None:
                bar.update(1)
            if cancel is not None and cancel.is_set():
                client.cancel([g for g in futures if not g.done()])
                break
    except KeyboardInterrupt:
        client.cancel(futures)
        raise
    return [o or _cancelled(i) for i, o in enumerate(out)]


__all__ = ["Outcome", "connect", "run_cases"]
