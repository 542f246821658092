"""oms.batch(): LODs for a library of assets, each run by the skinned-decimate tool in a process of its own,
here (``jobs`` at a time) or as one task per asset on a Dask cluster."""

import json
import os
import shutil

from . import _core

#: Where the build or the install put the tool (set by CMake; see _tool_paths.py).
try:
    from ._tool_paths import TOOL_PATHS as _TOOL_PATHS
except ImportError:  # pragma: no cover - a copy of the package without CMake's file
    _TOOL_PATHS = ()


def tool_path():
    """The skinned-decimate program batch() runs: $OMSK_SKINNED_DECIMATE, else the one installed with this
    package (or built beside it), else the first on PATH. Raises FileError when there is none."""
    candidates = [os.environ.get("OMSK_SKINNED_DECIMATE"), *_TOOL_PATHS, shutil.which("skinned-decimate")]
    for c in candidates:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    raise _core.FileError("skinned-decimate: not found (set OMSK_SKINNED_DECIMATE to the program)")


def _run_one(path, name, settings):
    # One Dask task: the worker imports this package and runs the tool on the asset, as run_batch() would.
    from . import _core as core

    return core._run_asset(path, name, settings)


def batch(paths, out_dir, jobs=1, client=None, *, html=False, force=False, asset_time_limit=0.0, progress=None,
          executable=None, **options):
    """Makes the LODs of every asset in ``paths`` (a list of files, or one folder: every file below it a reader
    takes, a numbered OBJ/PLY/STL/OFF sequence as one asset) into ``out_dir``, each asset run by the
    skinned-decimate tool in a process of its own, so that one that crashes, runs out of memory or hangs fails
    alone. Returns one dict per asset, in the order of the inputs: ``input``, ``name``, ``status`` ("ok",
    "failed", "skipped"), ``reason`` (a failure's one line), ``seconds``, ``triangles_in``, ``lods`` (``ratio``,
    ``triangles``, ``heldout_rms``, ``heldout_hausdorff`` (None: not measured), ``file``), ``log``, ``report``,
    ``page``; and writes ``out_dir/summary.json`` and ``out_dir/index.html``.

    Per asset NAME (its path below the inputs' common folder, without its extension): NAME.glb (NAME_lod1.glb
    ... for several ratios), NAME.report.json, NAME.log, NAME.batch.json, and with ``html=True`` NAME.html. An
    asset whose outputs are newer than it and were made by the same tool with the same options is skipped
    (``force=True`` runs it again). ``asset_time_limit``: seconds one asset may take (0: no limit).

    ``options``: make_lods()'s keywords (not per_vertex_error), passed to the tool as its command line
    options. ``jobs``: assets run at the same time here. ``client``: a ``distributed.Client``; then each asset
    is one task on its cluster, every worker runs the tool itself (``executable``, by default tool_path() as
    found here, must be that path on the workers too), and ``out_dir`` must be the same shared folder on all
    of them; the summary is written here. ``progress(done, total, result)`` after each asset (local runs only;
    returning False stops: the assets not finished fail as "cancelled").

    Raises OptionsError or TypeError for bad options (before anything runs), FileError when the output folder
    cannot be made or the tool cannot be started.
    """
    arguments = _core._tool_arguments(**options)
    out_dir = os.fspath(out_dir)
    if isinstance(paths, (str, os.PathLike)):
        folder = os.fspath(paths)
        if not os.path.isdir(folder):
            raise _core.FileError(folder + ": not a folder (give a folder or a list of files)")
        inputs = _core._find_inputs(folder, out_dir, "--no-sequence" not in arguments)
    else:
        inputs = _core._batch_inputs([os.fspath(p) for p in paths])
    if not inputs:
        raise _core.FileError("batch: no input: no file a reader takes")
    try:
        os.makedirs(out_dir, exist_ok=True)
    except OSError as e:
        raise _core.FileError(f"{out_dir}: cannot be made: {e.strerror}") from None
    settings = {
        "executable": os.fspath(executable) if executable else tool_path(),
        "out_dir": out_dir,
        "jobs": int(jobs),
        "arguments": arguments,
        "html": bool(html),
        "force": bool(force),
        "asset_time_limit": float(asset_time_limit),
    }
    if client is None:
        report = None if progress is None else lambda done, total, r: progress(done, total, json.loads(r))
        results = _core._run_batch(inputs, settings, report)
    else:
        futures = [client.submit(_run_one, path, name, settings, pure=False) for path, name in inputs]
        results = client.gather(futures)
    _core._write_summary(results, settings)
    return [json.loads(r) for r in results]
