"""The add-on inside Blender, headless:
    blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon.py -- \
        --zip BUILD/blender/openmeshskinned_lod.zip --package-dir BUILD/python --cli BUILD/apps/skinned-decimate \
        --scratch DIR --models /usr/share/assimp/models
Installs the zip, builds the character (character.py), runs Object > Make Skinned LODs on it and checks the LODs as
Blender sees them: in the collection, on the same armature, same vertex groups, materials and shape keys, capped
influences, and, posed by Blender at the held-out frames, within 10 % of the command line's held-out error for the
same settings. Then a second run (a triangle count, skeleton LoD, the glTF written and validated), what the add-on
must refuse, and a cancel. Exits non-zero on the first failure. BLENDER_USER_SCRIPTS must name a scratch folder
(ctest's entry sets it): the zip is installed there.
The operator's modal path (invoke: the job on a thread polled by a timer, Esc) needs a window: test_modal.py."""

import os
import shutil
import sys
import traceback

import bpy

sys.dont_write_bytecode = True  # nothing written into the source tree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import character  # noqa: E402
import measure  # noqa: E402

SETTINGS = {"ratios": [0.5, 0.25], "max_influences": 3, "poses": 8, "action": "Wuson_Walk_skin"}


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1 :]
    return dict(zip((a.lstrip("-").replace("-", "_") for a in argv[::2]), argv[1::2]))


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def install(zip_path, package_dir):
    import addon_utils

    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    addon_utils.enable("openmeshskinned_lod", default_set=True, handle_error=None)
    preferences = bpy.context.preferences.addons["openmeshskinned_lod"].preferences
    preferences.python_path = package_dir  # what a user of a build tree sets; puts it on sys.path
    import openmeshskinned  # noqa: F401  (the add-on's job imports it on use)


def select_only(obj):
    for o in bpy.context.scene.objects:
        o.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def configure(settings, **changes):
    values = {
        "lod_mode": "RATIOS",
        "ratios": ", ".join(str(r) for r in SETTINGS["ratios"]),
        "max_influences": SETTINGS["max_influences"],
        "poses": SETTINGS["poses"],
        "pose_action": SETTINGS["action"],
        "max_error": 0.0,
        "max_joints": "",
        "anim_error": 0.0,
        "write_gltf": False,
    }
    values.update(changes)
    for key, value in values.items():
        setattr(settings, key, value)


def cli_reference(args, armature, mesh, scratch):
    """The command line on the same export, with the same settings: its report per LOD and held-out frames."""
    import json
    import subprocess

    from openmeshskinned_lod import exchange, operator

    source = os.path.join(scratch, "character.glb")
    exchange.export_character(bpy.context, armature, [mesh], source)
    clip = operator.clip_name(armature, SETTINGS["action"], operator.animation_names(source))
    report = os.path.join(scratch, "cli-report.json")
    subprocess.run([args["cli"], source, "-o", os.path.join(scratch, "cli.glb"), "--lods",
                    ",".join(str(r) for r in SETTINGS["ratios"]), "--max-influences", str(SETTINGS["max_influences"]),
                    "--poses", str(SETTINGS["poses"]), "--pose-clip", clip, "--report", report, "--quiet"],
                   check=True)
    with open(report) as f:
        return json.load(f)


def check_lods(armature, mesh, settings, name):
    collection = bpy.data.collections.get(name + "_LODs")
    check(collection is not None, f"no collection {name}_LODs")
    lods = [bpy.data.objects.get(f"{name}_LOD{i}") for i in range(1, len(SETTINGS["ratios"]) + 1)]
    check(None not in lods, f"LOD objects missing: {[o.name for o in collection.objects]}")
    check(set(collection.objects) == set(lods), "the collection holds more than the LODs")
    bones = {b.name for b in armature.data.bones}
    original_groups = {g.name for g in mesh.vertex_groups}
    original_materials = [s.material for s in mesh.material_slots]
    original_keys = [k.name for k in mesh.data.shape_keys.key_blocks]
    for lod in lods:
        check(lod.parent == armature, f"{lod.name}: parent {lod.parent}")
        skins = [m for m in lod.modifiers if m.type == "ARMATURE"]
        check(len(skins) == 1 and skins[0].object == armature, f"{lod.name}: Armature modifier {skins}")
        groups = {g.name for g in lod.vertex_groups}
        check(groups <= bones and groups == original_groups,
              f"{lod.name}: vertex groups {sorted(groups ^ original_groups)} differ from the original's")
        materials = [s.material for s in lod.material_slots]
        check(all(m in original_materials for m in materials) and set(materials) == set(original_materials),
              f"{lod.name}: materials {[m and m.name for m in materials]}")
        check(lod.data.shape_keys is not None and [k.name for k in lod.data.shape_keys.key_blocks] == original_keys,
              f"{lod.name}: shape keys {lod.data.shape_keys and [k.name for k in lod.data.shape_keys.key_blocks]}")
        check([u.name for u in lod.data.uv_layers] == [u.name for u in mesh.data.uv_layers], f"{lod.name}: UV maps")
        widest = max(sum(1 for g in v.groups if g.weight > 0.0) for v in lod.data.vertices)
        check(widest <= SETTINGS["max_influences"], f"{lod.name}: a vertex has {widest} influences")
        check(lod.users_collection == (collection,), f"{lod.name}: in {lod.users_collection}")
    # Nothing of the imports is left: one armature, the original actions and materials.
    check(len(bpy.data.armatures) == 1, f"armatures left: {[a.name for a in bpy.data.armatures]}")
    check(set(bpy.data.materials) == set(original_materials), f"materials: {[m.name for m in bpy.data.materials]}")
    check(len(settings.report) == len(lods), "the panel's report has no row per LOD")
    return lods


def main():
    args = arguments()
    if not os.environ.get("BLENDER_USER_SCRIPTS"):
        raise SystemExit("test_addon.py: set BLENDER_USER_SCRIPTS to a scratch folder: the add-on is installed there")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scratch = args["scratch"]
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    install(args["zip"], args["package_dir"])
    armature, mesh = character.build(args["cli"], args["models"], scratch)
    actions_before = set(bpy.data.actions)
    reference = cli_reference(args, armature, mesh, scratch)

    settings = bpy.context.scene.omsk_lod
    configure(settings)
    select_only(armature)
    result = bpy.ops.object.omsk_make_lods()
    check(result == {"FINISHED"}, f"operator: {result}, {settings.message}")
    lods = check_lods(armature, mesh, settings, mesh.name)
    check(set(bpy.data.actions) == actions_before, "the import left actions behind")

    # The add-on's numbers are the library's for the same export: the command line's.
    for row, cli in zip(settings.report, reference["lods"]):
        check(row.faces == cli["faces"], f"{row.object_name}: {row.faces} triangles, the command line {cli['faces']}")
        check(abs(row.rms - cli["heldout_rms"]) <= 1e-6 * max(1.0, cli["heldout_rms"]),
              f"{row.object_name}: report RMS {row.rms}, the command line {cli['heldout_rms']}")

    frames = [(f["clip"], f["time"]) for f in reference["lods"][0]["heldout_times"]]
    errors = measure.heldout_rms(armature, mesh, lods, frames, lambda c, t: character.pose(armature, c, t))
    for lod, error, cli in zip(lods, errors, reference["lods"]):
        expected = cli["heldout_rms"]
        print(f"{lod.name}: {len(lod.data.polygons)} faces, held-out RMS posed by Blender {error:.4f} %, "
              f"the command line {expected:.4f} %")
        check(abs(error - expected) <= 0.1 * expected, f"{lod.name}: {error:.4f} % is not within 10 % of {expected:.4f} %")

    check_second_run(armature, mesh, settings, scratch, frames)
    check_refusals(armature, mesh, settings)
    check_cancel(args, armature, mesh, scratch)
    print("blender add-on test: all checks passed")


def check_second_run(armature, mesh, settings, scratch, frames):
    """By triangle count, with skeleton LoD, written as glTF too: the earlier LODs are replaced (they are not
    taken for part of the character either), the file written is valid glTF, and the LOD, whose skin now names
    fewer joints, still follows the original armature as closely as the library says: its error posed by Blender
    within 10 % of its report's, as above."""
    import subprocess

    folder = os.path.join(scratch, "written")
    os.makedirs(folder)
    configure(settings, lod_mode="FACES", faces="1500", max_joints="30", write_gltf=True, output_dir=folder)
    result = bpy.ops.object.omsk_make_lods()
    check(result == {"FINISHED"}, f"operator: {result}, {settings.message}")
    lods = list(bpy.data.collections[mesh.name + "_LODs"].objects)
    check([o.name for o in lods] == [mesh.name + "_LOD1"], f"after a second run: {[o.name for o in lods]}")
    check(len(lods[0].data.polygons) == settings.report[0].faces <= 1500,
          f"{len(lods[0].data.polygons)} faces, the report {settings.report[0].faces}")
    from openmeshskinned_lod.exchange import RIGID_GROUP

    # The skeleton LoD hands some weight to the armature node (a joint in the glTF hierarchy, no bone in
    # Blender): it must come back as the modifier's inverted mask, or Blender would spread it over the bones.
    groups = {g.name for g in lods[0].vertex_groups} - {RIGID_GROUP}
    check(groups <= {b.name for b in armature.data.bones} and len(groups) <= settings.report[0].joints <= 30,
          f"{len(groups)} vertex groups, {settings.report[0].joints} joints kept")
    modifier = lods[0].modifiers["Armature"] if "Armature" in lods[0].modifiers else None
    if RIGID_GROUP in lods[0].vertex_groups:
        check(modifier.vertex_group == RIGID_GROUP and modifier.invert_vertex_group, "the rigid part is not masked")
    error = measure.heldout_rms(armature, mesh, lods, frames, lambda c, t: character.pose(armature, c, t))[0]
    expected = settings.report[0].rms
    print(f"{lods[0].name}: {len(lods[0].data.polygons)} faces, {len(groups)} vertex groups, held-out RMS posed "
          f"by Blender {error:.4f} %, the report {expected:.4f} %")
    check(abs(error - expected) <= 0.1 * expected, f"{error:.4f} % is not within 10 % of {expected:.4f} %")
    written = os.path.join(folder, mesh.name + ".glb")
    check(os.listdir(folder) == [os.path.basename(written)], f"written: {os.listdir(folder)}")
    validator = os.path.join(os.path.dirname(__file__), "..", "..", "tools", "validate-gltf.mjs")
    subprocess.run(["node", validator, written], check=True)
    configure(settings)


def check_refusals(armature, mesh, settings):
    """What the add-on must refuse, each with its one-line message, and the LODs left as they were."""
    lods_before = sorted(o.name for o in bpy.data.collections[mesh.name + "_LODs"].objects)

    def refused(expected_part):
        try:
            result = bpy.ops.object.omsk_make_lods()
        except RuntimeError as e:  # how bpy.ops passes on the operator's report({"ERROR"}, ...)
            result = str(e).strip()
        check(result == "Error: " + settings.message, f"'{result}', expected a refusal with '{expected_part}'")
        check(expected_part in settings.message and "\n" not in settings.message,
              f"message '{settings.message}', expected one line with '{expected_part}'")
        check(sorted(o.name for o in bpy.data.collections[mesh.name + "_LODs"].objects) == lods_before,
              "a refused run changed the LODs")

    bpy.ops.mesh.primitive_cube_add()
    select_only(bpy.context.active_object)
    refused("is not an armature or a mesh with an Armature modifier")
    bpy.data.objects.remove(bpy.context.active_object)

    select_only(mesh)  # a skinned mesh stands for its character
    configure(settings, ratios="0.5, half")
    refused("Ratios: 'half' is not a number")
    configure(settings, ratios="1.5")
    refused("--lods: every ratio must be in (0, 1], got 1.5")
    configure(settings, pose_action="NoSuchAction")
    refused("'NoSuchAction' is not an action")
    configure(settings, max_joints="4, 0")
    refused("--max-joints: every value must be at least 1")  # the library's words, as the command line's
    configure(settings, lod_mode="FACES", faces="100000")
    refused(f"--faces 100000 is more than the input's {len(mesh.data.polygons)} triangles")  # not the LODs'
    configure(settings)

    # A character without animation: the library needs poses to learn from and to judge in.
    armature.animation_data_clear()
    for action in list(bpy.data.actions):
        bpy.data.actions.remove(action)
    configure(settings, pose_action="")
    refused("'skin' has no action")


def check_cancel(args, armature, mesh, scratch):
    """A cancel from the main thread while the library decimates on the worker thread, as Esc does in the modal
    operator: make_lods() stops at its next progress call and nothing is written."""
    import threading

    from openmeshskinned_lod import job

    source = os.path.join(scratch, "character.glb")
    out = os.path.join(scratch, "cancelled")
    os.makedirs(out)
    run = job.LodJob(source, {"ratios": [0.5, 0.25]}, job.output_path(out, "x"))
    decimating, cancel_sent = threading.Event(), threading.Event()
    stages = []

    def hold_until_cancelled(stage, fraction):  # on the worker: the cancel arrives mid-decimation, not after it
        stages.append(stage)
        if stage != "reading" and not decimating.is_set():
            decimating.set()
            cancel_sent.wait(60.0)

    run.start(on_progress=hold_until_cancelled)
    check(decimating.wait(120.0), f"the library never reported progress: {stages}")
    run.cancel()
    cancel_sent.set()
    run.wait()
    check(run.cancelled and run.error is None, f"not cancelled: error {run.error}, stages {stages}")
    check(run.paths == [] and os.listdir(out) == [], f"a cancelled run wrote {os.listdir(out)}")


if __name__ == "__main__":
    try:
        main()
    except Exception:
        traceback.print_exc()
        sys.stdout.flush()
        sys.exit(1)
