"""The operator as the UI runs it (invoke: the export, then the library on a worker thread polled by a timer,
progress, Esc), in a real Blender window under Xvfb with simulated events:
    xvfb-run -a blender --factory-startup --enable-event-simulate --python tests/blender/test_modal.py -- \
        --package-dir BUILD/python --cli BUILD/apps/skinned-decimate --scratch DIR --models /usr/share/assimp/models
First Esc right after the start: the run ends cancelled and the scene has no LODs; then a run left alone: the
LODs arrive in their collection with the panel's report. Exits non-zero on failure (or after 5 minutes)."""

import os
import sys
import time

import bpy

sys.dont_write_bytecode = True  # nothing written into the source tree
here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [here, os.path.join(here, "..", "..", "blender")]

import character  # noqa: E402
import openmeshskinned_lod  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1 :]
args = dict(zip((a.lstrip("-").replace("-", "_") for a in argv[::2]), argv[1::2]))
sys.path.insert(0, args["package_dir"])
os.makedirs(args["scratch"], exist_ok=True)
openmeshskinned_lod.register()
armature, mesh = character.build(args["cli"], args["models"], args["scratch"])
NAME = mesh.name
settings = bpy.context.scene.omsk_lod
settings.ratios, settings.pose_action = "0.5, 0.25", "Wuson_Walk_skin"
for o in bpy.context.scene.objects:
    o.select_set(o == armature)
bpy.context.view_layer.objects.active = armature
started = time.time()
steps = iter(["cancel", "wait_cancelled", "run", "wait_done"])
state = {"step": next(steps)}


def fail(message):
    print("modal test FAILED:", message, flush=True)
    os._exit(1)


def invoke():
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    with bpy.context.temp_override(window=window, area=area, region=area.regions[-1]):
        result = bpy.ops.object.omsk_make_lods("INVOKE_DEFAULT")
    if result != {"RUNNING_MODAL"}:
        fail(f"invoke returned {result}: {bpy.context.scene.omsk_lod.message}")
    return window


def tick():
    settings = bpy.context.scene.omsk_lod  # looked up afresh: the undo step at the end renews the datablocks
    step = state["step"]
    if time.time() - started > 300:
        fail(f"still at '{step}' after 5 minutes; message '{settings.message}'")
    if step == "cancel":
        settings.message = ""
        window = invoke()
        window.event_simulate(type="ESC", value="PRESS")  # reaches the modal handler before the library is done
        state["step"] = next(steps)
    elif step == "wait_cancelled" and settings.message:
        if settings.message != "Cancelled: nothing was changed" or NAME + "_LODs" in bpy.data.collections:
            fail(f"after Esc: '{settings.message}', collections {list(bpy.data.collections.keys())}")
        print("Esc: " + settings.message, flush=True)
        state["step"] = next(steps)
    elif step == "run":
        settings.message = ""
        invoke()
        state["step"] = next(steps)
    elif step == "wait_done" and settings.message:
        collection = bpy.data.collections.get(NAME + "_LODs")
        names = sorted(o.name for o in collection.objects) if collection else []
        if names != [NAME + "_LOD1", NAME + "_LOD2"] or len(settings.report) != 2:
            fail(f"'{settings.message}', LODs {names}, {len(settings.report)} report rows")
        print("modal run: " + settings.message, [(r.faces, round(r.rms, 4)) for r in settings.report], flush=True)
        print("blender modal test: all checks passed", flush=True)
        os._exit(0)
    return 0.1


bpy.app.timers.register(tick, first_interval=1.0)
