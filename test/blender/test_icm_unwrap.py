"""Headless tests of the Blender add-on ICM Unwrap (python/blender/icm_unwrap, doc/blender.md).

    blender -b --factory-startup --addons icm_unwrap --python test/blender/test_icm_unwrap.py \
        [-- --figure FILE.png [--preview FILE.png]]

with the add-on and the module icm installed in Blender's user scripts
(scripts/install_blender_addon.sh; ctest's blender.icm_unwrap installs them into the build
folder). Cases: a disk, a disk with a hole, a closed genus-1 mesh, a mesh with marked seams, a
quad mesh, n-gons, a selection in edit mode, and refused selections (non-manifold, degenerate).
Every unwrap is checked: UVs in [0, 1]^2, no flipped triangle (the signed UV area of each
triangle of each face positive), a UV discontinuity along every marked seam. A refused one
must raise Blender's error report (RuntimeError from bpy.ops) and leave the UVs as they were.
Exits 1 if any case fails (Blender's --python returns 0 otherwise). --figure FILE draws the
add-on's distortion picture of Suzanne's unwrap into FILE, --preview FILE renders Suzanne with a
checkerboard through those UVs (Cycles on the CPU): the pictures of the README.
"""

import math
import os
import sys
import tempfile
import time
import traceback

import addon_utils
import bmesh
import bpy
import numpy as np


def clear_scene():
    """Leaves object mode with no object, mesh or image."""
    if bpy.context.object is not None and bpy.context.object.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.images):
        for item in list(collection):
            collection.remove(item)


def object_from(name, verts, faces):
    """A new active mesh object of the given vertices and faces."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    return obj


def uv_array(obj):
    """The active UV layer's UVs, one row per loop, or None without a layer."""
    layer = obj.data.uv_layers.active
    if layer is None:
        return None
    uv = np.zeros(2 * len(obj.data.loops))
    layer.data.foreach_get("uv", uv)
    return uv.reshape(-1, 2)


def object_bmesh(obj):
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    return bm


def check_layout(obj, faces=None):
    """UVs in [0, 1]^2 and every triangle of the faces (all if None) positively oriented."""
    bm = object_bmesh(obj)
    layer = bm.loops.layers.uv.active
    assert layer is not None, "no UV layer"
    bm.faces.index_update()
    chosen = None if faces is None else set(faces)
    flipped = 0
    count = 0
    for tri in bm.calc_loop_triangles():
        if chosen is not None and tri[0].face.index not in chosen:
            continue
        p, q, r = (np.array(loop[layer].uv) for loop in tri)
        assert np.all(p >= -1e-6) and np.all(p <= 1 + 1e-6), f"UV {p} outside [0,1]^2"
        e1, e2 = q - p, r - p
        flipped += e1[0] * e2[1] - e1[1] * e2[0] <= 0
        count += 1
    bm.free()
    assert count > 0, "no triangle checked"
    assert flipped == 0, f"{flipped} of {count} triangles flipped or degenerate in UV"


def check_seams_open(obj):
    """Across every marked seam between two faces, the two sides' UVs differ; returns the count."""
    bm = object_bmesh(obj)
    layer = bm.loops.layers.uv.active
    seams = 0
    for edge in bm.edges:
        if not edge.seam or len(edge.link_faces) != 2:
            continue
        sides = [
            {l.vert.index: l[layer].uv.copy() for l in (loop, loop.link_loop_next)} for loop in edge.link_loops
        ]
        gap = max((sides[0][v] - sides[1][v]).length for v in sides[0])
        assert gap > 1e-6, f"seam edge {edge.index} has the same UVs on both sides"
        seams += 1
    bm.free()
    assert seams > 0, "no seam checked"
    return seams


def unwrap(**options):
    result = bpy.ops.uv.icm_unwrap(**options)
    assert result == {"FINISHED"}, result


def test_registered():
    assert addon_utils.check("icm_unwrap")[1], "the add-on is not loaded"
    assert hasattr(bpy.ops.uv, "icm_unwrap")
    texts = [f.__name__ for f in bpy.types.VIEW3D_MT_uv_map._dyn_ui_initialize()]
    assert "menu_func" in texts, f"not in the UV menu: {texts}"


def test_disk():
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=12, y_subdivisions=12, size=2)
    obj = bpy.context.active_object
    unwrap()
    check_layout(obj)


def test_data_disk():
    """examples/data/nefertiti.off (a disk, 562 faces) read by icm.read_mesh into a Blender mesh."""
    import icm

    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "data", "nefertiti.off")
    V, F, _ = icm.read_mesh(path)
    obj = object_from("nefertiti", V.tolist(), F.tolist())
    unwrap()
    check_layout(obj)
    # The UVs written back are ICM's map: the module's own run measures the same distortion.
    fuv = np.array([list(p.loop_indices) for p in obj.data.polygons])
    ours = icm.measure_distortion(V, F, uv_array(obj), fuv)["log_area_distortion"]
    direct = icm.parameterize(V, F, atlas=1024, padding=1).report["log_area_distortion"]
    assert abs(ours - direct) < 1e-6 * max(1.0, direct), (ours, direct)


def test_disk_with_hole():
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=12, y_subdivisions=12, size=2)
    obj = bpy.context.active_object
    bm = object_bmesh(obj)
    middle = [f for f in bm.faces if f.calc_center_median().length < 0.4]
    bmesh.ops.delete(bm, geom=middle, context="FACES_ONLY")
    bm.to_mesh(obj.data)
    bm.free()
    unwrap(cone_mode="NONE")
    check_layout(obj)


def test_torus():
    bpy.ops.mesh.primitive_torus_add(major_segments=32, minor_segments=12)
    obj = bpy.context.active_object
    path = os.path.join(tempfile.mkdtemp(), "torus_uv.png")
    unwrap(distortion_picture=True, picture_path=path, picture_size=128)
    check_layout(obj)
    assert os.path.getsize(path) > 0, "no picture written"
    assert "ICM distortion" in bpy.data.images


def test_marked_seams():
    """A UV sphere with the equator and a half meridian marked: two hemispheres, each cut open."""
    bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8)
    obj = bpy.context.active_object
    for edge in obj.data.edges:
        a, b = (obj.data.vertices[i].co for i in edge.vertices)
        equator = abs(a.z) < 1e-5 and abs(b.z) < 1e-5
        meridian = all(abs(p.y) < 1e-5 and p.x >= -1e-5 for p in (a, b))
        edge.use_seam = equator or meridian
    unwrap(cone_mode="NONE")
    check_layout(obj)
    seams = check_seams_open(obj)
    assert seams >= 16 + 8, seams


def island_boxes(obj):
    """The UV bounding box (lo, hi) of each piece of faces that no seam parts."""
    bm = object_bmesh(obj)
    layer = bm.loops.layers.uv.active
    seen, boxes = set(), []
    for start in bm.faces:
        if start.index in seen:
            continue
        stack, uvs = [start], []
        seen.add(start.index)
        while stack:
            face = stack.pop()
            uvs += [tuple(loop[layer].uv) for loop in face.loops]
            for edge in face.edges:
                for other in edge.link_faces:
                    if not edge.seam and other.index not in seen:
                        seen.add(other.index)
                        stack.append(other)
        boxes.append((np.min(uvs, axis=0), np.max(uvs, axis=0)))
    bm.free()
    return boxes


def test_margin():
    """The two hemispheres of a sphere cut at its equator: charts at least Margin apart."""
    bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8)
    obj = bpy.context.active_object
    for edge in obj.data.edges:
        edge.use_seam = all(abs(obj.data.vertices[i].co.z) < 1e-5 for i in edge.vertices)
    unwrap(cone_mode="COUNT", cone_count=2, margin=0.05)
    check_layout(obj)
    (lo0, hi0), (lo1, hi1) = island_boxes(obj)
    gap = max(np.max(lo1 - hi0), np.max(lo0 - hi1))
    assert gap >= 0.045, f"charts {gap:.4f} apart, Margin 0.05"


def test_quad_mesh():
    bpy.ops.mesh.primitive_cube_add()
    obj = bpy.context.active_object
    bm = object_bmesh(obj)
    bmesh.ops.subdivide_edges(bm, edges=bm.edges[:], cuts=4, use_grid_fill=True)
    bm.to_mesh(obj.data)
    bm.free()
    assert all(len(p.vertices) == 4 for p in obj.data.polygons)
    unwrap(margin=0.02)
    check_layout(obj)


def test_ngons():
    bpy.ops.mesh.primitive_cylinder_add(vertices=24)  # two 24-gons for caps
    obj = bpy.context.active_object
    assert max(len(p.vertices) for p in obj.data.polygons) == 24
    unwrap(cone_mode="COUNT", cone_count=4)
    check_layout(obj)


def test_edit_mode_selection():
    """Only the selected faces change; the others keep the grid's own UVs."""
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=10, y_subdivisions=10, size=2)
    obj = bpy.context.active_object
    mesh = obj.data
    chosen = [p.index for p in mesh.polygons if p.center.x < 0]
    before = uv_array(obj)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="DESELECT")
    bm = bmesh.from_edit_mesh(mesh)
    bm.faces.ensure_lookup_table()
    for i in chosen:
        bm.faces[i].select_set(True)
    bmesh.update_edit_mesh(mesh)
    unwrap()
    bpy.ops.object.mode_set(mode="OBJECT")
    after = uv_array(obj)
    other = [i for p in mesh.polygons if p.index not in chosen for i in p.loop_indices]
    assert np.array_equal(before[other], after[other]), "an unselected face's UVs changed"
    mine = [i for p in mesh.polygons if p.index in chosen for i in p.loop_indices]
    assert not np.allclose(before[mine], after[mine]), "the selected faces kept their UVs"
    check_layout(obj, chosen)


def test_edit_mode_without_uv_layer():
    """In edit mode on a mesh with no UV layer: one is made; with nothing selected: refused."""
    verts = [(x, y, 0.1 * x * y) for y in range(5) for x in range(5)]
    faces = [(y * 5 + x, y * 5 + x + 1, y * 5 + x + 6, y * 5 + x + 5) for y in range(4) for x in range(4)]
    obj = object_from("sheet", verts, faces)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="DESELECT")
    try:
        bpy.ops.uv.icm_unwrap()
    except RuntimeError as error:
        assert "no face selected" in str(error), error
    else:
        raise AssertionError("an empty selection was not refused")
    bpy.ops.mesh.select_all(action="SELECT")
    unwrap()
    bpy.ops.object.mode_set(mode="OBJECT")
    assert len(obj.data.uv_layers) == 1
    check_layout(obj)


def test_non_manifold_vertex():
    """Two triangles meeting at one vertex: split there, as ICM's readers split it, not refused."""
    verts = [(0, 0, 0), (1, 0, 0), (0.5, 1, 0), (-1, 0, 0), (-0.5, -1, 0)]
    obj = object_from("bowtie", verts, [(0, 1, 2), (0, 3, 4)])
    unwrap()
    check_layout(obj)


def check_refused(obj, word):
    """The unwrap fails with Blender's error report naming `word`, and changes no UV."""
    before = uv_array(obj)
    layers = len(obj.data.uv_layers)
    try:
        bpy.ops.uv.icm_unwrap()
    except RuntimeError as error:
        message = str(error)
    else:
        raise AssertionError("the bad selection was not refused")
    assert word in message and "Traceback" not in message, message
    assert len(obj.data.uv_layers) == layers, "a UV layer was added"
    after = uv_array(obj)
    assert (before is None and after is None) or np.array_equal(before, after), "the UVs changed"


def test_refused_non_manifold():
    """Three triangles on one edge."""
    verts = [(0, 0, 0), (1, 0, 0), (0.5, 1, 0), (0.5, -1, 0), (0.5, 0, 1)]
    obj = object_from("fin", verts, [(0, 1, 2), (1, 0, 3), (0, 1, 4)])
    obj.data.uv_layers.new(name="UVMap")
    obj.data.uv_layers.active.data.foreach_set("uv", np.linspace(0, 1, 18))
    check_refused(obj, "non-manifold")


def test_refused_degenerate():
    """A strip of triangles, one of them with three collinear corners; no UV layer before."""
    verts = [(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0), (1, 1, 0)]
    obj = object_from("flat", verts, [(0, 1, 4), (0, 4, 3), (0, 1, 2)])
    check_refused(obj, "degenerate")


def test_refused_by_icm():
    """A closed mesh with Cones: None: ICM's own error, reported, the primitive's UVs kept."""
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2)
    obj = bpy.context.active_object
    obj.data.uv_layers.new(name="UVMap")
    obj.data.uv_layers.active.data.foreach_set("uv", np.linspace(0, 1, 2 * len(obj.data.loops)))
    before = uv_array(obj)
    try:
        bpy.ops.uv.icm_unwrap(cone_mode="NONE")
    except RuntimeError as error:
        assert "ICM Unwrap" in str(error) and "Traceback" not in str(error), error
    else:
        raise AssertionError("a closed mesh without cones was not refused")
    assert np.array_equal(before, uv_array(obj)), "the UVs changed"


def suzanne():
    """Blender's Suzanne, subdivided twice (7872 quads), turned a little towards the camera."""
    bpy.ops.mesh.primitive_monkey_add(rotation=(0, 0, math.radians(-25)))
    obj = bpy.context.active_object
    modifier = obj.modifiers.new("subdivision", "SUBSURF")
    modifier.levels = 2
    bpy.ops.object.modifier_apply(modifier=modifier.name)
    bpy.ops.object.shade_smooth()
    return obj


def checker_material(obj):
    """A checkerboard through the active UV layer."""
    material = bpy.data.materials.new("checker")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    checker = nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = 48
    checker.inputs["Color1"].default_value = (0.9, 0.9, 0.9, 1)
    checker.inputs["Color2"].default_value = (0.15, 0.15, 0.2, 1)
    links.new(nodes.new("ShaderNodeTexCoord").outputs["UV"], checker.inputs["Vector"])
    links.new(checker.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
    obj.data.materials.append(material)


def render(path):
    """Renders the scene with Cycles on the CPU (headless) into path."""
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.location, camera.rotation_euler = (0, -4.2, 0.3), (math.radians(86), 0, 0)
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.rotation_euler, sun.data.energy = (math.radians(50), math.radians(-20), math.radians(-30)), 3
    scene = bpy.context.scene
    for obj in (camera, sun):
        scene.collection.objects.link(obj)
    scene.camera = camera
    scene.render.engine = "CYCLES"
    scene.cycles.device, scene.cycles.samples, scene.cycles.use_denoising = "CPU", 16, False
    scene.render.resolution_x = scene.render.resolution_y = 512
    scene.world.color = (0.3, 0.3, 0.3)
    scene.render.filepath = os.path.abspath(path)
    bpy.ops.render.render(write_still=True)


def figures(picture, preview):
    """The README's pictures: the distortion picture of Suzanne's unwrap (automatic cones) and,
    if preview, Suzanne rendered with a checkerboard through its UVs."""
    clear_scene()
    obj = suzanne()
    bpy.ops.uv.icm_unwrap(distortion_picture=True, picture_path=os.path.abspath(picture), picture_size=768)
    check_layout(obj)
    print(f"figure: {picture}")
    if preview:
        checker_material(obj)
        render(preview)
        print(f"figure: {preview}")


TESTS = [
    test_registered, test_disk, test_data_disk, test_disk_with_hole, test_torus, test_marked_seams, test_margin, test_quad_mesh,
    test_ngons, test_edit_mode_selection, test_refused_non_manifold, test_refused_degenerate,
    test_edit_mode_without_uv_layer, test_non_manifold_vertex, test_refused_by_icm,
]


def main():
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    failures = 0
    for test in TESTS:
        clear_scene()
        start = time.perf_counter()
        try:
            test()
            print(f"PASS {test.__name__} ({time.perf_counter() - start:.2f} s)")
        except Exception:  # every failure is counted, the other cases still run
            traceback.print_exc()
            print(f"FAIL {test.__name__}")
            failures += 1
    if "--figure" in argv:
        preview = argv[argv.index("--preview") + 1] if "--preview" in argv else None
        figures(argv[argv.index("--figure") + 1], preview)
    print(f"{len(TESTS) - failures} of {len(TESTS)} passed")
    sys.stdout.flush()
    sys.exit(1 if failures else 0)


main()
