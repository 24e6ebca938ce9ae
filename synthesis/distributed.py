"""Evaluation on a Dask cluster: the LPτ blocks of a search, the files of a batch.

Optional: it needs the extra ``distributed`` (``pip install -e '.[distributed]'``). Dask is
imported only when a cluster is asked for (:func:`connect`); the default single-process path
never imports it.

A scheduler is named as on the command line (``--scheduler``):

* ``local:N``: a :class:`distributed.LocalCluster` of N worker processes (one thread each)
  on this machine, closed at the end of the run;
* ``tcp://HOST:PORT`` (or ``tls://…``): an existing cluster; its workers must have the same
  versions of this program and of NumPy/SciPy, and see the files of a batch.

:class:`DaskExecutor` has the ``map(fn, items)`` of :class:`synthesis.search.Executor`: it
submits the items as tasks (a window of them ahead of the consumer), and yields the results
in the order of the items whatever the order in which the tasks finish. The search then
draws its blocks from the seed and reduces them in a fixed order, so a run on a cluster
gives the same design, bit for bit, as the run in one process. The tasks are pure: a task
lost with its worker is run again (Dask's rescheduling; ``retries`` more times if it
raises), and the result does not change. When the consumer stops early (a stop rule,
Ctrl-C) the tasks still pending are cancelled.
"""

from __future__ import annotations

import itertools
import logging
import uuid
from collections import deque
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import AbstractContextManager, contextmanager, nullcontext
from typing import TYPE_CHECKING, TypeVar

from assur.errors import AssurError
from assur.text import Message

if TYPE_CHECKING:
    from distributed import Client, Future

__all__ = ["DaskExecutor", "DistributedError", "connect", "executor_for", "parse_scheduler"]

T = TypeVar("T")
R = TypeVar("R")

#: The prefix of a local cluster: ``local:N``.
LOCAL = "local:"
#: Address schemes of an existing cluster.
SCHEMES = ("tcp://", "tls://")
#: Worker threads per item of a task by default: with one LPτ block per task, Dask's client
#: and scheduler keep pace with about 15 workers (``docs/scale.md``); 8 leaves a margin.
THREADS_PER_ITEM = 8
#: Dask's setting of the workers' memory trimming (unset for a local cluster).
TRIM = "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_"


class DistributedError(AssurError):
    """A scheduler cannot be used: not installed, misnamed or unreachable (exit code 2)."""

    def __init__(self, message: Message) -> None:
        self.message = message
        super().__init__(message.text("en"))

    def text(self, lang: str = "en") -> str:
        """The sentence in ``lang``."""
        return self.message.text(lang)


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
        When ``spec`` is neither ``local:N`` (N ≥ 1) nor ``tcp://HOST:PORT``.

    Examples
    --------
    >>> parse_scheduler("local:4"), parse_scheduler("tcp://10.0.0.5:8786")
    (4, 'tcp://10.0.0.5:8786')
    >>> parse_scheduler("local:0")
    Traceback (most recent call last):
    ...
    synthesis.distributed.DistributedError: --scheduler expects 'local:N' (N workers on this \
machine, N ≥ 1) or 'tcp://HOST:PORT' (an existing Dask cluster); found 'local:0'
    """
    if spec.startswith(LOCAL):
        count = spec[len(LOCAL):]
        if count.isdigit() and int(count) >= 1:
            return int(count)
    elif spec.startswith(SCHEMES) and spec.partition("://")[2]:
        return spec
    raise DistributedError(Message("dist.scheduler", {"found": spec}))


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

        ``fn`` is sent to every worker once; the items are drawn lazily, a window of tasks
        ahead of the consumer. Closing the iterator (or an exception in the consumer, such
        as Ctrl-C) cancels the tasks not yet consumed.
        """
        client = self.client
        threads = max(1, sum(client.nthreads().values()))
        ahead = self.ahead or 2 * threads
        chunk = self.chunk or -(-threads // THREADS_PER_ITEM)
        function = client.scatter(fn, broadcast=True, hash=False)
        run = uuid.uuid4().hex
        keys = (f"assur-{run}-{k}" for k in itertools.count())
        chunks = _chunks(items, max(1, chunk))
        pending: deque[Future[list[R]]] = deque()

        def submit() -> bool:
            part = next(chunks, None)
            if part is None:
                return False
            pending.append(client.submit(_apply, function, part, pure=False,
                                         retries=self.retries,
                                         key=next(keys)))
            return True

        try:
            while len(pending) < ahead and submit():
                pass
            while pending:
                results = pending.popleft().result()
                submit()
                yield from results
        finally:
            client.cancel([*pending, function])


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
        install), or the cluster cannot be reached.
    """
    target = parse_scheduler(spec)
    try:
        import dask
        from distributed import Client, LocalCluster
    except ImportError:
        raise DistributedError(Message("dist.missing", {
            "spec": spec, "install": "pip install 'assur[distributed]'",
            "clone": "pip install -e '.[distributed]'"})) from None
    if isinstance(target, int):
        # no dashboard; the scheduler's other web routes on a free port. Dask's eager
        # return of freed memory to the system (MALLOC_TRIM_THRESHOLD_) makes every large
        # temporary array of an evaluation a fresh mapping: twice the page faults, about
        # 1.3 times the CPU time of a block (docs/scale.md); the workers here go without it.
        with dask.config.set({TRIM: None}):
            cluster = LocalCluster(n_workers=target, threads_per_worker=1, processes=True,
                                   dashboard_address=None, silence_logs=logging.ERROR,
                                   scheduler_kwargs={"dashboard_address": ":0"})
        client = Client(cluster)
    else:
        cluster = None
        try:
            client = Client(target, timeout=10)
        except (OSError, TimeoutError) as exc:
            raise DistributedError(Message("dist.connect", {"address": target,
                                                            "reason": str(exc)})) from None
    try:
        yield DaskExecutor(client, retries=retries, chunk=chunk)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


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
