"""Animation-safe LODs of a skinned character, made by the OpenMeshSkinned library (its Python package
openmeshskinned) and put back beside the character: same armature, same materials, shape keys kept."""

bl_info = {
    "name": "OpenMeshSkinned LODs",
    "author": "OpenMeshSkinned",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Object > Make Skinned LODs; View3D > Sidebar > LOD",
    "description": "LODs of a skinned character judged in its animation's poses, parented to its armature",
    "category": "Object",
}

import sys

import bpy

from . import panel, properties
from .operator import OMSK_OT_make_lods, menu_entry


class OMSK_AddonPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    python_path: bpy.props.StringProperty(
        name="Package folder",
        subtype="DIR_PATH",
        description="Folder that holds the openmeshskinned package (e.g. BUILD/python), when it is not installed "
        "where Blender's Python looks (PREFIX/lib/python3.11/dist-packages)",
        update=lambda self, context: add_python_path(self.python_path),
    )

    def draw(self, context):
        self.layout.prop(self, "python_path")


def add_python_path(folder):
    folder = bpy.path.abspath(folder).rstrip("/") if folder else ""
    if folder and folder not in sys.path:
        sys.path.insert(0, folder)


CLASSES = (OMSK_AddonPreferences, OMSK_OT_make_lods) + panel.CLASSES


def register():
    properties.register()
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.VIEW3D_MT_object.append(menu_entry)
    preferences = bpy.context.preferences.addons.get(__package__)
    if preferences is not None and preferences.preferences is not None:
        add_python_path(preferences.preferences.python_path)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(menu_entry)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
    properties.unregister()
