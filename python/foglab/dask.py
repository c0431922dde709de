"""A fleet of gyros on a Dask cluster: ``foglab batch`` with each recording on a worker.

``batch(client, inputs, out, **options)`` analyses every recording of ``inputs`` (files,
folders or globs, as ``foglab batch`` takes them) on the workers of a ``dask.distributed``
client, one task a recording, and gathers the results where the client runs: each unit's
``analyze --json`` document into ``out/units/NAME.json`` as it arrives, then the fleet report
(``out/fleet.json``, ``fleet.csv``, ``fleet.md``, ``fleet.html``) by the same code as the
command. The options are ``foglab.batch``'s (channel, rate_hz, units, taus, temp_degree, ...).

The workers read the recordings themselves: the paths must mean the same files on every
worker (a shared file system, or a LocalCluster). Only the JSON documents (about 50 kB a unit)
travel back. foglab must be importable on the workers (``pip install .`` on each machine, or
the same environment).

A rerun resumes as the command does: units already in ``out/units`` (same file, same
options) are not sent to the workers again. A recording that fails on a worker is analysed
once more where the client runs when the report is written, and listed with its error.

Example, on one machine's cores or on a cluster::

    from dask.distributed import Client, LocalCluster
    import foglab.dask

    client = Client(LocalCluster(n_workers=4, threads_per_worker=1))
    # or a running scheduler: Client("tcp://scheduler.lab:8786")
    fleet = foglab.dask.batch(client, ["/data/fleet/*.mat"], "/data/fleet-report")
    print(fleet["fleet"]["outliers"])
"""

import os
import sys
import tempfile

from . import _foglab


def _units_of_file(path, name, options):
    """A worker's task: one recording's units, analysed there (nothing written)."""
    from . import _foglab as core  # imported on the worker

    return core._batch_file_units(path, name, **options)


def _write_whole(path, text):
    """Writes ``text`` to ``path`` through a temporary beside it, renamed into place."""
    folder = os.path.dirname(path)
    handle, temporary = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", dir=folder,
                                         suffix=".tmp")
    try:
        with os.fdopen(handle, "w", encoding="utf-8") as stream:
            stream.write(text)
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise


def batch(client, inputs, out, progress=False, **options):
    """Analyses the recordings of ``inputs`` on ``client``'s workers and writes the fleet report
    to ``out``; returns the fleet.json document (a dict). ``progress``: a line on stderr for
    each recording that comes back."""
    from dask.distributed import as_completed

    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    inputs = [os.fspath(i) for i in inputs]
    out = os.fspath(out)
    files = _foglab._batch_files(inputs)
    units_dir = os.path.join(out, "units")
    os.makedirs(units_dir, exist_ok=True)
    # Recordings whose units an earlier run left, by the command's own rule (same file, not
    # modified since, same options), are not sent to the workers.
    rule = {k: v for k, v in options.items() if k != "redo"}
    todo = [(path, name) for path, name in files
            if options.get("redo") or not _foglab._batch_file_kept(path, name, units_dir, **rule)]
    futures = client.map(_units_of_file, [p for p, _ in todo], [n for _, n in todo],
                         options=options, pure=False)
    done = 0
    for future in as_completed(futures):
        units = future.result()
        done += 1
        for unit in units:
            if unit["json"]:
                _write_whole(os.path.join(units_dir, unit["name"] + ".json"), unit["json"])
        if progress:
            names = ", ".join(u["name"] + ("" if u["json"] else " failed") for u in units)
            print(f"foglab: [{done}/{len(todo)}] {names}", file=sys.stderr)
    kept = dict(options)
    kept.pop("redo", None)  # the units just written stand
    return _foglab.batch(inputs, out, **kept)

