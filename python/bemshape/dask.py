"""Many parts checked on a dask.distributed cluster: the Python side of `bemshape check-all`.

    import bemshape.dask
    summary = bemshape.dask.check_parts(paths, min_thickness=1.0, max_edge=2.0)

check_parts maps check_part over the paths on a dask.distributed Client: a LocalCluster of
worker processes on this machine (loopback only) unless a client is given, or any cluster a
Client is connected to (`dask scheduler` and `dask worker` on several machines;
docs/usage.md, "Many parts on a Dask cluster"). Each task runs the library in its worker
(bemshape.read_mesh, bemshape.thickness; the GIL is released during the job) and returns
one record, the fields of a line of check-all's JSON-lines summary (apps/part_summary.hpp):

    part, verdict ("pass", "thin", "error", "timeout"), exit_code (what `bemshape thickness`
    exits with for that part), threshold, min_thickness, min_location, regions, thin_area,
    h0, units_warning, seconds, peak_mb, error, report (the thickness report as a dict with
    keep_reports=True, else None), resumed (always False here).

A part's own problem (unreadable file, a mesh that bounds no solid, memory refused, no
convergence, its timeout) is its record's verdict and error, never an exception: the other
parts go on. Only dask.distributed and the standard library are needed (no pandas).
"""
import contextlib
import os
import sys
import time
from urllib.parse import urlparse

import bemshape

# Share of a worker's memory limit its tasks may give bemshape's memory guard (max_memory),
# divided among the worker's threads: dask.distributed's default pause threshold
# (distributed.worker.memory.pause). Above it the worker starts no task, at 0.95 its nanny
# kills it; a part that needs more is refused by the guard with a message instead.
WORKER_MEMORY_SHARE = 0.8

# The exit codes of `bemshape thickness` (apps/exit_codes.hpp), for the records.
_EXIT_PASS, _EXIT_THIN, _EXIT_BAD_INPUT, _EXIT_FAILED = 0, 1, 2, 3

# The keywords of bemshape.thickness that check_part sets itself.
_SET_BY_CHECK_PART = ("progress", "name")


class _PartTimeout(Exception):
    """Raised from a part's progress callback when its timeout has passed."""


def _reset_peak_memory():
    """Starts a new peak of this process's resident memory (Linux: VmHWM), so that a
    report's peak_mb is the part's own, not that of an earlier task in the same worker."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:
        pass  # the peak then covers the worker's earlier tasks too


def _peak_mb():
    """Peak resident memory of this process [MB, 10^6 bytes] (VmHWM), None if unknown."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) * 1024 / 1e6
    except OSError:
        pass
    return None


def _record_without_report(part, verdict, error, exit_code, threshold, seconds, peak_mb):
    return {
        "part": part,
        "verdict": verdict,
        "exit_code": exit_code,
        "threshold": threshold,
        "min_thickness": None,
        "min_location": None,
        "regions": None,
        "thin_area": None,
        "h0": None,
        "units_warning": None,
        "seconds": seconds,
        "peak_mb": peak_mb,
        "error": error,
        "report": None,
        "resumed": False,
    }


def summary_record(part, report, keep_report=False):
    """The record of a part from its thickness report (a dict: thickness(...)["report"], or
    the JSON `bemshape thickness --report` writes) made with min_thickness."""
    check = report["check"]
    return {
        "part": part,
        "verdict": "pass" if check["pass"] else "thin",
        "exit_code": _EXIT_PASS if check["pass"] else _EXIT_THIN,
        "threshold": check["threshold"],
        "min_thickness": report["thickness"]["min"],
        "min_location": list(report["thickness"]["min_location"]),
        "regions": len(check["regions"]),
        "thin_area": check["thin_area"],
        "h0": report["parameters"]["h0"],
        "units_warning": report["units_warning"],
        "seconds": report["timing"]["total"],
        "peak_mb": report["memory"]["peak_mb"],
        "error": None,
        "report": report if keep_report else None,
        "resumed": False,
    }


def check_part(path, *, min_thickness, timeout=None, keep_report=False, **options):
    """The record of one part, checked in this process: bemshape.read_mesh(path), then
    bemshape.thickness(V, F, min_thickness=..., **options) with its report.

    options: the keywords of bemshape.thickness (h0, max_edge, measure, threads,
    max_memory, ...). timeout: seconds the part may take (checked at the library's progress
    reports, at most 0.05 s apart; like Ctrl-C, it stops every bemshape call running in
    this process). Raises TypeError for an unknown keyword; everything about the part itself
    ends up in the record."""
    part = os.fspath(path)
    unknown = set(options) & set(_SET_BY_CHECK_PART)
    if unknown:
        raise TypeError(f"check_part sets {', '.join(sorted(unknown))} itself")
    start = time.monotonic()
    deadline = None if timeout is None else start + timeout

    def progress(stage, fraction):
        if deadline is not None and time.monotonic() > deadline:
            raise _PartTimeout(stage)

    _reset_peak_memory()

    def failed(verdict, error, exit_code):
        return _record_without_report(part, verdict, error, exit_code, min_thickness,
                                      time.monotonic() - start, _peak_mb())

    try:
        V, F = bemshape.read_mesh(part)
        result = bemshape.thickness(V, F, min_thickness=min_thickness, progress=progress,
                                    name=part, **options)
    except _PartTimeout as stopped:
        return failed("timeout", f"time limit of {timeout:g} s (timeout) reached in stage "
                      f"'{stopped}'; stopped cleanly", _EXIT_FAILED)
    except (ValueError, MemoryError) as error:  # bemshape.InputError, bemshape.ResourceError
        return failed("error", str(error), _EXIT_BAD_INPUT)
    except TypeError:
        raise  # a wrong keyword: the caller's mistake, the same for every part
    except Exception as error:  # bemshape.NumericalError and anything unforeseen
        return failed("error", str(error) or repr(error), _EXIT_FAILED)
    return summary_record(part, result["report"], keep_report)


def _worker_share():
    """(threads, max_memory) of one task on this worker: its machine's cores divided among
    the worker's threads and those of the other workers on the same machine (as the client
    counted them), and WORKER_MEMORY_SHARE of its memory limit divided among its threads."""
    from distributed import get_worker

    worker = get_worker()
    # Where distributed keeps them since 2022.8 (worker.state, worker.memory_manager), else
    # the older attributes.
    state = getattr(worker, "state", worker)
    nthreads = max(1, state.nthreads)
    limit = getattr(getattr(worker, "memory_manager", worker), "memory_limit", None)
    memory = WORKER_MEMORY_SHARE * limit / nthreads if limit else None
    return nthreads, memory


def _check_part_on_worker(path, threads_by_worker, min_thickness, timeout, keep_report,
                          options):
    from distributed import get_worker

    nthreads, memory = _worker_share()
    options = dict(options)
    if options.get("threads") is None:
        options["threads"] = threads_by_worker.get(
            get_worker().address, max(1, len(os.sched_getaffinity(0)) // nthreads))
    if options.get("max_memory") is None and memory is not None:
        options["max_memory"] = memory
    return check_part(path, min_thickness=min_thickness, timeout=timeout,
                      keep_report=keep_report, **options)


def _cpu_count():
    return len(os.sched_getaffinity(0))


def _threads_by_worker(client):
    """OpenMP threads per task for every worker: its machine's cores divided among all task
    slots (worker threads) on that machine, at least 1."""
    workers = client.scheduler_info()["workers"]
    cores = client.run(_cpu_count)
    slots = {}
    for address, info in workers.items():
        host = urlparse(address).hostname
        slots[host] = slots.get(host, 0) + info["nthreads"]
    return {address: max(1, cores.get(address, 1) // slots[urlparse(address).hostname])
            for address in workers}


@contextlib.contextmanager
def _main_without_unreadable_file():
    """A LocalCluster's worker processes are started by multiprocessing's spawn, which runs
    the main module's file again in each (as __mp_main__). A program read from standard input
    (`python3 - <<EOF`) has the file name "<stdin>", which spawn cannot open, and every
    worker would fail to start: its name is hidden while the cluster lives. The workers need
    nothing from the main module (the tasks are functions of bemshape.dask)."""
    main = sys.modules.get("__main__")
    name = getattr(main, "__file__", None)
    hide = name is not None and not os.path.isfile(name)
    if hide:
        del main.__file__
    try:
        yield
    finally:
        if hide:
            main.__file__ = name


def check_parts(paths, client=None, *, min_thickness, jobs=None, timeout=None,
                keep_reports=False, **options):
    """The records of the parts `paths` (in their order), checked on a dask.distributed
    cluster; see the module's doc for the fields.

    client: a distributed.Client; None starts a LocalCluster of `jobs` worker processes
        (default: one per core) with one thread each, on 127.0.0.1 only, for this call.
    min_thickness: the check's threshold (required). timeout: seconds per part.
    options: the keywords of bemshape.thickness (h0, max_edge, measure, a, ...). threads
        (OpenMP threads per task) defaults to the cores of the worker's machine divided
        among the task slots there; max_memory (bytes) to WORKER_MEMORY_SHARE of the
        worker's memory limit divided among its threads.
    keep_reports: put each part's thickness report (a dict) in its record.

    A task that fails on the cluster (its worker died on it three times, say) gives a record
    with verdict "error"; Ctrl-C cancels the tasks and, for a cluster of its own, stops it.
    """
    from distributed import Client, LocalCluster

    paths = [os.fspath(p) for p in paths]
    unknown = set(options) & set(_SET_BY_CHECK_PART)
    if unknown:
        raise TypeError(f"check_parts sets {', '.join(sorted(unknown))} itself")
    with contextlib.ExitStack() as own:
        if client is None:
            own.enter_context(_main_without_unreadable_file())
            cluster = own.enter_context(LocalCluster(
                n_workers=jobs or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                host="127.0.0.1", dashboard_address=None))
            client = own.enter_context(Client(cluster))
        return _map_parts(client, paths, min_thickness, timeout, keep_reports, options)


def _map_parts(client, paths, min_thickness, timeout, keep_reports, options):
    futures = []
    try:
        threads = _threads_by_worker(client)
        futures = client.map(_check_part_on_worker, paths, pure=False,
                             threads_by_worker=threads, min_thickness=min_thickness,
                             timeout=timeout, keep_report=keep_reports, options=options)
        records = []
        for path, future in zip(paths, futures):
            try:
                records.append(future.result())
            except Exception as error:
                records.append(_record_without_report(
                    path, "error", f"the task failed on the cluster: {error!r}", _EXIT_FAILED,
                    min_thickness, None, None))
        return records
    except BaseException:
        if futures:
            client.cancel(futures)
        raise
