"""The README's picture (docs/blender-lods.png): the test character and its LODs made by the add-on, posed by
Blender at a held-out frame of the walk, rendered with Workbench, flat-shaded so the triangles show.
    blender -b --factory-startup --python tests/blender/render_preview.py -- --package-dir BUILD/python \
        --cli BUILD/apps/skinned-decimate --scratch DIR --models /usr/share/assimp/models --out docs/blender-lods.png
The add-on is used from the source tree (blender/ on sys.path); only for the picture, each LOD is moved beside the
character on its own copy of the armature (sharing its bones and action), because an object moved away from its
armature would be deformed from the wrong place."""

import math
import os
import sys

import bpy

sys.dont_write_bytecode = True  # nothing written into the source tree

here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [here, os.path.join(here, "..", "..", "blender")]

import character  # noqa: E402
import openmeshskinned_lod  # noqa: E402


def label(text, y, z, height):
    curve = bpy.data.curves.new("label", "FONT")
    curve.body = text
    curve.align_x = "CENTER"
    curve.size = 0.08 * height
    obj = bpy.data.objects.new("label", curve)
    obj.location = (0.0, y, z)
    obj.rotation_euler = (math.pi / 2, 0.0, math.pi / 2)  # facing +X, the camera
    bpy.context.scene.collection.objects.link(obj)


def main():
    argv = sys.argv[sys.argv.index("--") + 1 :]
    args = dict(zip((a.lstrip("-").replace("-", "_") for a in argv[::2]), argv[1::2]))
    os.makedirs(args["scratch"], exist_ok=True)
    sys.path.insert(0, args["package_dir"])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    openmeshskinned_lod.register()
    armature, mesh = character.build(args["cli"], args["models"], args["scratch"])

    settings = bpy.context.scene.omsk_lod
    settings.ratios, settings.max_influences, settings.pose_action = "0.5, 0.25, 0.1", 4, "Wuson_Walk_skin"
    for o in bpy.context.scene.objects:
        o.select_set(o == armature)
    bpy.context.view_layer.objects.active = armature
    assert bpy.ops.object.omsk_make_lods() == {"FINISHED"}, settings.message

    # Side by side along Y, seen from +X (the character walks along -Y): original first, then the LODs.
    corners = [mesh.matrix_world @ v.co for v in mesh.data.vertices]
    length = max(c.y for c in corners) - min(c.y for c in corners)
    floor, top = min(c.z for c in corners), max(c.z for c in corners)
    step = 1.1 * length
    middle_y = (min(c.y for c in corners) + max(c.y for c in corners)) / 2
    label(f"original  {len(mesh.data.polygons):,} triangles", middle_y, floor - 0.08 * (top - floor), top - floor)
    for i, row in enumerate(settings.report, start=1):
        lod = bpy.data.objects[row.object_name]
        stand = armature.copy()  # shares the armature data and the action: the same pose
        stand.location.y += i * step
        bpy.context.scene.collection.objects.link(stand)
        lod.parent = stand
        for m in lod.modifiers:
            if m.type == "ARMATURE":
                m.object = stand
        label(f"LOD{i}  {row.faces:,} triangles  held-out {row.rms:.3f} %", middle_y + i * step,
              floor - 0.08 * (top - floor), top - floor)
    for obj in [mesh] + [bpy.data.objects[r.object_name] for r in settings.report]:
        for polygon in obj.data.polygons:
            polygon.use_smooth = False

    character.pose(armature, "Wuson_Walk", 1.28)
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.display.shading.light = "STUDIO"
    scene.display.shading.color_type = "MATERIAL"
    scene.world = bpy.data.worlds.new("background")
    scene.world.color = (0.92, 0.92, 0.94)
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    camera.data.type = "ORTHO"
    span = step * (len(settings.report) + 1)
    height = 1.7 * (top - floor)
    camera.data.ortho_scale = span
    scene.render.resolution_x = 1600
    scene.render.resolution_y = int(1600 * height / span)
    camera.data.clip_end = 100.0 * (top - floor)
    camera.location = (max(c.x for c in corners) + 10.0 * (top - floor), middle_y + span / 2 - step / 2, (top + floor) / 2 - 0.08 * (top - floor))
    camera.rotation_euler = (math.pi / 2, 0.0, math.pi / 2)
    scene.camera = camera
    scene.render.filepath = os.path.abspath(args["out"])
    bpy.ops.render.render(write_still=True)


main()
