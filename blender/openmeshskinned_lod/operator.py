"""Object > Make Skinned LODs: export the character, let the library make the LODs, bring them back.

From the UI (invoke) the library works on a thread while a timer shows its progress in the progress bar and the
status bar, and Esc cancels. From a script or in background mode (execute) the same job runs on the calling thread.
What the library refuses ends as an error in the report area with the library's one-line message; nothing in the
scene changes then, nor after a cancel.
"""

import json
import os
import shutil
import struct
import tempfile

import bpy

from . import exchange, job, options

# What the stages' fractions are worth of the whole bar (export and import are Blender's, before and after).
BAR = {"export": (0.0, 0.05), "reading": (0.05, 0.1), "writing": (0.9, 0.95), "import": (0.95, 1.0)}
DECIMATE = (0.1, 0.9)


def overall(stage, fraction):
    low, high = BAR.get(stage, DECIMATE)
    return low + (high - low) * min(max(fraction, 0.0), 1.0)


def animation_names(path):
    with open(path, "rb") as f:
        data = f.read()
    length = struct.unpack_from("<I", data, 12)[0]
    document = json.loads(data[20 : 20 + length].decode("utf-8"))
    return [a.get("name", "") for a in document.get("animations", [])]


def clip_name(armature, action_name, names):
    """The clip Blender's exporter made of an action: named as the action, or as the NLA track that holds it."""
    if action_name in names:
        return action_name
    data = armature.animation_data
    for track in data.nla_tracks if data else ():
        if track.name in names and any(s.action and s.action.name == action_name for s in track.strips):
            return track.name
    raise options.SettingsError(
        f"From action: '{action_name}' is not an action of '{armature.name}' that the glTF exporter writes"
    )


class OMSK_OT_make_lods(bpy.types.Operator):
    """Make animation-safe LODs of the selected character and put them beside it"""

    bl_idname = "object.omsk_make_lods"
    bl_label = "Make Skinned LODs"
    bl_options = {"REGISTER", "UNDO"}

    _job = None
    _timer = None

    @classmethod
    def poll(cls, context):
        return context.active_object is not None or bool(context.selected_objects)

    def prepare(self, context):
        """Everything before the library: settings, selection, export. Returns False (reported) on a refusal."""
        settings = context.scene.omsk_lod
        try:
            keywords = options.make_lods_keywords(settings)
            armature, meshes = exchange.find_character(context)
            job.library()
        except (options.SettingsError, exchange.CharacterError) as e:
            return self.refuse(settings, str(e))
        except ImportError as e:
            return self.refuse(settings, f"the Python package openmeshskinned cannot be imported ({e}); install "
                               "it, or set its folder in the add-on's preferences")
        folder = None
        if settings.write_gltf:
            folder = bpy.path.abspath(settings.output_dir)
            if settings.output_dir.startswith("//") and not bpy.data.filepath:
                folder = ""  # relative to a .blend file that has no place yet
            if not folder or not os.path.isdir(folder):
                return self.refuse(settings, f"Folder: '{settings.output_dir}' is not a folder (save the .blend "
                                   "file first for a relative one)")
        self.armature_name = armature.name
        self.mesh_names = [m.name for m in meshes]
        self.character_name = exchange.character_name(armature, meshes)
        self.scratch = tempfile.mkdtemp(prefix="omsk-lod-")
        source = os.path.join(self.scratch, "character.glb")
        context.window_manager.progress_begin(0.0, 1.0)
        try:
            exchange.export_character(context, armature, meshes, source)
        except RuntimeError as e:  # the exporter's own error, passed on by bpy.ops
            self.cleanup(context)
            return self.refuse(settings, "glTF export: " + str(e).strip().splitlines()[-1])
        if keywords["pose_clip"]:
            try:
                keywords["pose_clip"] = clip_name(armature, keywords["pose_clip"], animation_names(source))
            except options.SettingsError as e:
                self.cleanup(context)
                return self.refuse(settings, str(e))
        self._job = job.LodJob(source, keywords, job.output_path(folder or self.scratch, self.character_name))
        return True

    def refuse(self, settings, message):
        settings.message = message
        self.report({"ERROR"}, message)
        return False

    def cleanup(self, context):
        context.window_manager.progress_end()
        if context.workspace is not None:
            context.workspace.status_text_set(None)
        shutil.rmtree(self.scratch, ignore_errors=True)

    def finish(self, context):
        settings = context.scene.omsk_lod
        done = self._job
        try:
            for warning in done.warnings:
                self.report({"WARNING"}, warning)
            if done.cancelled:
                settings.message = "Cancelled: nothing was changed"
                self.report({"WARNING"}, settings.message)
                return {"CANCELLED"}
            if done.error is not None:
                self.refuse(settings, done.error)
                return {"CANCELLED"}
            armature = bpy.data.objects.get(self.armature_name)
            meshes = [bpy.data.objects.get(n) for n in self.mesh_names]
            if armature is None or None in meshes:
                self.refuse(settings, "the character was deleted while its LODs were made")
                return {"CANCELLED"}
            context.window_manager.progress_update(overall("import", 0.0))
            collection = exchange.lods_collection(context, self.character_name)
            settings.report.clear()
            for i, (path, report) in enumerate(zip(done.paths, done.reports), start=1):
                try:
                    lod, warnings = exchange.import_lod(context, path, armature, meshes,
                                                        f"{self.character_name}_LOD{i}", collection)
                except (exchange.CharacterError, RuntimeError) as e:
                    self.refuse(settings, f"LOD{i}: " + str(e).strip().splitlines()[-1])
                    return {"CANCELLED"}
                for warning in warnings:
                    self.report({"WARNING"}, warning)
                row = settings.report.add()
                row.object_name = lod.name
                row.faces, row.vertices = report["faces"], report["vertices"]
                row.joints, row.max_influences = report["joints"], report["max_influences"]
                row.rms = report["rms"] if report["rms"] is not None else -1.0
                row.hausdorff = report["hausdorff"] if report["hausdorff"] is not None else -1.0
            settings.message = f"{len(done.paths)} LODs in {collection.name}"
            if settings.write_gltf:
                settings.message += " and " + os.path.dirname(done.paths[0])
            self.report({"INFO"}, settings.message)
            return {"FINISHED"}
        finally:
            self.cleanup(context)

    def execute(self, context):
        if not self.prepare(context):
            return {"CANCELLED"}
        wm = context.window_manager
        self._job.run(on_progress=lambda stage, fraction: wm.progress_update(overall(stage, fraction)))
        return self.finish(context)

    def invoke(self, context, event):
        if not self.prepare(context):
            return {"CANCELLED"}
        self._job.start()
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type == "ESC":
            self._job.cancel()
            return {"RUNNING_MODAL"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}  # the rest of Blender stays usable meanwhile
        stage, fraction = self._job.stage, self._job.fraction
        context.window_manager.progress_update(overall(stage, fraction))
        if context.workspace is not None:
            context.workspace.status_text_set(f"Skinned LODs: {stage} {fraction * 100:.0f}% (Esc to cancel)")
        if not self._job.done():
            return {"RUNNING_MODAL"}
        context.window_manager.event_timer_remove(self._timer)
        return self.finish(context)


def menu_entry(self, context):
    self.layout.separator()
    self.layout.operator(OMSK_OT_make_lods.bl_idname, icon="MOD_DECIM")
