"""The panel's settings (the command line's main options) and the last run's report, kept on the scene."""

import bpy
from bpy.props import (
    BoolProperty,
    CollectionProperty,
    EnumProperty,
    FloatProperty,
    IntProperty,
    PointerProperty,
    StringProperty,
)


class OMSK_LodReportRow(bpy.types.PropertyGroup):
    """One LOD of the last run: what it has and its held-out error (% of the rest-pose diagonal)."""

    object_name: StringProperty()
    faces: IntProperty()
    vertices: IntProperty()
    joints: IntProperty()
    max_influences: IntProperty()
    rms: FloatProperty(default=-1.0)  # -1: not measured
    hausdorff: FloatProperty(default=-1.0)


class OMSK_LodSettings(bpy.types.PropertyGroup):
    lod_mode: EnumProperty(
        name="LODs by",
        items=[
            ("RATIOS", "Ratios", "One LOD per share of the character's triangles"),
            ("FACES", "Triangles", "One LOD per triangle count"),
        ],
        default="RATIOS",
    )
    ratios: StringProperty(
        name="Ratios",
        default="0.5, 0.25, 0.1",
        description="One LOD per ratio of the triangles, largest first (--lods)",
    )
    faces: StringProperty(
        name="Triangles", default="", description="One LOD per triangle count, instead of ratios (--faces)"
    )
    max_influences: IntProperty(
        name="Max influences", default=4, min=1, max=8, description="Bones per vertex at every LOD (--max-influences)"
    )
    poses: IntProperty(
        name="Example poses (0: auto)",
        default=0,
        min=0,
        max=256,
        description="Evenly spaced times of the action(s) the decimation learns from (--poses); 0: 8 per moving "
        "action, at most 16, on a character of up to 20,000 vertices; else 8",
    )
    pose_action: StringProperty(
        name="From action",
        default="",
        description="The action the example poses come from; empty: all the armature's actions, end to end "
        "(--pose-clip). The error is then also measured on the other actions",
    )
    max_error: FloatProperty(
        name="Max error %",
        default=0.0,
        min=0.0,
        precision=3,
        description="Bound on the distance of the character's vertices to each LOD in every example pose, % of "
        "the rest-pose bounding-box diagonal; 0: none (--max-error)",
    )
    max_joints: StringProperty(
        name="Max joints",
        default="",
        description="Skeleton LoD: joints kept, one per LOD, the last repeating; empty: all (--max-joints). "
        "The LODs still use the original armature: removed joints' weights move to kept ones",
    )
    anim_error: FloatProperty(
        name="Motion error %",
        default=0.0,
        min=0.0,
        precision=3,
        description="Motion LoD: keys dropped while no vertex moves further, % of the diagonal; 0: off "
        "(--anim-error). Applies to the written glTF files; in Blender the LODs play the original actions",
    )
    write_gltf: BoolProperty(
        name="Write glTF", default=False, description="Also keep the LOD chain as .glb files in a folder"
    )
    output_dir: StringProperty(name="Folder", subtype="DIR_PATH", default="//")
    report: CollectionProperty(type=OMSK_LodReportRow)
    message: StringProperty(default="")  # the last run's outcome, one line


CLASSES = (OMSK_LodReportRow, OMSK_LodSettings)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.omsk_lod = PointerProperty(type=OMSK_LodSettings)


def unregister():
    del bpy.types.Scene.omsk_lod
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
