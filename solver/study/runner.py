"""Running a study's points on Dask (``dask.distributed``) and saving each run as it finishes.

:func:`run_study` submits the runs not yet finished in the study folder to a Dask client: one task
per dynamic run, and the quasi-static runs in batches (a quasi-static run takes tens of
milliseconds, about the cost of scheduling one task, so a batch holds enough runs to keep the
scheduling overhead small). Without a client it starts a ``LocalCluster`` of single-threaded
worker processes (one per core by default) and closes it at the end. Each worker loads the
compiled numba kernels from the on-disk cache once, when it starts (solver.study.worker).

Each run's NetCDF file and record are written atomically (solver.study.store) as soon as it
finishes, so a stop loses only the runs that were running: by the worker itself when it shares
this machine's file system (``shared_folder``; the default for the local cluster, so the writing
runs in parallel), otherwise by this process when the result comes back. A
run that fails (no quasi-static solution, diverged, invalid) is recorded with its message and the
others go on; a worker that dies has its tasks run again by Dask on the other workers. ``cancel``
(a ``threading.Event``) stops the study, also while the workers warm up: pending tasks are
cancelled, the local cluster is closed (quietly) and what is done is kept.

:func:`connect_scheduler` connects to an existing scheduler under one deadline that also covers
Dask's handshake, and refuses an address that is not ``tcp://HOST:PORT``.
"""

from __future__ import annotations

import contextlib
import logging
import math
import os
import threading
import time
import uuid
from dataclasses import dataclass

from solver.errors import CaseError, Problem

from .store import FAILED, StudyFolder

#: Quasi-static runs per task: at least this many ...
QS_BATCH_MIN = 4
#: ... and at most this many, so that every worker gets several batches.
QS_BATCH_MAX = 32
#: The address the local cluster listens on.
LOOPBACK = "127.0.0.1"
#: Longest wait for an existing scheduler to answer (connection and handshake), in seconds.
CONNECT_TIMEOUT_S = 30.0
#: Longest wait for the local workers to be told to log nothing before a stopped study closes them.
QUIET_WAIT_S = 5.0


@dataclass(frozen=True)
class Progress:
    """What :func:`run_study` reports to its ``progress`` callback after every change."""

    done: int  # runs finished (including failed) in this session
    failed: int
    running: int  # runs in tasks that a worker is executing (estimate: tasks in flight)
    total: int  # runs to do in this session
    skipped: int  # runs already finished before (resume)
    elapsed_s: float
    eta_s: float  # nan until the first run finishes
    last: str  # the last run finished, as "p0003 dynamic: done"


def _tasks(todo: list, workers: int) -> list[list]:
    """Group the runs to do: each dynamic run alone, quasi-static runs in batches."""
    dynamic = [t for t in todo if t[1] == "dynamic"]
    quasi = [t for t in todo if t[1] == "quasistatic"]
    tasks = [[t] for t in dynamic]
    if quasi:
        size = math.ceil(len(quasi) / max(4 * workers, 1))
        size = max(QS_BATCH_MIN, min(QS_BATCH_MAX, size))
        tasks = [quasi[i : i + size] for i in range(0, len(quasi), size)] + tasks
    return tasks


def start_local_cluster(workers: int | None = None):
    """A LocalCluster of ``workers`` single-threaded worker processes (default: one per core),
    and its Client.

    Everything listens on the loopback address only, each on a port the system chooses: the
    scheduler, the workers and the scheduler's HTTP dashboard (Dask always starts it; it is not
    used here and is never on a fixed port such as 8787), so several studies run side by side on
    one machine without a port clash or Dask's "port already in use" warning."""
    from dask.distributed import Client, LocalCluster

    n = workers or os.cpu_count() or 1
    cluster = LocalCluster(
        n_workers=n,
        threads_per_worker=1,
        processes=True,
        host=LOOPBACK,
        scheduler_port=0,
        dashboard_address=f"{LOOPBACK}:0",
        memory_limit=0,
        silence_logs=40,
    )
    return cluster, Client(cluster)


def scheduler_address(address: str) -> str:
    """``tcp://HOST:PORT`` of a Dask scheduler address given as ``tcp://HOST:PORT`` or
    ``HOST:PORT`` (an IPv6 host in brackets); CaseError (key ``scheduler``) naming the form
    otherwise (another scheme such as ``http://``, no host, no port, a port out of range)."""
    from urllib.parse import urlsplit

    def wrong(why: str) -> CaseError:
        return CaseError(
            Problem(
                "scheduler",
                f"--scheduler {address!r}: {why}; give the scheduler's address as tcp://HOST:PORT, "
                "e.g. tcp://head-node:8786",
            )
        )

    text = str(address).strip()
    if not text or any(c.isspace() or ord(c) < 32 for c in text):
        raise wrong("not an address")
    if "://" not in text:
        text = f"tcp://{text}"
    try:
        parts = urlsplit(text)
        port = parts.port
    except ValueError as error:
        raise wrong(str(error)) from None
    if parts.scheme != "tcp":
        raise wrong(f"{parts.scheme}:// is not a Dask scheduler protocol")
    if parts.path not in ("", "/") or parts.query or parts.fragment or parts.username:
        raise wrong("an address has only a host and a port")
    if not parts.hostname:
        raise wrong("no host")
    if port is None or port == 0:
        raise wrong("no port")
    host = f"[{parts.hostname}]" if ":" in parts.hostname else parts.hostname
    return f"tcp://{host}:{port}"


def connect_scheduler(address: str, timeout_s: float | None = None):
    """A ``dask.distributed.Client`` of the scheduler at ``address`` (see
    :func:`scheduler_address`), or CaseError within about ``timeout_s`` seconds (default
    :data:`CONNECT_TIMEOUT_S`).

    Connecting and Dask's handshake are first tried under one deadline (Dask's own timeout does
    not cover the handshake, so a server that accepts the connection and stays silent, or a web
    server, would hang forever); then the Client connects with the same timeout."""
    import asyncio

    from dask.distributed import Client
    from distributed.comm import connect

    address = scheduler_address(address)
    timeout_s = CONNECT_TIMEOUT_S if timeout_s is None else timeout_s

    def nobody(why: str) -> CaseError:
        return CaseError(
            Problem(
                "scheduler",
                f"no Dask scheduler answered at {address} within {timeout_s:g} s ({why}): check "
                "the address and that `dask scheduler` runs there",
            )
        )

    async def handshake() -> None:
        comm = await asyncio.wait_for(connect(address, timeout=timeout_s), timeout_s)
        try:
            if not isinstance(getattr(comm, "remote_info", None), dict):
                raise OSError("the server did not answer as Dask does")
        finally:
            comm.abort()

    try:
        asyncio.run(handshake())
    except TimeoutError:
        raise nobody("no answer") from None
    except Exception as error:  # noqa: BLE001 - whatever a foreign server makes Dask raise
        raise nobody(f"{type(error).__name__}: {error}") from None
    try:
        return Client(address, timeout=timeout_s)
    except Exception as error:  # noqa: BLE001
        raise nobody(f"{type(error).__name__}: {error}") from None


def run_study(
    spec,
    points,
    output,
    client=None,
    workers: int | None = None,
    resume: bool = False,
    progress=None,
    cancel=None,
    version: str = "",
    log=None,
    shared_folder: bool | None = None,
    inputs: dict | None = None,
    restart: bool = False,
    accept_solver_change: bool = False,
) -> StudyFolder:
    """Run every unfinished (point, model) of ``points`` and save them in ``output``.

    Returns the :class:`~solver.study.store.StudyFolder` (its Dataset holds what was done). See
    the module docstring for the client, cancel and saving rules. ``log``: callable(str) for
    one-line notes (skipped runs, warm-up). ``shared_folder``: the workers write the runs into
    the study folder themselves (default: True with the local cluster this function starts, False
    with a given client). ``inputs``, ``restart``, ``accept_solver_change``: what the folder
    records and checks on resume (:meth:`~solver.study.store.StudyFolder.start`).
    """
    from dask.distributed import wait

    from .worker import WarmUp, run_batch, warm_up_cases

    folder = StudyFolder(output)
    folder.start(
        spec,
        points,
        version,
        resume,
        inputs=inputs,
        restart=restart,
        accept_solver_change=accept_solver_change,
        log=log,
    )
    finished = folder.finished()
    todo = [
        (p.name, model, p.case)
        for p in points
        for model in p.models
        if (p.name, model) not in finished
    ]
    if finished and log is not None:
        failed = sum(1 for r in finished.values() if r.get("status") == FAILED)
        log(
            f"resume: {len(finished)} run(s) already finished in {folder.path} are skipped "
            f"({failed} of them failed; delete a point's .json record to run it again)"
        )
    own_cluster = None
    if not todo:
        folder.save_dataset()
        return folder
    if client is None:
        if log is not None:
            log(f"starting a local Dask cluster: {workers or os.cpu_count()} worker(s)")
        own_cluster, client = start_local_cluster(workers)
    if shared_folder is None:
        shared_folder = own_cluster is not None
    target = str(folder.path.resolve()) if shared_folder else None
    try:
        cases = warm_up_cases([p for p in points if any(t[0] == p.name for t in todo)])
        if log is not None:
            log(_warm_up_note(own_cluster is not None))
        if not _warm_up(client, WarmUp(cases), cancel):
            return folder
        n_workers = max(len(client.scheduler_info().get("workers", {})), 1)
        tasks = _tasks(todo, n_workers)
        total = len(todo)
        session = uuid.uuid4().hex[:8]  # keys unique per session: a cancelled key may linger
        futures = {
            client.submit(
                run_batch,
                task,
                target,
                pure=False,
                key=f"racetrace-{task[0][0]}-{task[0][1]}-{session}",
            ): task
            for task in tasks
        }
        pending = set(futures)
        done = failed = 0
        last = ""
        t0 = time.perf_counter()

        left = {m: sum(1 for t in todo if t[1] == m) for m in ("quasistatic", "dynamic")}
        times: dict[str, list[float]] = {"quasistatic": [], "dynamic": []}

        def report() -> None:
            if progress is None:
                return
            elapsed = time.perf_counter() - t0
            running = min(len(pending), n_workers)
            progress(Progress(done, failed, running, total, len(finished), elapsed, eta(), last))

        def eta() -> float:
            """Runs left of each model times that model's mean run time so far, shared by the
            workers (nan until a run of each model left has finished)."""
            work = 0.0
            for model, count in left.items():
                if count == 0:
                    continue
                if not times[model]:
                    return math.nan
                work += count * sum(times[model]) / len(times[model])
            return work / n_workers

        report()
        while pending:
            if cancel is not None and cancel.is_set():
                client.cancel(list(pending))
                break
            try:
                finished_now = wait(pending, timeout=0.5, return_when="FIRST_COMPLETED").done
            except TimeoutError:
                continue
            for future in finished_now:
                pending.discard(future)
                task = futures[future]
                try:
                    outcome = future.result()
                except Exception as error:  # noqa: BLE001 - a task that raised (or lost workers)
                    outcome = [
                        (
                            name,
                            model,
                            {
                                "status": FAILED,
                                "message": f"{type(error).__name__}: {error}",
                            },
                            None,
                        )
                        for name, model, _case in task
                    ]
                for name, model, record, ds in outcome:
                    if not record.get("saved"):
                        folder.save_run(name, model, record, ds)
                    done += 1
                    failed += record["status"] == FAILED
                    last = f"{name} {model}: {record['status']}"
                    left[model] -= 1
                    spent = record.get("wall_time_s")
                    if spent is not None:
                        times[model].append(spent + record.get("write_time_s", 0.0))
            report()
    finally:
        if own_cluster is not None:
            # after a stop the workers may be busy: Dask's complaints about closing them are noise
            stopped = cancel is not None and cancel.is_set()
            with _quiet_dask(stopped):
                if stopped:
                    _within(lambda: client.run(logging.disable, logging.CRITICAL), QUIET_WAIT_S)
                client.close()
                own_cluster.close()
        folder.save_dataset()
    return folder


def _warm_up_note(local: bool) -> str:
    """What the warm-up before the points does, as the log says it."""
    from solver.compiled import dynamic_model_compiled

    if local and dynamic_model_compiled():
        return "loading the compiled solver kernels on each worker before the points start"
    return (
        "compiling the solver kernels the study uses (first run only): one worker compiles, "
        "then the others load them, before the points start (not counted in the ETA)"
    )


def _warm_up(client, plugin, cancel) -> bool:
    """Warm the workers before the points start, checking ``cancel`` twice a second; False when
    cancelled first. One worker runs the warm-up of ``plugin`` (compiling the kernels into the
    shared cache on a first run: up to minutes), then the plugin is registered on every worker
    (which then loads the kernels from the cache, also a worker started later).

    Dask's calls wait for the workers and cannot be interrupted, so they run in a thread; an error
    they raise is raised here."""
    from .worker import warm_up

    errors: list[BaseException] = []

    def register() -> None:
        try:
            workers = sorted(client.scheduler_info().get("workers", {}))
            if len(workers) > 1:  # one compiles; the others would compile the same kernels
                client.run(warm_up, plugin.cases, workers=workers[:1])
            client.register_plugin(plugin)
        except BaseException as error:  # noqa: BLE001 - also the cancellation when closing
            errors.append(error)

    thread = threading.Thread(target=register, name="racetrace-warm-up", daemon=True)
    thread.start()
    while thread.is_alive():
        if cancel is not None and cancel.is_set():
            return False
        thread.join(0.5)
    if errors:
        raise errors[0]
    return True


def _within(call, seconds: float) -> None:
    """Call ``call()`` in a thread and wait at most ``seconds`` for it; its errors are ignored
    (used for courtesies to workers that may be gone)."""

    def run() -> None:
        try:
            call()
        except BaseException:  # noqa: BLE001, S110 - a courtesy: nothing to do if it fails
            pass

    thread = threading.Thread(target=run, name="racetrace-quiet", daemon=True)
    thread.start()
    thread.join(seconds)


@contextlib.contextmanager
def _quiet_dask(quiet: bool):
    """While active and ``quiet``: this process logs nothing (Dask's scheduler and nannies run in
    it and complain about closing busy workers); the workers are silenced by the caller."""
    if not quiet:
        yield
        return
    previous = logging.root.manager.disable
    logging.disable(logging.CRITICAL)
    try:
        yield
    finally:
        logging.disable(previous)
