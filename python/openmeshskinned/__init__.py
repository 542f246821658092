"""LODs of skinned, animated characters that stay right in poses never seen.

The Python face of the OpenMeshSkinned C++ library: the job the ``skinned-decimate`` command does, as calls::

    import openmeshskinned as oms

    m = oms.load("hero.fbx")            # read in a child process, as the command line does
    print(m.warnings)                   # what the reader changed or could not use
    lods = oms.make_lods(m, ratios=[0.5, 0.25, 0.1], max_influences=4)
    for lod in lods:
        print(lod.report.faces, lod.report.hausdorff)
    oms.save(lods, "hero.glb")          # hero_lod1.glb, hero_lod2.glb, hero_lod3.glb

Errors are raised as this package's exceptions, all subclasses of :class:`Error`, carrying the command line's
one-line messages: :class:`OptionsError` (a ``ValueError``) for a request that cannot be carried out,
:class:`ReadError` and :class:`WriteError` (``OSError``, via :class:`FileError`) for files, :class:`Cancelled`
when a progress callable stops the work. The GIL is released while reading, decimating and measuring.
"""

from os import fspath as _fspath

from . import _core
from .batch import batch, tool_path
from ._core import (
    Cancelled,
    Error,
    FileError,
    HeldOutError,
    Lod,
    LodChain,
    LodReport,
    Mesh,
    OptionsError,
    ReadError,
    WriteError,
    default_options,
    evaluate,
    lod_methods,
    make_lods,
)

__all__ = [
    "Cancelled",
    "Error",
    "FileError",
    "HeldOutError",
    "Lod",
    "LodChain",
    "LodReport",
    "Mesh",
    "OptionsError",
    "ReadError",
    "WriteError",
    "batch",
    "default_options",
    "evaluate",
    "load",
    "lod_methods",
    "make_lods",
    "save",
    "tool_path",
]


def load(path, **options):
    return _core.load(_fspath(path), **options)


load.__doc__ = _core.load.__doc__


def save(what, path):
    """Writes a LodChain or a Mesh as glTF (``.glb``, or ``.gltf`` with its buffers embedded); returns the
    paths written (a list of str).

    A LodChain of one LOD is written to ``path`` itself; of several, to ``NAME_lod1.glb``, ``NAME_lod2.glb``,
    ... beside it, largest first, as the command line names them. All files appear together at the end, or
    none; never over the file the mesh was read from. Raises WriteError with the one-line reason, and nothing
    is written.
    """
    path = _fspath(path)
    if isinstance(what, LodChain):
        return _core._save_chain(what, path)
    if isinstance(what, Mesh):
        _core._save_mesh(what, path)
        return [path]
    raise TypeError("save() takes a LodChain or a Mesh, not " + type(what).__name__)
