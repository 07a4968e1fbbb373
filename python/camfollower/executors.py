# SPDX-License-Identifier: BSD-3-Clause
"""Run the cases of a study on any executor, with the same code: serially, on a process pool, on any
``concurrent.futures.Executor`` or on a Dask cluster (``dask.distributed``, optional extra).

:func:`run_cases` maps a picklable function over the cases and returns one :class:`Outcome` per case,
in the cases' order, whatever order they finished in: the value, or the error the case raised (with
its traceback text). A case that kills its worker process is reported as failed with its inputs; the
other cases' results are kept, on every executor (cases that only shared the dead worker are run
again). Pool workers die with the process that started them, even when it is killed. A progress bar
(tqdm, optional) counts finished cases; Ctrl-C (or ``cancel.set()``) cancels the pending cases and
raises KeyboardInterrupt (resp. returns the finished ones with the others marked cancelled).

``executor`` is one of

- ``None`` or ``"processes"``: a process pool of ``workers`` processes (default: the CPU count);
- ``"serial"``: in this process, one case after the other (debugging, tiny studies);
- a ``concurrent.futures.Executor`` (used as is, not shut down);
- a ``dask.distributed.Client`` (used as is);
- a string ``"tcp://host:port"`` (``tls://``, ``ws://``, ``wss://``, ``ucx://`` alike) or ``"dask"`` /
  ``"dask:N"`` (a LocalCluster of N processes): a Dask scheduler to connect to. Connecting (the TCP
  connection, the scheduler's handshake and the client's registration) either succeeds or raises
  RuntimeError naming the address within ``connect_timeout`` seconds, whatever the peer does.

Any other ``executor`` (or ``workers`` with an executor that has its own workers) is refused before
anything runs: ValueError naming ``executor`` and these forms (TypeError for an object of another type).
"""

from __future__ import annotations

import concurrent.futures as cf_futures
import contextlib
import math
import numbers
import os
import re
import sys
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
    return any(c.__name__ == "Client" and c.__module__.startswith("distributed") for c in type(obj).__mro__)


_MAX_LOCAL_WORKERS = 1024  # more local Dask processes than that is a typo, not a machine
SCHEDULER_FORMS = (
    "a Dask scheduler address 'tcp://host:port' (or tls://, ws://, wss://, ucx://), 'dask' or "
    f"'dask:N' (a LocalCluster of N processes, N a whole number in [1, {_MAX_LOCAL_WORKERS}])"
)
FORMS = (
    "None or 'processes' (a process pool of `workers` processes), 'serial', "
    + SCHEDULER_FORMS
    + ", a concurrent.futures.Executor or a dask.distributed.Client"
)
_ADDRESS = re.compile(r"(tcp|tls|ws|wss|ucx)://(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9._-]+):([0-9]{1,5})")


def check_executor(executor, workers: Optional[int] = None) -> None:
    """Refuse an ``executor`` (and ``workers``) that :func:`run_cases` cannot use, before anything
    runs; the studies call it first. ValueError for a string of no accepted form (``"dask:abc"``,
    ``"dask:0"``, ``"tcp://host"`` without a port) or a ``workers`` count the executor would ignore,
    TypeError for an object of another type; the message names the parameter and the accepted forms."""
    if isinstance(executor, str):
        if executor not in ("serial", "processes"):
            _check_scheduler(executor, "executor", FORMS)
    elif not (executor is None or _is_dask_client(executor) or isinstance(executor, cf_futures.Executor)):
        raise TypeError(f"executor must be {FORMS}; got an object of type {type(executor).__name__}")
    _check_workers(workers, executor)


def _check_scheduler(address: str, name: str, forms: str = SCHEDULER_FORMS) -> None:
    """A Dask scheduler's address, or "dask" / "dask:N"; ValueError naming ``name`` and ``forms``."""
    if address == "dask" or address.startswith("dask:"):
        _local_workers(address, name, forms)
        return
    m = _ADDRESS.fullmatch(address)
    if m is None or not 1 <= int(m.group(3)) <= 65535:
        raise ValueError(f"{name} must be {forms}; got {address!r}")


def _local_workers(spec: str, name: str = "executor", forms: str = SCHEDULER_FORMS) -> int:
    """N of "dask:N" (the CPU count for "dask"): ASCII digits only, 1 <= N <= _MAX_LOCAL_WORKERS."""
    if spec == "dask":
        return os.cpu_count() or 1
    n = spec.partition(":")[2]
    if not (n.isascii() and n.isdigit() and 1 <= int(n) <= _MAX_LOCAL_WORKERS):
        raise ValueError(
            f"{name}: {spec!r} needs N, a whole number of worker processes in [1, {_MAX_LOCAL_WORKERS}]; "
            f"{name} must be {forms}"
        )
    return int(n)


def _check_workers(workers, executor) -> None:
    if workers is None:
        return
    if isinstance(workers, bool) or not isinstance(workers, numbers.Integral):
        raise TypeError(
            f"workers must be an integer >= 1 (the process pool's size), got an object of type {type(workers).__name__}"
        )
    if workers < 1:
        raise ValueError(f"workers must be an integer >= 1 (the process pool's size), got {workers}")
    # The other executors have their own workers: a count given with them would be silently ignored.
    if not (executor is None or executor == "processes" or (executor == "serial" and workers == 1)):
        raise ValueError(
            f"workers={workers} sizes the process pool (executor None or 'processes'); executor "
            f"{executor if isinstance(executor, str) else type(executor).__name__!r} has its own workers "
            "(give a LocalCluster's size as executor='dask:N')"
        )


def _check_timeout(timeout) -> float:
    if isinstance(timeout, bool) or not isinstance(timeout, numbers.Real):
        raise TypeError(f"connect_timeout must be a number of seconds, got an object of type {type(timeout).__name__}")
    if not (math.isfinite(timeout) and timeout > 0):
        raise ValueError(f"connect_timeout must be a finite number of seconds > 0, got {timeout!r}")
    return float(timeout)


def connect(address: str, timeout: float = 5.0):
    """A Dask client for a scheduler address ("tcp://host:8786"), or a LocalCluster for "dask" /
    "dask:N" (N worker processes, one thread each). Raises RuntimeError naming the address within
    ``timeout`` seconds when no Dask scheduler answers there (nothing listening, a silent peer, a peer
    speaking another protocol), ValueError for an address of no accepted form, and ImportError when
    dask.distributed is not installed."""
    if not isinstance(address, str):
        raise TypeError(f"address must be {SCHEDULER_FORMS}; got an object of type {type(address).__name__}")
    _check_scheduler(address, "address")
    timeout = _check_timeout(timeout)
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise ImportError(
            "Dask executors need the optional extra: pip install 'camfollower[dask]' (dask[distributed])"
        ) from None
    if address == "dask" or address.startswith("dask:"):
        # allowed_failures=0: a worker's death fails its tasks at once instead of rerunning a crashing
        # case on 3 more workers; _dask reruns the cases that only shared the dead worker.
        cluster = LocalCluster(
            n_workers=_local_workers(address),
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            scheduler_kwargs={"allowed_failures": 0},
        )
        return Client(cluster)
    try:
        return _bounded_client(Client)(address, timeout=timeout)
    except Exception as e:  # noqa: BLE001 - whatever the peer sent (garbage, a huge length): not a scheduler
        raise RuntimeError(
            f"cannot reach the Dask scheduler at {address} within {timeout:g} s (nothing answers, or "
            f"the peer is not a Dask scheduler): {type(e).__name__}: {e}"
        ) from None


def _bounded_client(client_type):
    """A Client subclass whose start (TCP connection, handshake, registration) finishes within its
    ``timeout`` or is torn down: distributed bounds the TCP connection but waits for ever for the
    peer's handshake, so a peer that accepts and stays silent would hang Client()."""

    class Client(client_type):
        def start(self, **kwargs):
            try:
                super().start(callback_timeout=self._timeout, **kwargs)
            except BaseException:
                with contextlib.suppress(Exception):
                    self.close(timeout=2)
                raise

    return Client


def run_cases(
    fn: Callable[[Any], Any],
    items: Sequence[Any],
    *,
    executor=None,
    workers: Optional[int] = None,
    progress: bool = True,
    desc: str = "cases",
    cancel: Optional[threading.Event] = None,
    connect_timeout: float = 5.0,
) -> List[Outcome]:
    """``[fn(item) for item in items]`` on ``executor`` (module docstring), as Outcomes in order.

    ``fn`` must be picklable for processes and Dask (a module-level function, or a functools.partial of
    one). Results are bit-identical whatever the executor: each case is computed from its own inputs.
    """
    check_executor(executor, workers)
    connect_timeout = _check_timeout(connect_timeout)
    items = list(items)
    if not items:
        return []
    bar = _progress_bar(len(items), desc, progress)
    try:
        if executor == "serial":
            return _serial(fn, items, bar, cancel)
        if executor is None or executor == "processes":
            return _pool(fn, items, int(workers or os.cpu_count() or 1), bar, cancel)
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
        return _futures(executor, fn, items, bar, cancel)  # check_executor let nothing else through
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


def _die_with_parent(parent: int) -> None:
    """Pool worker initializer: a worker outlives a parent killed with SIGKILL (nothing tells it to
    stop), holding memory and CPU for ever. On Linux the kernel sends it SIGKILL when its parent dies
    (PR_SET_PDEATHSIG: works even while the case holds the GIL in compiled code); elsewhere a thread
    polls the parent."""
    try:
        if sys.platform.startswith("linux"):
            import ctypes
            import signal

            PR_SET_PDEATHSIG = 1
            ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
            if not _alive(parent):  # died before prctl took effect: no signal will come
                os._exit(1)
        elif os.name == "posix":

            def watch():
                while _alive(parent):
                    threading.Event().wait(1.0)
                os._exit(1)

            threading.Thread(target=watch, name="camfollower-parent-watch", daemon=True).start()
    except Exception:  # noqa: BLE001 - never break the pool over this; the worker just is not guarded
        pass


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)  # signal 0: only checks that the process exists
    except ProcessLookupError:
        return False
    except PermissionError:  # the pid was reused by another user's process
        return False
    return True


def _pool(fn, items, workers, bar, cancel) -> List[Outcome]:
    """A process pool; when a worker dies (BrokenProcessPool) the unfinished cases are retried in a
    fresh pool, and those that break it again alone, one per pool: a case that kills its worker on
    its own is reported as failed, the others complete."""
    out: List[Optional[Outcome]] = [None] * len(items)
    todo = list(range(len(items)))
    for _attempt in range(2):
        with _process_pool(min(workers, len(todo))) as pool:

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
        with _process_pool(1) as pool:
            got = _collect({pool.submit(_guarded, fn, items[i]): i}, len(items), bar, cancel, lambda p: None)
        out[i] = got[i] or Outcome(
            i,
            False,
            error="worker crashed",
            detail="the worker process running this case died (killed, out of memory or a crash "
            "in compiled code); rerun it with executor='serial' to see where",
        )
    return out  # type: ignore[return-value]


def _process_pool(workers: int) -> cf_futures.ProcessPoolExecutor:
    return cf_futures.ProcessPoolExecutor(max_workers=workers, initializer=_die_with_parent, initargs=(os.getpid(),))


def _futures(executor, fn, items, bar, cancel) -> List[Outcome]:
    futures = {executor.submit(_guarded, fn, item): i for i, item in enumerate(items)}

    def stop(pending):
        for f in pending:
            f.cancel()

    got = _collect(futures, len(items), bar, cancel, stop)
    return [
        o or Outcome(i, False, error="worker crashed", detail="the executor's worker died running this case")
        for i, o in enumerate(got)
    ]


def _dask(client, fn, items, bar, cancel) -> List[Outcome]:
    """All cases at once, then each case whose worker died (KilledWorker) again alone: a worker's death
    fails every task it held, the crashing case's and those only queued beside it; run alone, the
    others complete and a case that kills its worker on its own is reported as crashed."""
    out: List[Optional[Outcome]] = [None] * len(items)
    for i in _dask_round(client, fn, items, range(len(items)), out, bar, cancel):
        if _dask_round(client, fn, items, [i], out, bar, cancel):
            out[i] = Outcome(
                i,
                False,
                error="worker crashed",
                detail="the Dask worker running this case alone died (killed, out of memory or a crash "
                "in compiled code); rerun it with executor='serial' to see where",
            )
            if bar is not None:
                bar.update(1)
    return [o or _cancelled(i) for i, o in enumerate(out)]


def _dask_round(client, fn, items, indices, out, bar, cancel) -> List[int]:
    """Run ``indices`` into ``out``; returns those whose worker died (KilledWorker), in order. Cancelled
    ones stay None."""
    from distributed import KilledWorker, as_completed

    if cancel is not None and cancel.is_set():
        return []
    indices = list(indices)
    # retries=0: a case's own exception is data (_guarded); nothing else is worth a rerun.
    futures = client.map(_guarded, [fn] * len(indices), [items[i] for i in indices], pure=False, retries=0)
    index = {f.key: i for f, i in zip(futures, indices)}
    killed = []
    try:
        for f in as_completed(futures):
            i = index[f.key]
            try:
                out[i] = _outcome(i, f.result())
            except KilledWorker:
                killed.append(i)  # counted when settled
            except Exception as e:  # noqa: BLE001 - e.g. the result did not pickle, the scheduler went away
                out[i] = Outcome(i, False, error=f"{type(e).__name__}: {e}", detail="the Dask task failed")
            if bar is not None and out[i] is not None:
                bar.update(1)
            if cancel is not None and cancel.is_set():
                client.cancel([g for g in futures if not g.done()])
                return []
    except KeyboardInterrupt:
        client.cancel(futures)
        raise
    return sorted(killed)


__all__ = ["Outcome", "check_executor", "connect", "run_cases"]
