"""The library's part of the work: read the exported character, make the LODs, write them.

No bpy here: a LodJob runs on a worker thread while Blender's UI goes on (the library releases the GIL while it
reads, decimates and measures), or on the calling thread in background mode. The main thread reads
`stage`/`fraction` to show progress and calls cancel(); the library's progress callback then answers False,
make_lods() raises Cancelled, and nothing is written.
"""

import os
import threading


def library():
    """The openmeshskinned package, imported on first use so that the add-on loads (and says what is missing)
    without it."""
    import openmeshskinned

    return openmeshskinned


class LodJob:
    """One run: character.glb in, NAME.glb (one LOD) or NAME_lod1.glb, NAME_lod2.glb, ... out."""

    def __init__(self, source_path, keywords, output_path):
        self.source_path = source_path
        self.keywords = dict(keywords)
        self.output_path = output_path
        self.stage = "reading"
        self.fraction = 0.0
        self.paths = []  # the LOD files written, largest first
        self.reports = []  # one dict per LOD (LodReport.to_dict()) with its heldout error
        self.heldout_frames = []  # (clip name, seconds) the LODs were judged in
        self.warnings = []
        self.error = None  # the library's one-line message when it refused or failed
        self.cancelled = False
        self._cancel = threading.Event()
        self._thread = None

    def cancel(self):
        self._cancel.set()

    def _progress(self, stage, fraction):
        self.stage, self.fraction = stage, fraction
        return not self._cancel.is_set()

    def run(self, on_progress=None):
        """Does the whole job on this thread; on_progress(stage, fraction) is called as it advances. Errors end
        up in self.error (the library's message), a cancel in self.cancelled; nothing is raised."""
        oms = library()

        def progress(stage, fraction):
            go = self._progress(stage, fraction)
            if on_progress is not None:
                on_progress(stage, fraction)
            return go

        try:
            progress("reading", 0.0)
            mesh = oms.load(self.source_path)
            self.warnings = list(mesh.warnings)
            if self._cancel.is_set():
                raise oms.Cancelled("cancelled")
            chain = oms.make_lods(mesh, progress=progress, **self.keywords)
            self.warnings += list(chain.warnings)
            self.heldout_frames = list(chain.heldout_frames)
            self.reports = [lod.report.to_dict() for lod in chain]
            progress("writing", 1.0)
            if self._cancel.is_set():
                raise oms.Cancelled("cancelled")
            self.paths = oms.save(chain, self.output_path)
        except oms.Cancelled:
            self.cancelled = True
        except oms.Error as e:
            self.error = str(e)

    def start(self, on_progress=None):
        """Runs it on a worker thread (on_progress is called there); poll done()."""
        self._thread = threading.Thread(target=self.run, args=(on_progress,), name="openmeshskinned-lod",
                                        daemon=True)
        self._thread.start()

    def done(self):
        return self._thread is not None and not self._thread.is_alive()

    def wait(self):
        if self._thread is not None:
            self._thread.join()


def output_path(folder, name):
    """Where the chain is written: FOLDER/NAME.glb (save() puts NAME_lod1.glb, ... beside it for several)."""
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in name) or "character"
    return os.path.join(folder, safe + ".glb")
