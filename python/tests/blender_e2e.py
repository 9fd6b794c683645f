#!/usr/bin/env python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""End-to-end test of the Blender add-on python/blender/meshquilt_addon.py (not collected by pytest).

Installs the add-on from its file into a temporary user-scripts folder (nothing reaches
~/.config/blender), enables it, imports tests/data/surface/eight.obj and swatches/pebbles.obj, runs
``bpy.ops.object.meshquilt_decorate`` and checks the new object against a direct
``meshquilt.decorate`` call on the same arrays, then the error, cancellation, field, invoke and
missing-module paths, and finally disables the add-on. Prints one summary line; exits 1 on failure.

Needs Blender as a Python module (Python 3.11, ``bpy`` 4.2 or later) and meshquilt importable: either
installed, on PYTHONPATH, or built in <repo>/build*/python (found automatically)::

    PYTHONPATH=build-main/python /tmp/bpyenv/bin/python python/tests/blender_e2e.py

About 20 s on 2 cores. (Set BLENDER_E2E_KEEP=1 to keep the temporary folder.)
"""
import glob
import hashlib
import os
import shutil
import sys
import tempfile
import time
import traceback

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ADDON_FILE = os.path.join(ROOT, "python", "blender", "meshquilt_addon.py")
BASE_OBJ = os.path.join(ROOT, "tests", "data", "surface", "eight.obj")
SWATCH_OBJ = os.path.join(ROOT, "swatches", "pebbles.obj")
SCALE, SEED = 0.3, 3

# Blender reads its user folders from these at start-up: point them all at a temporary folder
# before bpy is imported, so the add-on is installed there and no preference leaks out.
TMP = tempfile.mkdtemp(prefix="meshquilt_blender_e2e_")
for var, sub in (("BLENDER_USER_RESOURCES", ""), ("BLENDER_USER_CONFIG", "config"),
                 ("BLENDER_USER_SCRIPTS", "scripts"), ("BLENDER_USER_DATAFILES", "datafiles"),
                 ("BLENDER_USER_EXTENSIONS", "extensions")):
    os.environ[var] = os.path.join(TMP, sub)


def import_meshquilt():
    """meshquilt as installed / on PYTHONPATH, else from the newest <repo>/build*/python."""
    try:
        import meshquilt  # noqa: PLC0415
        return meshquilt
    except ImportError:
        pass
    builds = glob.glob(os.path.join(ROOT, "build*", "python", "meshquilt", "_meshquilt*.so"))
    if not builds:
        raise SystemExit("blender_e2e: cannot import meshquilt; install it or set PYTHONPATH=<build>/python")
    newest = max(builds, key=os.path.getmtime)
    sys.path.insert(0, os.path.dirname(os.path.dirname(newest)))
    import meshquilt  # noqa: PLC0415
    return meshquilt


meshquilt = import_meshquilt()
import bpy  # noqa: E402
import numpy as np  # noqa: E402

CHECKS = []


def check(condition, what):
    """Record one check; raise AssertionError (ending the test) when it fails."""
    CHECKS.append(what)
    if not condition:
        raise AssertionError(what)


def expect_error(fragment, **kwargs):
    """Run the operator expecting an error report: bpy.ops raises RuntimeError with its text."""
    try:
        result = bpy.ops.object.meshquilt_decorate(**kwargs)
    except RuntimeError as e:
        message = str(e)
        check(fragment.lower() in message.lower(), f"error for {kwargs} mentions '{fragment}' (got: {message.strip()})")
        return message.strip()
    raise AssertionError(f"operator with {kwargs} returned {result} instead of reporting an error")


def co_array(obj):
    co = np.empty(len(obj.data.vertices) * 3, dtype=np.float32)
    obj.data.vertices.foreach_get("co", co)
    return co.reshape(-1, 3)


def snapshot(obj):
    return len(obj.data.vertices), len(obj.data.polygons), hashlib.sha256(co_array(obj).tobytes()).hexdigest(), \
        tuple(tuple(r) for r in obj.matrix_world)


def import_obj(path):
    before = set(bpy.data.objects)
    bpy.ops.wm.obj_import(filepath=path)
    (obj,) = set(bpy.data.objects) - before
    return obj


def result_arrays(obj):
    """Faces (f, 3), element ids (f,) and vertices (n, 3) of a result object."""
    mesh = obj.data
    loops = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.loops.foreach_get("vertex_index", loops)
    attr = mesh.attributes.get("meshquilt_element")
    ids = np.empty(len(mesh.polygons), dtype=np.int32)
    attr.data.foreach_get("value", ids)
    return loops.reshape(-1, 3), ids, co_array(obj)


def new_objects(before):
    return [o for o in bpy.data.objects if o not in before]


def run():
    t_start = time.perf_counter()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    addons_dir = bpy.utils.user_resource("SCRIPTS", path="addons")
    check(os.path.realpath(addons_dir).startswith(os.path.realpath(TMP)),
          f"user scripts folder is the temporary one ({addons_dir})")

    # -- install and enable --
    check(bpy.ops.preferences.addon_install(filepath=ADDON_FILE, overwrite=True) == {"FINISHED"}, "addon_install")
    check(os.path.isfile(os.path.join(addons_dir, "meshquilt_addon.py")), "add-on file installed in the temporary folder")
    bpy.ops.preferences.addon_enable(module="meshquilt_addon")
    addon = sys.modules.get("meshquilt_addon")
    check(addon is not None and os.path.realpath(addon.__file__).startswith(os.path.realpath(TMP)),
          "the installed copy of the add-on is the one enabled")
    check(hasattr(bpy.types, "OBJECT_OT_meshquilt_decorate") and "meshquilt_addon" in bpy.context.preferences.addons,
          "operator registered and add-on enabled")
    check(addon.load_meshquilt() is not None, f"the add-on imports meshquilt ({addon._import_error})")

    # -- scene --
    scene, view_layer = bpy.context.scene, bpy.context.view_layer
    base = import_obj(BASE_OBJ)
    swatch = import_obj(SWATCH_OBJ)
    view_layer.objects.active = base
    base_before = snapshot(base)

    # -- the main run --
    objects_before = set(bpy.data.objects)
    t0 = time.perf_counter()
    result = bpy.ops.object.meshquilt_decorate(swatch=swatch.name, scale=SCALE, seed=SEED)  # raises on an error report
    t_operator = time.perf_counter() - t0
    check(result == {"FINISHED"}, f"operator returned FINISHED (got {result})")
    added = new_objects(objects_before)
    check(len(added) == 1, f"exactly one new object (got {[o.name for o in added]})")
    out = added[0]
    check(out.name == base.name + "_meshquilt" and out.type == "MESH", f"new object named {base.name}_meshquilt ({out.name})")
    check(base.users_collection[0] in out.users_collection, "new object linked to the base's collection")
    check(np.allclose(np.array(out.matrix_world), np.eye(4)), "new object has identity transform")
    num_faces = len(out.data.polygons)
    check(num_faces > 0, "new object has faces")
    attr = out.data.attributes.get("meshquilt_element")
    check(attr is not None and attr.domain == "FACE" and attr.data_type == "INT",
          "face attribute meshquilt_element (INT, FACE)")
    faces, ids, verts = result_arrays(out)
    num_elements = out.get("meshquilt_elements")
    check(isinstance(num_elements, int) and num_elements > 10, f"stored element count > 10 ({num_elements})")
    check(ids.min() >= 0 and ids.max() < num_elements, "element ids in [0, meshquilt_elements)")
    check(len(np.unique(ids)) == num_elements, "every element id is used")
    check(out.get("meshquilt_faces") == num_faces and out.get("meshquilt_seconds", 0) > 0, "stored faces and seconds")
    col = out.data.color_attributes.get("meshquilt_color")
    check(col is not None and col.domain == "CORNER" and out.data.color_attributes.active_color_name == col.name,
          "active colour attribute meshquilt_color")
    mat = out.data.materials[0] if out.data.materials else None
    check(mat is not None and any(n.type == "ATTRIBUTE" and n.attribute_name == "meshquilt_color"
                                  for n in mat.node_tree.nodes), "material reads meshquilt_color")
    check(snapshot(base) == base_before, "base object unchanged")

    # -- determinism: the same arrays and seed through meshquilt.decorate directly --
    depsgraph = bpy.context.evaluated_depsgraph_get()
    bv, bf = addon.mesh_arrays(base, depsgraph)
    sv, sf = addon.mesh_arrays(swatch, depsgraph)
    check(bv.dtype == np.float64 and bf.dtype == np.int32 and bv.shape[1] == bf.shape[1] == 3, "mesh_arrays dtypes")
    check(len(bf) == len(base.data.polygons) and len(sf) == len(swatch.data.polygons),
          "mesh_arrays: one row per triangle (both OBJ files hold triangles)")
    direct = meshquilt.decorate(bv, bf, sv, sf, scale=SCALE, seed=SEED)
    check(len(direct.faces) == num_faces and direct.num_elements == num_elements,
          f"same faces and elements as meshquilt.decorate ({num_faces}/{len(direct.faces)}, "
          f"{num_elements}/{direct.num_elements})")
    check(np.array_equal(faces, direct.faces) and np.array_equal(ids, direct.element_ids), "same triangles and element ids")
    check(np.allclose(verts, direct.vertices, atol=1e-5), "same vertex positions")

    # -- errors: a clear message, no new object, no orphan data --
    view_layer.objects.active = base
    objects_before, meshes_before = set(bpy.data.objects), len(bpy.data.meshes)
    empty = bpy.data.objects.new("an_empty", None)
    scene.collection.objects.link(empty)
    objects_before.add(empty)
    expect_error("does not exist", swatch="no_such_object", scale=SCALE)
    expect_error("not a mesh", swatch=empty.name, scale=SCALE)
    expect_error("is the object to decorate", swatch=base.name, scale=SCALE)
    expect_error("no attribute", swatch=swatch.name, scale=SCALE, field_attribute="no_such_attribute")
    flat = bpy.data.objects.new("flat", bpy.data.meshes.new("flat"))
    flat.data.from_pydata([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [], [(0, 1, 2, 3)])
    scene.collection.objects.link(flat)
    objects_before.add(flat)
    meshes_before += 1
    library_message = expect_error("has no thickness", swatch=flat.name, scale=SCALE)  # InvalidInputError from the library
    check(not new_objects(objects_before) and len(bpy.data.meshes) == meshes_before, "no new object or mesh after errors")

    # -- cancellation through Job's progress callback: cancelled on the first call --
    calls = []

    def cancel_at_once(job, stage, fraction):
        calls.append((stage, fraction))
        job.cancel()

    addon.Job.observers.append(cancel_at_once)
    try:
        t0 = time.perf_counter()
        result = bpy.ops.object.meshquilt_decorate(swatch=swatch.name, scale=SCALE, seed=SEED)
        t_cancel = time.perf_counter() - t0
    finally:
        addon.Job.observers.remove(cancel_at_once)
    check(result == {"CANCELLED"}, f"cancelled run returns CANCELLED (got {result})")
    check(len(calls) == 1, f"progress callback called once before stopping (got {len(calls)})")
    check(not new_objects(objects_before) and len(bpy.data.meshes) == meshes_before, "no new object after cancelling")

    # -- the modal (UI) path's logic, driven by hand: bpy as a module has no event loop, so the
    #    operator's modal() runs on a stand-in with a real Job and synthetic events --
    op_class = addon.OBJECT_OT_meshquilt_decorate

    class StandIn:
        modal, _show_status, _end_modal, _finish = op_class.modal, op_class._show_status, op_class._end_modal, op_class._finish
        seed = SEED

        def __init__(self, job):
            self._job, self._timer, self.reports = job, None, []
            self._base_name, self._swatch_name = base.name, swatch.name

        def report(self, kind, message):
            self.reports.append((set(kind), message))

    class Event:
        def __init__(self, type_, value="NOTHING"):
            self.type, self.value = type_, value

    def drive(stand_in, events):
        """Feed events, then timer ticks until modal() ends; its return value."""
        for event in events:
            state = stand_in.modal(bpy.context, event)
            if event.type.startswith("WHEEL"):
                check(state == {"PASS_THROUGH"}, "modal: view navigation passes through")
            elif state != {"RUNNING_MODAL"}:
                return state
        deadline = time.perf_counter() + 60
        while time.perf_counter() < deadline:
            time.sleep(0.05)
            state = stand_in.modal(bpy.context, Event("TIMER"))
            if state != {"RUNNING_MODAL"}:
                return state
        raise AssertionError("modal() did not end within 60 s")

    objects_before, meshes_before = set(bpy.data.objects), len(bpy.data.meshes)
    job = addon.Job(meshquilt.decorate, bv, bf, sv, sf, scale=SCALE, seed=SEED).start()
    stand_in = StandIn(job)
    state = drive(stand_in, [Event("MOUSEMOVE"), Event("WHEELUPMOUSE", "PRESS"), Event("ESC", "PRESS")])
    check(state == {"CANCELLED"} and job.cancelled and isinstance(job.error, meshquilt.CancelledError),
          f"modal: Esc cancels the running job ({state}, {job.error!r})")
    check(any("WARNING" in k and "cancelled" in m for k, m in stand_in.reports), "modal: cancellation reported as a warning")
    check(not new_objects(objects_before) and len(bpy.data.meshes) == meshes_before, "modal: nothing added when cancelled")
    stages = []

    def finished_job(progress):  # the result computed above, through the same progress path
        for stage, fraction in (("shell map", 1.0), ("quilting", 0.5), ("quilting", 1.0)):
            progress(stage, fraction)
            stages.append(stage)
        return direct

    job = addon.Job(finished_job).start()
    stand_in = StandIn(job)
    state = drive(stand_in, [Event("MOUSEMOVE")])
    check(state == {"FINISHED"} and job.overall == 1.0 and len(stages) == 3, f"modal: a finished job gives FINISHED ({state})")
    (modal_out,) = new_objects(objects_before)
    check(len(modal_out.data.polygons) == num_faces and modal_out["meshquilt_elements"] == num_elements,
          "modal: result object built")
    bpy.data.objects.remove(modal_out)

    # -- a POINT-domain guidance field, and the UI path (invoke falls back to execute in background) --
    view_layer.objects.active = base
    field = base.data.attributes.new("flow", "FLOAT_VECTOR", "POINT")
    co = co_array(base).astype(np.float64)
    axis = np.argmax(co.max(axis=0) - co.min(axis=0))  # along the eight's long axis
    vectors = np.zeros_like(co)
    vectors[:, axis] = 1.0
    field.data.foreach_set("vector", vectors.astype(np.float32).ravel())
    settings = scene.meshquilt
    settings.swatch, settings.scale, settings.seed, settings.field_attribute = swatch, SCALE, SEED, "flow"
    objects_before = set(bpy.data.objects)
    result = bpy.ops.object.meshquilt_decorate("INVOKE_DEFAULT")  # options from the sidebar's settings
    check(result == {"FINISHED"}, f"invoke with the sidebar's settings and a field: FINISHED (got {result})")
    (guided,) = new_objects(objects_before)
    check(guided.name.startswith(base.name + "_meshquilt") and guided["meshquilt_elements"] > 10,
          f"guided result {guided.name} with {guided['meshquilt_elements']} elements")
    guided_faces = result_arrays(guided)[0]
    check(guided_faces.shape != faces.shape or not np.array_equal(guided_faces, faces), "the field changes the result")
    data = addon.read_mesh_data(base, bpy.context.evaluated_depsgraph_get(), "flow")
    check(data.field_vertices is not None and data.field_vertices.shape == data.vertices.shape, "field read per vertex")

    # -- missing module: poll explains how to install it --
    saved = addon._meshquilt, addon._import_error
    addon._meshquilt, addon._import_error = None, "ImportError: No module named 'meshquilt' (simulated)"
    try:
        expect_error("pip install", swatch=swatch.name)
    finally:
        addon._meshquilt, addon._import_error = saved

    # -- disable: unregister cleans up --
    bpy.ops.preferences.addon_disable(module="meshquilt_addon")
    check(not hasattr(bpy.types, "OBJECT_OT_meshquilt_decorate") and not hasattr(bpy.types.Scene, "meshquilt"),
          "addon_disable unregisters everything")

    total = time.perf_counter() - t_start
    print(f"blender_e2e: OK: {len(CHECKS)} checks; {num_elements} elements, {num_faces} faces in {t_operator:.1f} s "
          f"(eight + pebbles, scale {SCALE}, seed {SEED}); cancelled after {t_cancel:.2f} s; "
          f"flat swatch: '{library_message.splitlines()[0]}'; Blender {bpy.app.version_string}, "
          f"meshquilt {meshquilt.__version__}; {total:.1f} s")


def main():
    status = 0
    try:
        run()
    except AssertionError as e:
        print(f"blender_e2e: FAILED: {e} (after {len(CHECKS) - 1} passing checks)", file=sys.stderr)
        status = 1
    except BaseException:
        traceback.print_exc()
        print(f"blender_e2e: FAILED with an exception (after {len(CHECKS)} passing checks)", file=sys.stderr)
        status = 1
    finally:
        if not os.environ.get("BLENDER_E2E_KEEP"):
            shutil.rmtree(TMP, ignore_errors=True)
    sys.stdout.flush()
    sys.stderr.flush()
    # bpy 4.5 as a module can hang in a static destructor at exit (a thread waiting on a condition
    # variable being destroyed); leave at once with the status.
    os._exit(status)


if __name__ == "__main__":
    main()
