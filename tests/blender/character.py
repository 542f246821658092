"""The test character, built inside Blender from the suite's assets: Testwuson (assimp's test models) written as
glTF by the project's command line at ratio 1, read by Blender's importer, then given what an artist's character
has and Testwuson lacks: a second material and a shape key.

Shared by test_addon.py and render_preview.py (the README's picture)."""

import os
import subprocess

import bpy


def wuson_glb(cli, models, scratch):
    """Testwuson.X as GLB, untouched apart from the reader's repairs (--ratio 1 decimates nothing)."""
    path = os.path.join(scratch, "wuson.glb")
    subprocess.run([cli, os.path.join(models, "X", "Testwuson.X"), "-o", path, "--ratio", "1", "--no-eval",
                    "--quiet"], check=True)
    return path


def build(cli, models, scratch):
    """Adds the character to the scene; returns (armature, mesh)."""
    from openmeshskinned_lod import exchange

    before = set(bpy.data.objects)
    with exchange.numpy_bool_alias():
        bpy.ops.import_scene.gltf(filepath=wuson_glb(cli, models, scratch), merge_vertices=True)
    imported = [o for o in bpy.data.objects if o not in before]
    armature = next(o for o in imported if o.type == "ARMATURE")
    mesh = next(o for o in imported if o.type == "MESH")

    # A second material on the upper half, so that the LODs' slots have more than one original to match.
    belly = bpy.data.materials.new("Belly")
    belly.diffuse_color = (0.8, 0.35, 0.2, 1.0)
    belly.use_nodes = True
    belly.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.8, 0.35, 0.2, 1.0)
    mesh.data.materials.append(belly)
    top = max(v.co.z for v in mesh.data.vertices)
    bottom = min(v.co.z for v in mesh.data.vertices)
    middle = 0.5 * (top + bottom)
    for polygon in mesh.data.polygons:
        if polygon.center.z > middle:
            polygon.material_index = 1

    # A shape key that swells the body along its normals (left at 0, so the poses are the skin's alone).
    mesh.shape_key_add(name="Basis")
    swell = mesh.shape_key_add(name="Swell")
    size = (top - bottom) * 0.03
    for i, vertex in enumerate(mesh.data.vertices):
        swell.data[i].co = vertex.co + vertex.normal * size
    return armature, mesh


def action_of_clip(armature, clip):
    """The action Blender's exporter wrote as \\p clip: named as the action, or as the NLA track holding it."""
    action = bpy.data.actions.get(clip)
    if action is not None:
        return action
    for track in armature.animation_data.nla_tracks:
        if track.name == clip and track.strips:
            return track.strips[0].action
    raise KeyError(clip)


def pose(armature, clip, seconds):
    """Blender's own pose of the character at \\p seconds into \\p clip (the exporter writes frame / fps)."""
    scene = bpy.context.scene
    armature.animation_data.action = action_of_clip(armature, clip)
    frame = seconds * scene.render.fps
    whole = int(frame // 1)
    scene.frame_set(whole, subframe=frame - whole)
