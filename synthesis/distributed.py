"""Evaluation on a Dask cluster: the LPτ blocks of a search, the files of a batch.

Optional: it needs the extra ``distributed`` (``pip install -e '.[distributed]'``). Dask is
imported only when a cluster is asked for (:func:`connect`); the default single-process path
never imports it.

A scheduler is named as on the command line (``--scheduler``):

* ``local:N``: a :class:`distributed.LocalCluster` of N worker processes (one thread each)
  on this machine, closed at the end of the run; 1 ≤ N ≤ the cores of this machine
  (:func:`usable_cores`);
* ``tcp://HOST:PORT`` (or ``tls://…``, with Dask's TLS settings in its configuration): an
  existing cluster; HOST a host name, an IPv4 address or an IPv6 address in brackets, PORT
  1–65535. Its workers must have the same versions of this program and of NumPy/SciPy, and
  see the files of a batch. A scheduler that does not answer within :data:`CONNECT_SECONDS`
  is refused.

The spec is checked (:func:`parse_scheduler`) before anything starts; every refusal, of the
spec or of the connection, is a :class:`DistributedError` (exit code 2) naming
``--scheduler``.

:class:`DaskExecutor` has the ``map(fn, items)`` of :class:`synthesis.search.Executor`: it
submits the items as tasks (a window of them ahead of the consumer), and yields the results
in the order of the items whatever the order in which the tasks finish. The search then
draws its blocks from the seed and reduces them in a fixed order, so a run on a cluster
gives the same design, bit for bit, as the run in one process.

The function reaches the workers as a task of its own, not as scattered data: Dask keeps a
task's recipe and computes its result again when every worker that held it is lost, whereas
scattered data lost with its last holder cancels every task that needs it. A worker that
joins late fetches the function from a peer with the first task the scheduler gives it, and
the window of tasks ahead grows with the cluster's threads. The block tasks are pure: a task lost with its
worker is run again (Dask's rescheduling; ``retries`` more times if it raises), and the
result does not change. When the consumer stops early (a stop rule, Ctrl-C) the tasks
still pending are cancelled.
"""

from __future__ import annotations

import ipaddress
import itertools
import logging
import os
import re
import signal
import threading
import uuid
from collections import deque
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import AbstractContextManager, contextmanager, nullcontext
from typing import TYPE_CHECKING, TypeVar

from assur.errors import AssurError
from assur.text import Message

if TYPE_CHECKING:
    from distributed import Client, Future, LocalCluster

__all__ = ["CONNECT_SECONDS", "DaskExecutor", "DistributedError", "connect", "executor_for",
           "parse_scheduler", "usable_cores"]

T = TypeVar("T")
R = TypeVar("R")

#: The prefix of a local cluster: ``local:N``.
LOCAL = "local:"
#: Address schemes of an existing cluster.
SCHEMES = ("tcp://", "tls://")
#: Seconds to wait for an existing scheduler to answer before refusing it.
CONNECT_SECONDS = 5
#: The highest port number.
PORTS = 65535
#: A host name: dot-separated labels of letters, digits and inner hyphens.
_HOST_NAME = re.compile(r"(?!-)[A-Za-z0-9-]{1,63}(?<!-)(\.(?!-)[A-Za-z0-9-]{1,63}(?<!-))*")
#: Worker threads per item of a task by default: with one LPτ block per task, Dask's client
#: and scheduler keep pace with about 15 workers (``docs/scale.md``); 8 leaves a margin.
THREADS_PER_ITEM = 8
#: Dask's setting of the workers' memory trimming (unset for a local cluster).
TRIM = "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_"
#: Dask's setting of how a nanny starts its worker process.
METHOD = "distributed.worker.multiprocessing-method"
#: Dask's TLS settings a ``tls://`` client needs: the authority and this client's identity.
TLS_SETTINGS = ("distributed.comm.tls.ca-file", "distributed.comm.tls.client.cert")


class DistributedError(AssurError):
    """A scheduler cannot be used: not installed, misnamed or unreachable (exit code 2)."""

    def __init__(self, message: Message) -> None:
        self.message = message
        super().__init__(message.text("en"))

    def text(self, lang: str = "en") -> str:
        """The sentence in ``lang``."""
        return self.message.text(lang)


def usable_cores() -> int:
    """The cores this process may run on: the most local workers (and batch processes).

    Examples
    --------
    >>> usable_cores() >= 1
    True
    """
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return os.cpu_count() or 1


def parse_scheduler(spec: str) -> int | str:
    """The number of local workers of ``local:N``, or the address of an existing cluster.

    Parameters
    ----------
    spec : str
        As given to ``--scheduler``.

    Returns
    -------
    int or str
        N of ``local:N``; else the address ``tcp://HOST:PORT`` (or ``tls://…``) itself.

    Raises
    ------
    DistributedError
        When ``spec`` is neither ``local:N`` (1 ≤ N ≤ :func:`usable_cores`) nor
        ``tcp://HOST:PORT`` / ``tls://HOST:PORT`` with a valid host and a port 1–65535;
        the message names what is wrong.

    Examples
    --------
    >>> parse_scheduler("local:1"), parse_scheduler("tcp://10.0.0.5:8786")
    (1, 'tcp://10.0.0.5:8786')
    >>> parse_scheduler("tls://[::1]:8786")
    'tls://[::1]:8786'
    >>> parse_scheduler("tcp://127.0.0.1:abc")
    Traceback (most recent call last):
    ...
    synthesis.distributed.DistributedError: --scheduler 'tcp://127.0.0.1:abc': expected a \
port, a whole number from 1 to 65535; found 'abc'
    """
    if spec.startswith(LOCAL):
        count, most = spec[len(LOCAL):], usable_cores()
        if not (count.isascii() and count.isdigit() and 1 <= int(count) <= most):
            raise DistributedError(Message("dist.local", {"spec": spec, "most": most,
                                                          "found": count}))
        return int(count)
    if not spec.startswith(SCHEMES):
        raise DistributedError(Message("dist.scheduler", {"found": spec,
                                                          "most": usable_cores()}))
    rest = spec.partition("://")[2]
    port: str | None
    if rest.startswith("["):
        inside, bracket, tail = rest[1:].partition("]")
        host, port = f"[{inside}{bracket}", tail.removeprefix(":") if tail else None
        valid = bool(bracket) and _is_ip(inside, 6)
    else:
        host, colon, port = rest.rpartition(":")
        if not colon:
            host, port = rest, None
        valid = _is_ip(host, 4) or (_HOST_NAME.fullmatch(host) is not None
                                    and not host.replace(".", "").isdigit())
    if not valid:
        raise DistributedError(Message("dist.host", {"spec": spec, "found": host}))
    if port is None or not (port.isascii() and port.isdigit() and 1 <= int(port) <= PORTS):
        raise DistributedError(Message("dist.port", {"spec": spec, "most": PORTS,
                                                     "found": "" if port is None else port}))
    return spec


def _is_ip(text: str, version: int) -> bool:
    """Whether ``text`` is an IP address of ``version`` (4 or 6)."""
    try:
        return ipaddress.ip_address(text).version == version
    except ValueError:
        return False


def _apply(fn: Callable[[T], R], items: Sequence[T]) -> list[R]:
    """The task: ``fn`` of each item of a chunk, in order (pure; runs on a worker)."""
    return [fn(item) for item in items]


class DaskExecutor:
    """Evaluate items as tasks on a Dask client; results in the order of the items.

    Parameters
    ----------
    client : distributed.Client
    retries : int
        Times a task that raised is run again before the error reaches the caller (a task
        lost with its worker is rescheduled by Dask without counting).
    chunk : int, optional
        Items per task (consecutive items; ≥ 1). Larger chunks cut the scheduler's work per
        item (see ``docs/scale.md``). Default: one item per task up to 8 worker threads,
        then one more per 8 threads (:data:`THREADS_PER_ITEM`), so that the client and the
        scheduler keep pace with the workers.
    ahead : int, optional
        Tasks submitted ahead of the consumer; default two per worker thread.
    """

    def __init__(self, client: Client, *, retries: int = 2, chunk: int | None = None,
                 ahead: int | None = None) -> None:
        self.client = client
        self.retries = retries
        self.chunk = chunk
        self.ahead = ahead

    def map(self, fn: Callable[[T], R], items: Iterable[T], /) -> Iterator[R]:
        """``fn(item)`` for each item, in order, evaluated on the cluster.

        ``fn`` is sent to the cluster once, as a task whose result the workers share (Dask
        computes it again if every worker holding it is lost); the items are drawn lazily,
        a window of tasks ahead of the consumer, two per worker thread of the cluster as it
        is now. Closing the iterator (or an exception in the consumer, such as Ctrl-C)
        cancels the tasks not yet consumed.

        Raises
        ------
        DistributedError
            When a task is lost for good: the workers that ran it kept dying (Dask's
            ``allowed-failures``), or the scheduler went away.
        """
        from distributed import CancelledError, KilledWorker

        client = self.client
        chunk = max(1, self.chunk or -(-_threads(client) // THREADS_PER_ITEM))
        run = uuid.uuid4().hex
        function = client.submit(_identity, fn, pure=False, retries=self.retries,
                                 key=f"assur-{run}-function")
        keys = (f"assur-{run}-{k}" for k in itertools.count())
        chunks = _chunks(items, chunk)
        pending: deque[Future[list[R]]] = deque()
        ahead = since = 0

        def fill() -> None:
            """Submit tasks up to the window; its size follows the cluster's threads, read
            again once a window of results has come back (a worker may have joined)."""
            nonlocal ahead, since
            if since >= ahead:
                ahead, since = self.ahead or 2 * _threads(client), 0
            while len(pending) < ahead:
                part = next(chunks, None)
                if part is None:
                    return
                pending.append(client.submit(_apply, function, part, pure=False,
                                             retries=self.retries, key=next(keys)))

        try:
            fill()
            while pending:
                try:
                    results = pending.popleft().result()
                except (KilledWorker, CancelledError) as exc:
                    raise DistributedError(Message("dist.lost", {
                        "reason": f"{type(exc).__name__}: {exc}"})) from None
                since += 1
                fill()
                yield from results
        finally:
            client.cancel([*pending, function])


def _identity(value: T) -> T:
    """The task that holds the function on the workers."""
    return value


def _threads(client: Client) -> int:
    """Worker threads of the cluster now (at least 1)."""
    threads: dict[str, int] = client.nthreads()
    return max(1, sum(threads.values()))


def _chunks(items: Iterable[T], size: int) -> Iterator[list[T]]:
    iterator = iter(items)
    while part := list(itertools.islice(iterator, size)):
        yield part


@contextmanager
def connect(spec: str, *, retries: int = 2, chunk: int | None = None
            ) -> Iterator[DaskExecutor]:
    """A :class:`DaskExecutor` on the scheduler ``spec`` for the duration of a ``with``.

    Parameters
    ----------
    spec : str
        ``local:N`` or ``tcp://HOST:PORT`` (:func:`parse_scheduler`).
    retries, chunk : int, optional
        As in :class:`DaskExecutor`.

    Yields
    ------
    DaskExecutor
        On the cluster; a local cluster is closed, and the client of an existing one
        disconnected, at the end of the ``with``.

    Raises
    ------
    DistributedError
        When the spec is wrong, Dask is not installed (the message names the extra to
        install), a ``tls://`` scheduler is named without Dask's TLS settings, or the
        cluster does not answer within :data:`CONNECT_SECONDS`.
    """
    target = parse_scheduler(spec)
    try:
        import distributed  # noqa: F401 - only whether Dask is installed
    except ImportError:
        raise DistributedError(Message("dist.missing", {
            "spec": spec, "install": "pip install 'assur[distributed]'",
            "clone": "pip install -e '.[distributed]'"})) from None
    import dask

    cluster: LocalCluster | None = None
    client: Client | None = None
    _quiet_cancel_race()
    # the local workers, restarted ones included, are forked from a server that ignores
    # Ctrl-C (:func:`_start_fork_server`)
    with dask.config.set({METHOD: "forkserver"} if isinstance(target, int) else {}):
        try:
            with _ctrl_c_held():
                cluster, client = _start(spec, target)
            yield DaskExecutor(client, retries=retries, chunk=chunk)
        finally:
            with _ctrl_c_held():
                if client is not None:
                    client.close()
                if cluster is not None:
                    cluster.close()


class _CancelRace(logging.Filter):
    """Drops the one traceback Dask's event loop logs when Ctrl-C strikes a call to the
    cluster before that call's future exists: the cancel callback of ``distributed.utils.sync``
    then reads its unset variable ``future`` (a ``NameError``, logged by tornado as "Exception
    in callback"). The run itself ends as interrupted (exit 130); every other record passes.

    >>> import logging
    >>> def record(exc: BaseException) -> logging.LogRecord:
    ...     return logging.LogRecord("tornado.application", logging.ERROR, __file__, 1,
    ...                              "Exception in callback", None, (type(exc), exc, None))
    >>> race = NameError("cannot access free variable 'future' where it is not associated "
    ...                  "with a value in enclosing scope")
    >>> _CancelRace().filter(record(race)), _CancelRace().filter(record(NameError("x")))
    (False, True)
    """

    def filter(self, record: logging.LogRecord) -> bool:
        error = record.exc_info[1] if record.exc_info else None
        return not (isinstance(error, NameError) and "'future'" in str(error))


def _quiet_cancel_race() -> None:
    """Install :class:`_CancelRace` on tornado's callback logger, once."""
    logger = logging.getLogger("tornado.application")
    if not any(isinstance(f, _CancelRace) for f in logger.filters):
        logger.addFilter(_CancelRace())


def _start(spec: str, target: int | str) -> tuple[LocalCluster | None, Client]:
    """The local cluster (None for an existing one) and the client of :func:`connect`."""
    import dask
    from distributed import Client, LocalCluster

    if isinstance(target, int):
        # no dashboard; the scheduler's other web routes on a free port. Dask's eager
        # return of freed memory to the system (MALLOC_TRIM_THRESHOLD_) makes every large
        # temporary array of an evaluation a fresh mapping: twice the page faults, about
        # 1.3 times the CPU time of a block (docs/scale.md); the workers here go without it.
        _start_fork_server()
        with dask.config.set({TRIM: None}):
            cluster = LocalCluster(n_workers=target, threads_per_worker=1, processes=True,
                                   dashboard_address=None, silence_logs=logging.ERROR,
                                   scheduler_kwargs={"dashboard_address": ":0"})
        try:
            return cluster, Client(cluster)
        except BaseException:
            cluster.close()
            raise
    missing = [name for name in TLS_SETTINGS if not dask.config.get(name, None)]
    if target.startswith("tls://") and missing:
        raise DistributedError(Message("dist.tls", {"spec": spec, "missing": ", ".join(missing)}))
    try:
        return None, Client(target, timeout=CONNECT_SECONDS)
    except (OSError, TimeoutError, TypeError, ValueError) as exc:
        # refused, unreachable, silent, or a TLS configuration Dask cannot use
        raise DistributedError(Message("dist.connect", {
            "spec": spec, "seconds": CONNECT_SECONDS,
            "reason": f"{type(exc).__name__}: {exc}"})) from None


def _start_fork_server() -> None:
    """Start the server the local workers are forked from, with Ctrl-C ignored.

    A process started with SIGINT ignored keeps ignoring it (Python installs its handler
    only over the default action), and so does every worker forked from the server: a
    Ctrl-C of the terminal, sent to the whole process group, then stops this process
    alone, which cancels the tasks and closes the workers. Workers spawned afresh would
    print a ``KeyboardInterrupt`` traceback each. Outside the main thread the server is
    started as it is.
    """
    import multiprocessing.forkserver

    from distributed.utils import get_mp_context

    get_mp_context()  # the modules preloaded by the server
    if threading.current_thread() is not threading.main_thread():
        multiprocessing.forkserver.ensure_running()
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        multiprocessing.forkserver.ensure_running()
    finally:
        signal.signal(signal.SIGINT, previous)


@contextmanager
def _ctrl_c_held() -> Iterator[None]:
    """Hold Ctrl-C while a cluster starts or stops; a press counts when the block ends.

    A cluster half started or half closed when Ctrl-C struck would be left to Dask's exit
    handlers, which fail with tracebacks. A press meanwhile is noted, and handed to the
    handler that was in place (the command's, which ends the run with exit code 130) once
    the block is over. Outside the main thread, where no Ctrl-C is delivered, nothing
    changes.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    pressed: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda signum, _frame: pressed.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if pressed and callable(previous):
            previous(signal.SIGINT, None)
        elif pressed and previous == signal.SIG_DFL:
            raise KeyboardInterrupt


def executor_for(spec: str | None) -> AbstractContextManager[DaskExecutor | None]:
    """:func:`connect` to ``spec``, or no executor (this process) when ``spec`` is None.

    Parameters
    ----------
    spec : str or None
        The ``--scheduler`` option.

    Returns
    -------
    context manager
        Gives a :class:`DaskExecutor`, or None; Dask is imported only in the first case.
    """
    return nullcontext() if spec is None else connect(spec)
