"""Blender's side of the data path: the character out to glTF with Blender's own exporter, each LOD back in with
Blender's own importer, then made a LOD of the *original* character (its armature, its materials).

glTF both ways because the library's reader already understands everything Blender's exporter writes (skeleton,
every action as a clip, shape keys as morph targets, UV sets, materials by name), and the importer turns the
library's files back into Blender's types: what remains is to swap the imported armature and materials for the
original ones and clean up.
"""

import contextlib
import json
import re
import struct

import bpy


class CharacterError(ValueError):
    """The selection is not something the add-on can make LODs of; the message says what is missing."""


def find_character(context):
    """(armature object, [its skinned mesh objects]) for the active/selected object: an armature, or a mesh
    deformed by one."""
    obj = context.active_object
    if obj is None or not obj.select_get():
        obj = next(iter(context.selected_objects), None)
    if obj is None:
        raise CharacterError("select an armature or a mesh skinned to one")
    armature = obj if obj.type == "ARMATURE" else armature_of(obj)
    if armature is None:
        raise CharacterError(f"'{obj.name}' is not an armature or a mesh with an Armature modifier")
    meshes = [o for o in context.scene.objects
              if o.type == "MESH" and armature_of(o) == armature and LOD_MARK not in o]
    if not meshes:
        raise CharacterError(f"no mesh in the scene is skinned to '{armature.name}'")
    if not bone_actions(armature):
        raise CharacterError(f"'{armature.name}' has no action: the LODs learn from and are judged in its poses")
    return armature, meshes


# Set on every LOD object (to the character's name): an earlier run's LODs are skinned to the same armature,
# but are not part of the character.
LOD_MARK = "omsk_lod_of"


def bone_actions(armature):
    """The actions the exporter writes as clips for \\p armature: those that move some bone of it."""
    bones = armature.data.bones
    found = []
    for action in bpy.data.actions:
        for curve in action.fcurves:
            path = curve.data_path
            if path.startswith('pose.bones["') and path[12 : path.find('"]', 12)] in bones:
                found.append(action)
                break
    return found


def armature_of(obj):
    if obj.type != "MESH":
        return None
    for modifier in obj.modifiers:
        if modifier.type == "ARMATURE" and modifier.object is not None:
            return modifier.object
    return None


def character_name(armature, meshes):
    """The LODs' base name: the mesh's own name for one mesh, else the armature's."""
    return meshes[0].name if len(meshes) == 1 else armature.name


@contextlib.contextmanager
def only_selected(context, objects):
    """Selects exactly \\p objects for the exporter's use_selection, and gives back the user's selection."""
    layer = context.view_layer
    was_selected = [o for o in context.scene.objects if o.select_get()]
    was_active = layer.objects.active
    for o in was_selected:
        o.select_set(False)
    for o in objects:
        o.select_set(True)
    layer.objects.active = objects[0]
    try:
        yield
    finally:
        for o in objects:
            o.select_set(False)
        for o in was_selected:
            o.select_set(True)
        layer.objects.active = was_active


def export_character(context, armature, meshes, path):
    """Writes the armature, its meshes and every action of the armature to \\p path (GLB) with Blender's exporter.
    All influences go out (the library caps them itself); modifiers other than the armature are not applied."""
    if context.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    with only_selected(context, [armature] + meshes):
        bpy.ops.export_scene.gltf(
            filepath=path,
            export_format="GLB",
            use_selection=True,
            export_apply=False,
            export_animations=True,
            export_anim_single_armature=True,  # every action of the armature becomes a clip
            export_force_sampling=True,
            export_skins=True,
            export_all_influences=True,
            export_morph=True,
            export_morph_normal=False,
            export_materials="EXPORT",
            export_cameras=False,
            export_lights=False,
            export_extras=False,
        )


@contextlib.contextmanager
def numpy_bool_alias():
    """Debian's Blender 3.4 glTF importer still names np.bool, which NumPy 1.24 removed: the alias is put back
    for the import only, and taken away again."""
    import numpy

    added = "bool" not in numpy.__dict__
    if added:
        numpy.bool = bool
    try:
        yield
    finally:
        if added:
            del numpy.bool


def gltf_material_names(path):
    """The materials' names as the file spells them (Blender renames imported copies 'NAME.001')."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"glTF":
        return [m.get("name", "") for m in json.loads(data).get("materials", [])]
    length, kind = struct.unpack_from("<II", data, 12)
    document = json.loads(data[20 : 20 + length].decode("utf-8"))
    return [m.get("name", "") for m in document.get("materials", [])]


def file_name_of(imported, file_names):
    """The name in the file that Blender's uniquifier turned into imported.name ('Skin' -> 'Skin.001')."""
    best = None
    for name in file_names:
        if imported.name == name or re.fullmatch(re.escape(name) + r"\.\d{3,}", imported.name):
            if best is None or len(name) > len(best):
                best = name
    return best


DATA_KINDS = ("objects", "meshes", "armatures", "materials", "images", "textures", "actions", "node_groups")


def snapshot():
    return {kind: set(getattr(bpy.data, kind)) for kind in DATA_KINDS}


def import_lod(context, path, armature, meshes, name, collection):
    """Imports one LOD file and turns it into a LOD of the original character: returns the new mesh object,
    parented to \\p armature with an Armature modifier on it, with the original material datablocks, UV map
    names and the LOD's shape keys, linked to \\p collection only, and warnings (list of str). Everything else
    the import made goes."""
    before = snapshot()
    with numpy_bool_alias():
        bpy.ops.import_scene.gltf(filepath=path, merge_vertices=True, import_shading="NORMALS")
    made = {kind: set(getattr(bpy.data, kind)) - before[kind] for kind in DATA_KINDS}
    lod_objects = [o for o in made["objects"] if o.type == "MESH"]
    if len(lod_objects) != 1:
        raise CharacterError(f"{path}: expected one mesh in the LOD file, found {len(lod_objects)}")
    lod = lod_objects[0]

    world = lod.matrix_world.copy()
    lod.parent = armature
    lod.parent_type = "OBJECT"
    lod.matrix_world = world
    skin_modifiers = [m for m in lod.modifiers if m.type == "ARMATURE"]
    if not skin_modifiers:
        skin_modifiers = [lod.modifiers.new("Armature", "ARMATURE")]
    for modifier in skin_modifiers[1:]:
        lod.modifiers.remove(modifier)
    skin_modifiers[0].object = armature

    warnings = reattach_groups(lod, armature, meshes, skin_modifiers[0])
    keep_materials = assign_original_materials(lod, path, meshes)
    rename_uv_maps(lod, meshes[0])

    for o in list(lod.users_collection):
        o.objects.unlink(lod)
    collection.objects.link(lod)
    lod.name = name
    lod.data.name = name
    lod[LOD_MARK] = meshes[0].name if len(meshes) == 1 else armature.name

    for o in made["objects"] - {lod}:
        bpy.data.objects.remove(o)
    for kind in ("armatures", "actions", "materials", "images", "textures", "node_groups"):
        for block in made[kind]:
            if kind == "materials" and block in keep_materials:
                continue
            getattr(bpy.data, kind).remove(block)
    return lod, warnings


# The vertex group that masks the Armature modifier (inverted) where the LOD's skin weights the armature object.
RIGID_GROUP = "rigid with armature"


def reattach_groups(lod, armature, meshes, modifier):
    """Makes the LOD's vertex groups say to Blender what its glTF skin says.

    The exporter writes the armature object (and the mesh objects) as nodes above the bones, and the library reads
    that hierarchy as the skeleton, so the LOD's skin lists them as joints. They mostly carry no weight, and their
    groups go. With skeleton LoD they can: a removed bone's weight handed to the armature node means "moves
    rigidly with the armature object". Blender's Armature modifier ignores a group that names no bone and spreads
    the other weights over the whole vertex, so that weight goes into RIGID_GROUP instead, set as the modifier's
    inverted vertex group: the modifier then moves the vertex by (1 - w) times the bones' normalised blend, which is
    the bones' own weights' blend, and leaves w of it in place in the armature's frame: the glTF skin's result.
    Returns warnings for weighted groups that name neither a bone nor those objects (kept as they are)."""
    bones = armature.data.bones
    rigid_names = {armature.name} | {m.name for m in meshes}
    names = [g.name for g in lod.vertex_groups]
    rigid, foreign = {}, set()
    for vertex in lod.data.vertices:
        for g in vertex.groups:
            name = names[g.group]
            if name in bones or g.weight <= 0.0:
                continue
            if name in rigid_names:
                rigid[vertex.index] = rigid.get(vertex.index, 0.0) + g.weight
            else:
                foreign.add(name)
    for group in list(lod.vertex_groups):
        if group.name not in bones and group.name not in foreign:
            lod.vertex_groups.remove(group)
    if rigid:
        group = lod.vertex_groups.new(name=RIGID_GROUP)
        for index, weight in rigid.items():
            group.add([index], min(weight, 1.0), "REPLACE")
        modifier.vertex_group = group.name
        modifier.invert_vertex_group = True
    return [f"{lod.name}: vertex group '{n}' has weights but names no bone of '{armature.name}'" for n in sorted(foreign)]


def assign_original_materials(lod, path, meshes):
    """Puts the original character's material datablocks in the LOD's slots, matched by name; returns the
    imported materials that have no original (kept so that no face loses its material)."""
    originals = {}
    for mesh in meshes:
        for slot in mesh.material_slots:
            if slot.material is not None:
                originals.setdefault(slot.material.name, slot.material)
    names = gltf_material_names(path)
    kept = set()
    for slot in lod.material_slots:
        imported = slot.material
        if imported is None:
            continue
        original = originals.get(file_name_of(imported, names) or "")
        if original is None:
            kept.add(imported)
            continue
        slot.link = "DATA"
        slot.material = original
    return kept


def rename_uv_maps(lod, source):
    """The importer names UV sets UVMap, UVMap.001, ...; the LOD takes the source mesh's names, in order."""
    for lod_layer, source_layer in zip(lod.data.uv_layers, source.data.uv_layers):
        lod_layer.name = source_layer.name


def lods_collection(context, name):
    """The collection NAME_LODs in the scene, emptied of an earlier run's LODs."""
    collection = bpy.data.collections.get(name + "_LODs")
    if collection is None:
        collection = bpy.data.collections.new(name + "_LODs")
    if collection.name not in context.scene.collection.children:
        context.scene.collection.children.link(collection)
    for o in list(collection.objects):
        data = o.data
        bpy.data.objects.remove(o)
        if data is not None and data.users == 0 and isinstance(data, bpy.types.Mesh):
            bpy.data.meshes.remove(data)
    return collection
