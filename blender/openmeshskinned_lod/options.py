"""The panel's settings as the keywords of openmeshskinned.make_lods().

Kept free of bpy so that the parsing can be checked without Blender. The library validates the values
themselves (ranges, one ratio per LOD, ...) and says what is wrong in the command line's words; this module only
turns the text fields into numbers and says which field holds something that is not one.
"""


class SettingsError(ValueError):
    """A text field that does not hold what it should; the message names the field and the bad entry."""


def parse_list(text, kind, field):
    """'0.5, 0.25 0.1' -> [0.5, 0.25, 0.1]; commas and spaces both separate. An empty field gives []."""
    values = []
    for entry in text.replace(",", " ").split():
        try:
            values.append(kind(entry))
        except ValueError:
            noun = "a whole number" if kind is int else "a number"
            raise SettingsError(f"{field}: '{entry}' is not {noun}") from None
    return values


def make_lods_keywords(settings):
    """The make_lods() keywords for \\p settings (anything with the panel's attribute names: the scene's
    property group, or a SimpleNamespace in a test). Raises SettingsError for a field that does not parse."""
    keywords = {
        "max_influences": settings.max_influences,
        "poses": settings.poses,
        "pose_clip": settings.pose_action,
        "max_error": settings.max_error,
        "anim_error": settings.anim_error,
        "max_joints": parse_list(settings.max_joints, int, "Max joints"),
    }
    if settings.lod_mode == "FACES":
        faces = parse_list(settings.faces, int, "Triangles")
        if not faces:
            raise SettingsError("Triangles: give one triangle count per LOD, e.g. 2000, 1000")
        keywords["faces"] = faces
    else:
        ratios = parse_list(settings.ratios, float, "Ratios")
        if not ratios:
            raise SettingsError("Ratios: give one ratio per LOD, e.g. 0.5, 0.25")
        keywords["ratios"] = ratios
    return keywords
