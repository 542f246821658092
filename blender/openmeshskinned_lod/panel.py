"""The sidebar panel (View3D > Sidebar > LOD): the settings, the button, and the last run's report."""

import bpy

from .operator import OMSK_OT_make_lods


class OMSK_PT_lods(bpy.types.Panel):
    bl_label = "Skinned LODs"
    bl_idname = "OMSK_PT_lods"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "LOD"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.omsk_lod
        layout.use_property_split = True
        layout.use_property_decorate = False

        col = layout.column()
        col.prop(settings, "lod_mode", expand=True)
        col.prop(settings, "ratios" if settings.lod_mode == "RATIOS" else "faces")
        col.prop(settings, "max_influences")
        col.prop(settings, "poses")
        col.prop_search(settings, "pose_action", bpy.data, "actions")
        col.prop(settings, "max_error")
        col.prop(settings, "max_joints")
        col.prop(settings, "anim_error")
        col.prop(settings, "write_gltf")
        sub = col.column()
        sub.enabled = settings.write_gltf
        sub.prop(settings, "output_dir")

        layout.operator(OMSK_OT_make_lods.bl_idname, icon="MOD_DECIM")
        if settings.message:
            layout.label(text=settings.message)
        if settings.report:
            self.draw_report(layout, settings.report)

    @staticmethod
    def draw_report(layout, rows):
        box = layout.box()
        grid = box.grid_flow(row_major=True, columns=4, even_columns=False, align=True)
        for heading in ("LOD", "Triangles", "RMS %", "Max %"):
            grid.label(text=heading)
        for row in rows:
            grid.label(text=row.object_name)
            grid.label(text=f"{row.faces:,}")
            grid.label(text=f"{row.rms:.4f}" if row.rms >= 0 else "-")
            grid.label(text=f"{row.hausdorff:.4f}" if row.hausdorff >= 0 else "-")
        box.label(text="Held-out error: poses not learnt from, % of the diagonal")


CLASSES = (OMSK_PT_lods,)
