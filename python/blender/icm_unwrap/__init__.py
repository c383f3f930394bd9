"""ICM Unwrap: Blender's UV menu unwraps through ICM (a conformal map with cones, least area distortion).

The operator `uv.icm_unwrap` unwraps the selected faces (all of them in object mode) of the
active mesh with `icm.parameterize`: n-gons cut into triangles internally, the edges marked as
seams the user's cut, every chart packed into [0, 1]^2 at one texel density with Blender's
"Margin" between them, the UVs written back per loop of the original faces into the active UV
layer (a new one if there is none). A selection ICM cannot unwrap (non-manifold, degenerate) or
a failed run is reported with Blender's error report and leaves the mesh as it was: everything
is computed first, the UVs are written only once it has succeeded.

It needs the Python module `icm` of this repository built for Blender's Python (Debian's
Blender runs on the system's /usr/bin/python3): scripts/install_blender_addon.sh builds it and
installs both into Blender's user scripts (doc/blender.md).
"""

import bmesh
import bpy
import numpy as np

from . import arrays as mesh_arrays
from . import cut
from . import picture

bl_info = {
    "name": "ICM Unwrap",
    "author": "ICM",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "3D Viewport > Edit Mode > UV > ICM Unwrap",
    "description": "Conformal unwrap with cones and least area distortion (inverse curvature map)",
    "category": "UV",
}

CONE_MODES = [
    ("AUTO", "Automatic", "Cones where the surface needs them (ICM's default)"),
    ("NONE", "None", "No cone: one chart per disk; a closed piece fails"),
    ("COUNT", "Count", "Exactly Cone Count cones on each piece (connected component)"),
]


def import_icm():
    """The module icm, or None when it is not where Blender's Python looks."""
    try:
        import icm
    except ImportError:
        return None
    return icm


def cones_argument(mode, count):
    """The `cones` argument of icm.parameterize."""
    return {"AUTO": "auto", "NONE": 0}.get(mode, count)


def padding_texels(margin, size):
    """Blender's margin (a fraction of the UV square) as ICM's padding in texels of the atlas."""
    return int(round(max(0.0, margin) * size))


def check_result(result, arrays):
    """The UVs, or SelectionError when they are not what the UV layer may take."""
    uv = np.asarray(result.uv, dtype=np.float64)
    fuv = np.asarray(result.fuv, dtype=np.int64)
    if fuv.shape != arrays.F.shape or len(uv) == 0 or not np.all(np.isfinite(uv)):
        raise mesh_arrays.SelectionError("ICM returned no usable UVs")
    if int(result.report.get("flipped_faces", 0)) != 0:
        raise mesh_arrays.SelectionError(f"ICM's layout has {result.report['flipped_faces']} flipped faces")
    return np.clip(uv, 0.0, 1.0), fuv


def loop_uvs(arrays, uv, fuv):
    """{loop: (u, v)} and the number of loops that got two UVs (an n-gon that ICM cut through)."""
    chosen = {}
    conflicts = 0
    for t, tri in enumerate(arrays.corner_loops):
        for c in range(3):
            value = (float(uv[fuv[t, c], 0]), float(uv[fuv[t, c], 1]))
            old = chosen.setdefault(tri[c], value)
            if old != value:
                conflicts += 1
    return chosen, conflicts


def write_uvs(bm, faces, uvs):
    """Writes the UVs into the active UV layer of bm, made if there is none.

    Adding a layer reallocates the loops' data, which leaves the Python loops stale: the loops
    are named by face index and corner first, and found again after.
    """
    corners = [(face.index, i, uvs[loop]) for face in faces for i, loop in enumerate(face.loops) if loop in uvs]
    layer = bm.loops.layers.uv.active
    if layer is None:
        layer = bm.loops.layers.uv.new("UVMap")
    bm.faces.ensure_lookup_table()
    for face, corner, value in corners:
        bm.faces[face].loops[corner][layer].uv = value


class MeshAccess:
    """The bmesh of the active mesh in either mode, and how to hand it back."""

    def __init__(self, obj):
        self.mesh = obj.data
        self.edit = obj.mode == "EDIT"
        if self.edit:
            self.bm = bmesh.from_edit_mesh(self.mesh)
        else:
            self.bm = bmesh.new()
            self.bm.from_mesh(self.mesh)

    def commit(self):
        """Puts the changed bmesh back into the mesh."""
        if self.edit:
            bmesh.update_edit_mesh(self.mesh)
        else:
            self.bm.to_mesh(self.mesh)
            self.mesh.update()

    def free(self):
        """Frees the object-mode copy (the edit-mode bmesh is Blender's)."""
        if not self.edit:
            self.bm.free()


class UV_OT_icm_unwrap(bpy.types.Operator):
    """Unwrap the selected faces conformally with cones and least area distortion (ICM)"""

    bl_idname = "uv.icm_unwrap"
    bl_label = "ICM Unwrap"
    bl_options = {"REGISTER", "UNDO"}

    cone_mode: bpy.props.EnumProperty(name="Cones", items=CONE_MODES, default="AUTO")
    cone_count: bpy.props.IntProperty(
        name="Cone Count", description="The number of cones of each piece when Cones is Count", default=8, min=1, max=1000
    )
    margin: bpy.props.FloatProperty(
        name="Margin", description="Space between charts, a fraction of the UV square",
        default=0.001, min=0.0, max=0.5, precision=3, step=0.1,
    )
    atlas_size: bpy.props.IntProperty(
        name="Texture Size", description="The texture the atlas is packed for, in texels (ICM's --atlas)",
        default=1024, min=64, max=16384,
    )
    distortion_picture: bpy.props.BoolProperty(
        name="Distortion Picture",
        description="Draw the layout, faces coloured by log area ratio, into the image 'ICM distortion'",
        default=False,
    )
    picture_path: bpy.props.StringProperty(
        name="Picture File", description="Also save the picture as this PNG (empty: only the image)",
        default="", subtype="FILE_PATH",
    )
    picture_size: bpy.props.IntProperty(name="Picture Size", default=512, min=64, max=4096)

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == "MESH"

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "cone_mode")
        row = layout.row()
        row.enabled = self.cone_mode == "COUNT"
        row.prop(self, "cone_count")
        layout.prop(self, "margin")
        layout.prop(self, "atlas_size")
        layout.prop(self, "distortion_picture")
        if self.distortion_picture:
            layout.prop(self, "picture_path")
            layout.prop(self, "picture_size")

    def unwrap(self, icm, access):
        """Runs ICM on the faces to unwrap: (arrays, result, uv, fuv), or raises with the reason."""
        arrays = mesh_arrays.build(access.bm, selected_only=access.edit)
        packing = {"atlas": self.atlas_size, "padding": padding_texels(self.margin, self.atlas_size)}
        cones = cones_argument(self.cone_mode, self.cone_count)
        result = icm.parameterize(arrays.V, arrays.F, cones=cones, **packing)
        seams = cut.off_diagonals(arrays, result.seams)
        if seams is not None:
            # Again on ICM's cut moved off the diagonals, with the first run's cones and angles
            # (cones=0: no more on the pieces without seams, which had none); if that fails
            # the first run stands, and the n-gons it cut through are reported.
            try:
                result = icm.parameterize(
                    arrays.V, arrays.F, cones=0, seams=seams, cone=cut.cones_for_moved_cut(arrays, result, seams),
                    **packing,
                )
            except icm.Error:
                pass
        uv, fuv = check_result(result, arrays)
        return arrays, result, uv, fuv

    def summary(self, result, cones, conflicts):
        """The line of the status bar: charts, cones, distortion."""
        report = result.report
        text = (
            f"ICM Unwrap: {report.get('faces', 0)} triangles, {result.charts} charts, "
            f"{cones} cones, log area distortion {report.get('log_area_distortion', 0.0):.4g}, "
            f"{report.get('flipped_faces', 0)} flipped"
        )
        if conflicts:
            text += f"; {conflicts} corners of n-gons cut through by ICM's seams"
        if report.get("faces_reoriented", 0):
            # ICM lays them out with their neighbours' orientation: the texture runs on across
            # them, their UVs wind the other way (Mesh > Normals > Recalculate Outside fixes it).
            text += f"; {report['faces_reoriented']} triangles with normals against their neighbours'"
        return text

    def execute(self, context):
        icm = import_icm()
        if icm is None:
            self.report({"ERROR"}, "ICM Unwrap: the Python module icm is not installed "
                                   "(run scripts/install_blender_addon.sh of the ICM repository)")
            return {"CANCELLED"}
        access = MeshAccess(context.active_object)
        try:
            arrays, result, uv, fuv = self.unwrap(icm, access)
            uvs, conflicts = loop_uvs(arrays, uv, fuv)
            if self.distortion_picture:
                path = bpy.path.abspath(self.picture_path) if self.picture_path else ""
                picture.distortion_picture(bpy, arrays, uv, fuv, self.picture_size, path)
            write_uvs(access.bm, arrays.faces, uvs)
            access.commit()
        except (mesh_arrays.SelectionError, icm.Error, ValueError, RuntimeError, OSError) as error:
            self.report({"ERROR"}, f"ICM Unwrap: {error}")
            return {"CANCELLED"}
        except Exception as error:  # never a traceback in the user's face: a report, the mesh kept
            self.report({"ERROR"}, f"ICM Unwrap failed: {type(error).__name__}: {error}")
            return {"CANCELLED"}
        finally:
            access.free()
        # The cones as the layout has them (interior vertices whose UV angle is not 360
        # degrees): ICM's count also names the flat ends of a cut given to it.
        cones = len(cut.cones_of(arrays, result))
        self.report({"WARNING"} if conflicts else {"INFO"}, self.summary(result, cones, conflicts))
        return {"FINISHED"}


def menu_func(self, context):
    self.layout.separator()
    self.layout.operator(UV_OT_icm_unwrap.bl_idname)


MENUS = ("VIEW3D_MT_uv_map", "IMAGE_MT_uvs_unwrap")


def register():
    bpy.utils.register_class(UV_OT_icm_unwrap)
    for name in MENUS:
        menu = getattr(bpy.types, name, None)
        if menu is not None:
            menu.append(menu_func)


def unregister():
    for name in MENUS:
        menu = getattr(bpy.types, name, None)
        if menu is not None:
            menu.remove(menu_func)
    bpy.utils.unregister_class(UV_OT_icm_unwrap)
