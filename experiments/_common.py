"""What every experiment script shares: its command line, its worker pool and how it writes outputs.

An experiment is a script ``experiments/<name>.py`` with ``main(argv)`` that writes
data to ``results/`` and figures to ``paper_figs/`` (one rule per result: a figure
is drawn from the data, see docs/architecture.md).  Every output carries its
provenance (:mod:`equimesh.io.provenance`): a CSV has ``<name>.provenance.json``
beside it and its Markdown report ends with the same record; a figure is written
as PNG and PDF with ``<name>.provenance.json`` beside them.  All writes are
atomic, and the PNG/PDF carry no timestamp, so equal inputs give equal bytes.

The scripts import this module as ``_common``.  Run as ``python experiments/x.py``
the folder is on ``sys.path`` already; loaded by file path (``equimesh table1``,
the benchmarks) each script first puts its own folder there.
"""

import argparse
import math
import re
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from equimesh.io._atomic import atomic_path, atomic_write_text
from equimesh.io.provenance import provenance_markdown, provenance_path, write_provenance

#: Figure formats and the metadata that would otherwise stamp the date or the
#: matplotlib version into the file.
FIGURE_FORMATS = ((".png", {"Software": None}), (".pdf", {"CreationDate": None}))


# --------------------------------------------------------------------------- command line


def parser(doc):
    """An argument parser whose description is the first paragraph of the script's docstring ``doc``."""
    return argparse.ArgumentParser(
        description=doc.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter
    )


def add_output_options(p, *, out_dir=True, fig_dir=True, jobs=False, plot_only=False):
    """The options experiments share: ``--out-dir``, ``--fig-dir``, ``--jobs``, ``--plot-only``."""
    if out_dir:
        p.add_argument("--out-dir", type=Path, default=Path("results"), help="data folder (default results)")
    if fig_dir:
        p.add_argument("--fig-dir", type=Path, default=Path("paper_figs"), help="figure folder (default paper_figs)")
    if jobs:
        p.add_argument("--jobs", type=int, default=2, help="worker processes (default 2; 1 runs in-process)")
        p.add_argument(
            "--scheduler",
            type=scheduler,
            default="local",
            help="where the cases run: local (a pool of --jobs processes, default), dask (a dask.distributed "
            "LocalCluster of --jobs workers) or tcp://HOST:PORT (a running Dask scheduler); same results on each",
        )
    if plot_only:
        p.add_argument("--plot-only", action="store_true", help="only redraw the figures from the existing CSV")
    return p


# --------------------------------------------------------------------------- computing


def scheduler(value):
    """The ``--scheduler`` option: ``local``, ``dask`` or the address ``tcp://HOST:PORT`` of a Dask scheduler."""
    if value in ("local", "dask") or re.fullmatch(r"tcp://[^\s/:]+:\d{1,5}", value):
        return value
    raise argparse.ArgumentTypeError(f"unknown scheduler {value!r}; use local, dask or tcp://HOST:PORT")


#: How long to wait for a Dask scheduler at ``tcp://HOST:PORT`` to answer.
CONNECT_TIMEOUT = "10s"
#: At most about this many Dask tasks per map: cases are batched so that a
#: sweep of 10^5 polygons does not flood the scheduler with 10^5 futures.
MAX_DASK_TASKS = 1000


def parallel_map(function, items, jobs, chunksize=1, scheduler="local"):
    """``function`` over ``items``, results in the order of ``items`` whatever ``jobs`` and ``scheduler`` are.

    ``scheduler="local"``: ``jobs <= 1`` runs in this process, otherwise
    ``jobs`` worker processes (``function`` must then be importable by name,
    i.e. defined at module level).  ``"dask"`` or ``"tcp://HOST:PORT"``: see
    :func:`dask_map`.  Every case is computed by the same code from the same
    inputs, so the results are identical bit for bit on every scheduler.
    """
    if scheduler != "local":
        yield from dask_map(function, items, jobs, chunksize, scheduler)
        return
    if jobs <= 1:
        yield from map(function, items)
        return
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        yield from pool.map(function, items, chunksize=chunksize)


def dask_map(function, items, jobs, chunksize, scheduler):
    """:func:`parallel_map` on Dask: a LocalCluster of ``jobs`` single-threaded workers, or the scheduler at an address.

    ``function``'s module (the experiment script) and this one are sent to the
    workers by value (cloudpickle), so a worker needs equimesh installed but
    not the experiments folder.  Cases go in batches of at least ``chunksize``
    (at most about :data:`MAX_DASK_TASKS` tasks).  A missing dask or an
    unreachable address ends the script with a one-line message (exit 1)
    before anything is written.
    """
    try:
        import cloudpickle
        from distributed import Client, LocalCluster
    except ImportError:
        raise SystemExit(f"--scheduler {scheduler} needs dask.distributed: pip install 'equimesh[dask]'") from None
    for name in {function.__module__, __name__} - {"__main__"}:
        cloudpickle.register_pickle_by_value(sys.modules[name])
    items = list(items)
    size = max(chunksize, math.ceil(len(items) / MAX_DASK_TASKS))
    batches = [items[i : i + size] for i in range(0, len(items), size)]
    if scheduler == "dask":
        cluster = LocalCluster(n_workers=max(jobs, 1), threads_per_worker=1, dashboard_address=None)
    else:
        cluster = None
    try:
        try:
            client = Client(cluster or scheduler, timeout=CONNECT_TIMEOUT)
        except (OSError, TimeoutError):
            raise SystemExit(f"--scheduler {scheduler}: no Dask scheduler answered within {CONNECT_TIMEOUT}") from None
        with client:
            for future in client.map(_apply, batches, function=function, pure=False):
                yield from future.result()
    finally:
        if cluster is not None:
            cluster.close()


def _apply(batch, function):
    """``[function(item) for item in batch]``: one Dask task."""
    return [function(item) for item in batch]


def timed(function, *args, **kwargs):
    """``(function(*args, **kwargs), wall-clock seconds)``."""
    start = time.perf_counter()
    out = function(*args, **kwargs)
    return out, time.perf_counter() - start


# --------------------------------------------------------------------------- outputs


def write_results(csv_path, frame, parameters, report, float_format="%.17g"):
    """Write ``frame`` as CSV, its provenance JSON beside it, and the Markdown ``report(record)``.

    The report goes to ``csv_path`` with suffix ``.md``; ``report`` receives the
    provenance record (see :func:`markdown_report`).  Returns the record.
    """
    csv_path = Path(csv_path)
    with atomic_path(csv_path) as tmp:
        frame.to_csv(tmp, index=False, float_format=float_format)
    record = write_provenance(provenance_path(csv_path), parameters)
    atomic_write_text(csv_path.with_suffix(".md"), report(record))
    return record


def markdown_report(title, generated_by, body, record):
    """A Markdown report: title, "Generated by ...; do not edit by hand.", ``body`` lines, provenance section."""
    lines = [
        f"# {title}",
        "",
        f"Generated by {generated_by}; do not edit by hand.",
        "",
        *body,
        "",
        *provenance_markdown(record),
    ]
    return "\n".join(lines) + "\n"


def save_figure(fig, path, parameters, **savefig):
    """Write ``fig`` as ``path`` with suffix .png and .pdf, and ``<stem>.provenance.json`` beside them.

    ``savefig`` goes to :meth:`matplotlib.figure.Figure.savefig` (``dpi``,
    ``bbox_inches``, ...).  The provenance parameters are ``parameters`` plus
    ``outputs``, the files written.  Returns those file names.
    """
    path = Path(path)
    outputs = []
    for suffix, metadata in FIGURE_FORMATS:
        out = path.with_suffix(suffix)
        with atomic_path(out) as tmp:
            fig.savefig(tmp, metadata=metadata, **savefig)
        outputs.append(str(out))
    write_provenance(provenance_path(path), {**parameters, "outputs": outputs})
    return outputs
