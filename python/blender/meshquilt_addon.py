# SPDX-License-Identifier: AGPL-3.0-or-later
"""meshquilt for Blender: cover the active mesh with a geometric texture grown from a swatch object.

A single-file (legacy) add-on for Blender 4.2 and later. It needs meshquilt's Python module
(``import meshquilt``) inside Blender's own Python; install it with Blender's interpreter::

    <blender>/<version>/python/bin/python3.11 -m pip install /path/to/meshquilt

(the source tree: pip builds the C++ library and the module), or point the add-on's preferences at a
folder that holds a built ``meshquilt`` package (e.g. ``<build>/python``).

Use: select the base mesh, pick a swatch object (a slab of separate closed elements: pebbles,
rivets, rings...) in the sidebar tab *meshquilt* (N panel of the 3D viewport) and press *Decorate*,
or use Object > Decorate with meshquilt. Esc or right-click cancels. The result is a new object
``<base>_meshquilt`` with identity transform, in world space, beside the base in its collection:

* face attribute ``meshquilt_element`` (INT): the element each face belongs to;
* colour attribute ``meshquilt_color`` (corner domain): one colour per element, shown in renders by the
  material ``meshquilt_elements`` (an Attribute node into the Principled BSDF);
* custom properties ``meshquilt_elements``, ``meshquilt_faces``, ``meshquilt_seconds``,
  ``meshquilt_seed``, ``meshquilt_swatch``, ``meshquilt_report`` (the full report, JSON) and
  ``meshquilt_warnings``.

From a script (or ``blender -b``, where modal operators cannot run; the call then blocks)::

    bpy.context.view_layer.objects.active = base
    bpy.ops.object.meshquilt_decorate(swatch="pebbles", scale=0.1, seed=3)

Options not given take the sidebar's values (``scene.meshquilt``; by default the same as the
operator's defaults). It returns {'CANCELLED'} with an error report (a RuntimeError from bpy.ops)
on bad input, and with a warning when cancelled; nothing is added then.
Both base and swatch are read as evaluated (modifiers applied), triangulated, in world space.
The pieces are usable on their own: :func:`mesh_arrays`, :func:`build_result_object`, :class:`Job`.
"""

bl_info = {
    "name": "meshquilt",
    "author": "meshquilt contributors",
    "version": (0, 1, 0),
    "blender": (4, 2, 0),
    "location": "View3D > Sidebar > meshquilt; Object > Decorate with meshquilt",
    "description": "Cover a mesh with a geometric texture (pebbles, rivets, chain mail) grown from a swatch object",
    "category": "Object",
}

import importlib
import json
import os
import sys
import threading
import time

import bpy
import numpy as np
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    IntProperty,
    PointerProperty,
    StringProperty,
)

ELEMENT_ATTRIBUTE = "meshquilt_element"
COLOR_ATTRIBUTE = "meshquilt_color"
MATERIAL_NAME = "meshquilt_elements"
RESULT_SUFFIX = "_meshquilt"

# ---------------------------------------------------------------------------------------------
# The Python module, imported lazily so that the add-on registers without it.

_meshquilt = None  # the module once imported
_import_error = None  # why it could not be imported (str)


def install_hint():
    """How to make ``import meshquilt`` work inside this Blender (one paragraph). The fix comes
    first: Blender cuts long poll messages."""
    return (
        f"meshquilt's Python module is missing: pip install it into Blender's Python, "
        f"\"{sys.executable} -m pip install /path/to/meshquilt\" (the meshquilt source tree), or set the "
        "folder that holds a built 'meshquilt' package (e.g. <build>/python) in the add-on's preferences, "
        f"then restart Blender or re-enable the add-on ({_import_error})"
    )


def load_meshquilt(extra_path="", retry=False):
    """Import meshquilt (after adding ``extra_path`` to sys.path if given); the module or None.

    A failed import is remembered (polls call this on every redraw); ``retry`` or a new
    ``extra_path`` tries again."""
    global _meshquilt, _import_error
    if _meshquilt is not None:
        return _meshquilt
    if _import_error is not None and not retry and not extra_path:
        return None
    if extra_path:
        folder = os.path.normpath(bpy.path.abspath(extra_path))
        if folder not in sys.path:
            sys.path.insert(0, folder)
        importlib.invalidate_caches()
    try:
        import meshquilt  # noqa: PLC0415 (optional dependency)
    except Exception as e:  # ImportError, or a broken build raising something else
        _import_error = f"{type(e).__name__}: {e}"
        return None
    _meshquilt, _import_error = meshquilt, None
    return meshquilt


def _prefs_module_path():
    addon = bpy.context.preferences.addons.get(__name__)
    return addon.preferences.module_path if addon and addon.preferences else ""


# ---------------------------------------------------------------------------------------------
# Geometry in and out.


class MeshData:
    """A mesh as NumPy arrays, in world space: ``vertices`` (n, 3) float64, ``faces`` (f, 3) int32,
    and the optional guidance field ``field_vertices`` (n, 3) or ``field_faces`` (f, 3)."""

    def __init__(self, vertices, faces, field_vertices=None, field_faces=None):
        self.vertices, self.faces = vertices, faces
        self.field_vertices, self.field_faces = field_vertices, field_faces


def read_mesh_data(obj, depsgraph, field_attribute=""):
    """Evaluated (modifiers applied), triangulated, world-space geometry of the mesh object ``obj``.

    ``field_attribute`` names a FLOAT_VECTOR attribute on the POINT or FACE domain of the evaluated
    mesh, returned as per-vertex or per-triangle tangent guidance vectors (transformed like
    tangents, by the linear part of the object's matrix; zero vectors mean "no value").
    Vertices used by no triangle (loose vertices and edges) are dropped.
    :raises ValueError: not a mesh, no faces, a missing or unsuitable attribute.
    """
    if obj is None or obj.type != "MESH":
        raise ValueError(f"'{getattr(obj, 'name', obj)}' is not a mesh object")
    obj_eval = obj.evaluated_get(depsgraph)
    mesh = obj_eval.to_mesh()
    try:
        mesh.calc_loop_triangles()
        nv, nt = len(mesh.vertices), len(mesh.loop_triangles)
        if nt == 0:
            raise ValueError(f"'{obj.name}' has no faces")
        co = np.empty(nv * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", co)
        tris = np.empty(nt * 3, dtype=np.int32)
        mesh.loop_triangles.foreach_get("vertices", tris)
        field_v = field_f = None
        if field_attribute:
            attr = mesh.attributes.get(field_attribute)
            if attr is None:
                raise ValueError(f"'{obj.name}' has no attribute '{field_attribute}' (after modifiers)")
            if attr.data_type != "FLOAT_VECTOR" or attr.domain not in {"POINT", "FACE"}:
                raise ValueError(
                    f"attribute '{field_attribute}' of '{obj.name}' is {attr.data_type} on the {attr.domain} "
                    "domain; a guidance field must be a FLOAT_VECTOR (Vector) attribute on Point or Face")
            values = np.empty(len(attr.data) * 3, dtype=np.float32)
            attr.data.foreach_get("vector", values)
            values = values.reshape(-1, 3).astype(np.float64)
            if attr.domain == "POINT":
                field_v = values
            else:
                poly = np.empty(nt, dtype=np.int32)
                mesh.loop_triangles.foreach_get("polygon_index", poly)
                field_f = values[poly]
    finally:
        obj_eval.to_mesh_clear()

    matrix = np.array(obj.matrix_world, dtype=np.float64)
    linear = matrix[:3, :3]
    vertices = co.reshape(-1, 3).astype(np.float64) @ linear.T + matrix[:3, 3]
    faces = tris.reshape(-1, 3)
    used = np.unique(faces)
    if len(used) < nv:  # compact: loose vertices would only widen the bounding box (and `scale`)
        remap = np.full(nv, -1, dtype=np.int32)
        remap[used] = np.arange(len(used), dtype=np.int32)
        vertices, faces = vertices[used], remap[faces]
        if field_v is not None:
            field_v = field_v[used]
    if field_v is not None:
        field_v = field_v @ linear.T
    if field_f is not None:
        field_f = field_f @ linear.T
    for f in (field_v, field_f):
        if f is not None and not np.any(np.abs(f) > 0):
            raise ValueError(f"attribute '{field_attribute}' of '{obj.name}' is zero everywhere; "
                             "leave the field empty for the automatic field")
    return MeshData(vertices, np.ascontiguousarray(faces, dtype=np.int32), field_v, field_f)


def mesh_arrays(obj, depsgraph):
    """``(V, F)``: evaluated, triangulated, world-space vertices (n, 3) float64 and faces (f, 3)
    int32 of the mesh object ``obj`` (see :func:`read_mesh_data`)."""
    data = read_mesh_data(obj, depsgraph)
    return data.vertices, data.faces


# Muted earthy palette (scripts/render.py's); each element takes one entry with a small jitter.
PALETTE = np.array([
    (0.80, 0.45, 0.32),  # terracotta
    (0.86, 0.72, 0.50),  # sand
    (0.45, 0.56, 0.66),  # slate blue
    (0.56, 0.66, 0.48),  # sage
    (0.72, 0.60, 0.70),  # heather
    (0.90, 0.84, 0.74),  # bone
    (0.62, 0.50, 0.40),  # walnut
])


def element_colours(count, seed=7):
    """``count`` linear RGBA colours (float32), one per element, reproducible."""
    rng = np.random.default_rng(seed)
    srgb = PALETTE[rng.integers(len(PALETTE), size=count)] * rng.uniform(0.85, 1.05, size=(count, 1))
    out = np.ones((count, 4), dtype=np.float32)
    out[:, :3] = np.clip(srgb, 0.0, 1.0) ** 2.2  # sRGB -> linear, roughly
    return out


def element_material():
    """The material ``meshquilt_elements`` (created once per file): Principled BSDF coloured by the
    face attribute ``meshquilt_color``."""
    mat = bpy.data.materials.get(MATERIAL_NAME)
    if mat is not None:
        return mat
    mat = bpy.data.materials.new(MATERIAL_NAME)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = next(n for n in nodes if n.type == "BSDF_PRINCIPLED")
    bsdf.inputs["Roughness"].default_value = 0.55
    attr = nodes.new("ShaderNodeAttribute")
    attr.attribute_name = COLOR_ATTRIBUTE
    attr.location = (bsdf.location.x - 250, bsdf.location.y)
    links.new(attr.outputs["Color"], bsdf.inputs["Base Color"])
    mat.diffuse_color = (0.75, 0.6, 0.5, 1.0)  # solid viewport
    return mat


def build_mesh(name, vertices, faces, element_ids=None, num_elements=0, smooth_angle=0.61):
    """A new mesh datablock from (n, 3) vertices and (f, 3) triangles (bulk foreach_set, no Python
    loop), with the face attributes ``meshquilt_element`` and ``meshquilt_color`` when
    ``element_ids`` is given. Removed again if anything fails."""
    vertices = np.asarray(vertices)
    faces = np.asarray(faces, dtype=np.int32)
    mesh = bpy.data.meshes.new(name)
    try:
        nv, nf = len(vertices), len(faces)
        mesh.vertices.add(nv)
        mesh.vertices.foreach_set("co", np.ascontiguousarray(vertices, dtype=np.float32).ravel())
        mesh.loops.add(3 * nf)
        mesh.loops.foreach_set("vertex_index", faces.ravel())
        mesh.polygons.add(nf)
        mesh.polygons.foreach_set("loop_start", np.arange(0, 3 * nf, 3, dtype=np.int32))
        mesh.update(calc_edges=True)
        if element_ids is not None:
            ids = np.ascontiguousarray(element_ids, dtype=np.int32)
            mesh.attributes.new(ELEMENT_ATTRIBUTE, "INT", "FACE").data.foreach_set("value", ids)
            # A corner-domain byte colour: Blender lists only point and corner colours as colour
            # attributes (Solid shading > Attribute, Material Preview); 4 bytes per corner.
            colours = element_colours(max(int(num_elements), int(ids.max()) + 1 if len(ids) else 0))
            col = mesh.color_attributes.new(COLOR_ATTRIBUTE, "BYTE_COLOR", "CORNER")
            col.data.foreach_set("color", colours[np.repeat(ids, 3)].ravel())
            mesh.color_attributes.active_color_name = COLOR_ATTRIBUTE  # shown in Solid > Attribute
            mesh.color_attributes.default_color_name = COLOR_ATTRIBUTE  # the render colour
        # Smooth where the surface is smooth (pebbles), flat across sharp edges (rivets, bevels).
        mesh.shade_smooth()
        if smooth_angle and hasattr(mesh, "set_sharp_from_angle"):
            mesh.set_sharp_from_angle(angle=smooth_angle)
    except BaseException:
        bpy.data.meshes.remove(mesh)
        raise
    return mesh


def _report_seconds(report):
    seconds = report.get("seconds", 0.0)
    return float(seconds.get("total", 0.0) if isinstance(seconds, dict) else seconds)


def build_result_object(context, name, result, base_obj=None, material=True):
    """The new object ``name`` holding ``result`` (a meshquilt.Result) in world space (identity
    transform), linked to ``base_obj``'s first collection (else the scene's), selected and active.
    Nothing is left behind if building fails."""
    mesh = build_mesh(name, result.vertices, result.faces, result.element_ids, result.num_elements)
    obj = None
    try:
        if material:
            mesh.materials.append(element_material())
        obj = bpy.data.objects.new(name, mesh)
        report = dict(result.report)
        obj["meshquilt_elements"] = int(result.num_elements)
        obj["meshquilt_faces"] = len(result.faces)
        obj["meshquilt_seconds"] = _report_seconds(report)
        obj["meshquilt_report"] = json.dumps(report, default=str)
        obj["meshquilt_warnings"] = "\n".join(result.warnings)
        collections = list(base_obj.users_collection) if base_obj is not None else []
        collection = collections[0] if collections else context.scene.collection
        collection.objects.link(obj)
    except BaseException:
        if obj is not None:
            bpy.data.objects.remove(obj)
        bpy.data.meshes.remove(mesh)
        raise
    view_layer = context.view_layer
    for o in context.selected_objects:
        o.select_set(False)
    if obj.name in view_layer.objects:
        obj.select_set(True)
        view_layer.objects.active = obj
    return obj


# ---------------------------------------------------------------------------------------------
# Running decorate() in a worker thread.

# Where each known stage sits in the whole run, for one overall progress figure.
_STAGES = {"shell map": (0.0, 0.05), "quilting": (0.05, 1.0)}


class Job:
    """One call of ``func(*args, progress=..., **kwargs)`` (normally meshquilt.decorate) in a
    worker thread, with a cancel flag and the latest progress.

    ``cancel()`` makes the next progress callback return False, which makes meshquilt stop with
    CancelledError. ``observers`` (class-level list of ``callable(job, stage, fraction)``) are called
    from the progress callback, on a worker thread; scripts and tests use them to watch or cancel.
    After the thread ends, exactly one of ``result`` and ``error`` is set.
    """

    observers = []

    def __init__(self, func, *args, **kwargs):
        self.func, self.args, self.kwargs = func, args, kwargs
        self.stage, self.fraction, self.overall = "starting", 0.0, 0.0
        self.result = self.error = None
        self.started = self.finished = None
        self._cancel = threading.Event()
        self._thread = threading.Thread(target=self._run, name="meshquilt", daemon=True)

    def _progress(self, stage, fraction):
        self.stage, self.fraction = stage, float(fraction)
        lo, hi = _STAGES.get(stage, (0.0, 1.0))
        self.overall = max(self.overall, lo + (hi - lo) * min(max(self.fraction, 0.0), 1.0))
        for observer in list(Job.observers):
            observer(self, stage, fraction)
        return not self._cancel.is_set()

    def _run(self):
        try:
            self.result = self.func(*self.args, progress=self._progress, **self.kwargs)
        except BaseException as e:  # reported on the main thread by the operator
            self.error = e
        finally:
            self.finished = time.perf_counter()

    def start(self):
        self.started = time.perf_counter()
        self._thread.start()
        return self

    def cancel(self):
        self._cancel.set()

    @property
    def cancelled(self):
        return self._cancel.is_set()

    @property
    def done(self):
        return self.finished is not None

    def wait(self, timeout=None):
        """Wait for the thread; True once it has ended."""
        self._thread.join(timeout)
        return not self._thread.is_alive()

    def run_blocking(self, poll=None, interval=0.1):
        """Start, then wait on the calling (main) thread, calling ``poll(job)`` every ``interval``
        seconds; Ctrl-C cancels. Returns self."""
        self.start()
        try:
            while not self.wait(interval):
                if poll is not None:
                    poll(self)
        except KeyboardInterrupt:
            self.cancel()
            self.wait()
            raise
        return self

    def status(self):
        text = f"meshquilt: {self.stage} {100 * self.fraction:.0f}%"
        return text + (" (cancelling)" if self.cancelled else "")


# ---------------------------------------------------------------------------------------------
# Settings, operator, UI.

EMBED_ITEMS = [
    ("SHELL", "Shell", "Embed through a stretch-optimised tetrahedral shell (keeps elements out of concave places)"),
    ("NORMAL", "Normal", "Offset along vertex normals (faster, may intersect in concave places)"),
]
SYMMETRY_ITEMS = [
    ("0", "Detect", "Detect the swatch's rotational symmetry"),
    ("1", "None", "No rotational symmetry"),
    ("2", "2-fold", "180 degrees"),
    ("4", "4-fold", "90 degrees"),
    ("6", "6-fold", "60 degrees"),
]


def _is_mesh(_self, obj):
    return obj.type == "MESH"


def _option_props(swatch_pointer=False):
    """The decorate options shared by the scene settings and the operator."""
    props = {
        "scale": FloatProperty(
            name="Scale", default=0.08, min=1e-4, soft_min=0.01, max=10.0, soft_max=0.5, precision=3,
            description="The swatch footprint's longer side as a fraction of the base's bounding-box diagonal"),
        "swatch_size": FloatProperty(
            name="Swatch Size", default=0.0, min=0.0, unit="LENGTH",
            description="The swatch footprint's longer side in scene units; 0 uses Scale"),
        "height": FloatProperty(
            name="Height", default=0.0, min=0.0, unit="LENGTH",
            description="Shell height in scene units; 0 uses the swatch's thickness at that scale"),
        "seed": IntProperty(name="Seed", default=1, min=0, description="Random seed (same seed, same result)"),
        "embed": EnumProperty(name="Embed", items=EMBED_ITEMS, default="SHELL",
                              description="How the flat decoration is mapped onto the surface"),
        "symmetry": EnumProperty(name="Symmetry", items=SYMMETRY_ITEMS, default="0",
                                 description="Rotational symmetry of the swatch's elements"),
        "repair": BoolProperty(
            name="Repair", default=False,
            description="Repair degenerate faces, duplicate vertices and inconsistent orientation of base "
                        "and swatch instead of refusing them"),
        "field_attribute": StringProperty(
            name="Field", default="",
            description="A Vector attribute (Point or Face domain) of the base guiding the texture's "
                        "direction; empty for the automatic field"),
    }
    if swatch_pointer:
        props["swatch"] = PointerProperty(name="Swatch", type=bpy.types.Object, poll=_is_mesh,
                                          description="The swatch: a mesh of separate closed elements in a thin slab")
    else:
        props["swatch"] = StringProperty(name="Swatch", default="",
                                         description="Name of the swatch object; empty uses the sidebar's swatch")
    return props


def _decimal(value):
    """A float property's value as the decimal the user typed: Blender stores floats in single
    precision (0.3 reads back as 0.30000001192...), which would make results differ from the same
    options given to meshquilt.decorate or the command line."""
    return float(str(np.float32(value)))


class MESHQUILT_Settings(bpy.types.PropertyGroup):
    """The sidebar's settings, kept in the scene (``scene.meshquilt``)."""
    __annotations__ = _option_props(swatch_pointer=True)


class MESHQUILT_Preferences(bpy.types.AddonPreferences):
    bl_idname = __name__

    def _retry(self, _context):
        load_meshquilt(self.module_path, retry=True)

    __annotations__ = {"module_path": StringProperty(
        name="Module Folder", subtype="DIR_PATH", default="", update=_retry,
        description="Folder holding a built 'meshquilt' package (added to sys.path), when it is "
                    "not installed in Blender's Python")}

    def draw(self, _context):
        layout = self.layout
        layout.prop(self, "module_path")
        if _meshquilt is None:
            _wrapped_label(layout.box(), install_hint(), icon="ERROR")
        else:
            layout.label(text=f"meshquilt {_meshquilt.__version__} from {_meshquilt.__file__}", icon="CHECKMARK")


class OBJECT_OT_meshquilt_decorate(bpy.types.Operator):
    """Cover the active mesh with a geometric texture grown from a swatch object (a new object)"""

    bl_idname = "object.meshquilt_decorate"
    bl_label = "Decorate with meshquilt"
    bl_options = {"REGISTER", "UNDO"}
    __annotations__ = dict(_option_props(swatch_pointer=False))

    _job = None
    _timer = None

    @classmethod
    def description(cls, _context, _properties):
        if load_meshquilt() is None:
            return install_hint()
        return cls.__doc__

    @classmethod
    def poll(cls, context):
        if load_meshquilt() is None:
            cls.poll_message_set(install_hint())
            return False
        obj = context.active_object
        if obj is None or obj.type != "MESH":
            cls.poll_message_set("Select the mesh object to decorate (make it active)")
            return False
        if context.mode != "OBJECT":
            cls.poll_message_set("Switch to Object Mode")
            return False
        return True

    # -- shared by execute and invoke --

    def _fill_from_settings(self, context):
        """Options not given to the operator take the sidebar's values (``scene.meshquilt``)."""
        settings = context.scene.meshquilt
        for key in ("scale", "swatch_size", "height", "seed", "embed", "symmetry", "repair", "field_attribute"):
            if not self.properties.is_property_set(key):
                setattr(self, key, getattr(settings, key))
        if not self.properties.is_property_set("swatch") and settings.swatch is not None:
            self.swatch = settings.swatch.name

    def _prepare(self, context):
        """The Job (not started) for the active object; raises ValueError with a clear message."""
        mq = load_meshquilt()
        base = context.active_object
        name = self.swatch
        if not name:
            raise ValueError("no swatch: pick a swatch object in the sidebar (tab meshquilt) or pass swatch='name'")
        swatch = bpy.data.objects.get(name)
        if swatch is None:
            raise ValueError(f"swatch object '{name}' does not exist")
        if swatch.type != "MESH":
            kind = swatch.type.lower()
            raise ValueError(f"swatch '{name}' is {'an' if kind[0] in 'aeiou' else 'a'} {kind} object, not a mesh")
        if swatch == base:
            raise ValueError(f"the swatch '{name}' is the object to decorate; pick another object as swatch")
        depsgraph = context.evaluated_depsgraph_get()
        b = read_mesh_data(base, depsgraph, self.field_attribute)
        s = read_mesh_data(swatch, depsgraph)
        self._base_name, self._swatch_name = base.name, swatch.name
        return Job(mq.decorate, b.vertices, b.faces, s.vertices, s.faces,
                   scale=_decimal(self.scale), swatch_size=_decimal(self.swatch_size) or None,
                   height=_decimal(self.height) or None,
                   seed=self.seed, symmetry=int(self.symmetry), embed=self.embed.lower(), repair=self.repair,
                   field_vertices=b.field_vertices, field_faces=b.field_faces)

    def _finish(self, context, job):
        """Turn an ended job into the new object, or a report; the operator's return value."""
        mq = _meshquilt
        if isinstance(job.error, mq.CancelledError) or (job.error is None and job.cancelled):
            self.report({"WARNING"}, "meshquilt: cancelled; nothing was added")
            return {"CANCELLED"}
        if isinstance(job.error, (ValueError, mq.Error)):
            self.report({"ERROR"}, f"meshquilt: {job.error}")
            return {"CANCELLED"}
        if job.error is not None:
            self.report({"ERROR"}, f"meshquilt: unexpected {type(job.error).__name__}: {job.error}")
            return {"CANCELLED"}
        base = bpy.data.objects.get(self._base_name)
        r = job.result
        try:
            obj = build_result_object(context, self._base_name + RESULT_SUFFIX, r, base)
        except Exception as e:
            self.report({"ERROR"}, f"meshquilt: could not build the result object: {e}")
            return {"CANCELLED"}
        obj["meshquilt_seed"] = self.seed
        obj["meshquilt_swatch"] = self._swatch_name
        for w in list(getattr(r, "repairs", [])) + list(r.warnings):
            self.report({"WARNING"}, f"meshquilt: {w}")
        self.report({"INFO"}, f"meshquilt: {obj.name}: {r.num_elements} elements, {len(r.faces)} faces "
                              f"in {job.finished - job.started:.1f} s")
        return {"FINISHED"}

    # -- scripts and background mode: blocking --

    def execute(self, context):
        self._fill_from_settings(context)
        try:
            job = self._prepare(context)
        except ValueError as e:
            self.report({"ERROR"}, f"meshquilt: {e}")
            return {"CANCELLED"}
        wm = context.window_manager
        wm.progress_begin(0, 100)
        try:
            job.run_blocking(poll=lambda j: wm.progress_update(100 * j.overall))
        finally:
            wm.progress_end()
        return self._finish(context, job)

    # -- the UI: a worker thread polled by a timer, Esc cancels --

    def invoke(self, context, event):
        self._fill_from_settings(context)
        if context.window is None or bpy.app.background:  # no event loop to drive a modal operator
            return self.execute(context)
        try:
            self._job = self._prepare(context)
        except ValueError as e:
            self.report({"ERROR"}, f"meshquilt: {e}")
            return {"CANCELLED"}
        wm = context.window_manager
        self._job.start()
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.progress_begin(0, 100)
        wm.modal_handler_add(self)
        self._show_status(context)
        return {"RUNNING_MODAL"}

    def _show_status(self, context):
        text = self._job.status() + ("" if self._job.cancelled else " (Esc to cancel)")
        if context.workspace is not None:
            context.workspace.status_text_set(text)
        if context.area is not None:
            context.area.header_text_set(text)
        context.window_manager.progress_update(100 * self._job.overall)

    def _end_modal(self, context):
        wm = context.window_manager
        if self._timer is not None:
            wm.event_timer_remove(self._timer)
            self._timer = None
        wm.progress_end()
        if context.workspace is not None:
            context.workspace.status_text_set(None)
        if context.area is not None:
            context.area.header_text_set(None)

    def modal(self, context, event):
        job = self._job
        if event.type in {"ESC", "RIGHTMOUSE"} and event.value == "PRESS" and not job.cancelled:
            job.cancel()
            self._show_status(context)
        if job.done:
            self._end_modal(context)
            return self._finish(context, job)
        if event.type == "TIMER":
            self._show_status(context)
        if event.type in {"MIDDLEMOUSE", "WHEELUPMOUSE", "WHEELDOWNMOUSE", "TRACKPADPAN", "TRACKPADZOOM"}:
            return {"PASS_THROUGH"}  # view navigation stays possible
        return {"RUNNING_MODAL"}

    def cancel(self, context):
        """Blender aborts the operator (e.g. the file is closed): stop the worker, add nothing."""
        if self._job is not None:
            self._job.cancel()
            self._job.wait(5.0)
        self._end_modal(context)


def _wrapped_label(layout, text, icon="NONE", width=40):
    import textwrap  # noqa: PLC0415
    col = layout.column(align=True)
    for i, line in enumerate(textwrap.wrap(text, width)):
        col.label(text=line, icon=icon if i == 0 else "BLANK1")


class VIEW3D_PT_meshquilt(bpy.types.Panel):
    """Sidebar tab: swatch, options and the Decorate button."""

    bl_label = "meshquilt"
    bl_idname = "VIEW3D_PT_meshquilt"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "meshquilt"

    def draw(self, context):
        layout = self.layout
        if load_meshquilt() is None:
            _wrapped_label(layout, install_hint(), icon="ERROR")
            return
        settings = context.scene.meshquilt
        obj = context.active_object
        layout.label(text=f"Base: {obj.name}" if obj and obj.type == "MESH" else "Base: (select a mesh)",
                     icon="MESH_DATA")
        layout.prop(settings, "swatch")
        col = layout.column(align=True)
        col.prop(settings, "scale")
        col.prop(settings, "swatch_size")
        col.prop(settings, "height")
        layout.prop(settings, "seed")
        layout.prop(settings, "embed")
        layout.prop(settings, "symmetry")
        layout.prop(settings, "repair")
        if obj is not None and obj.type == "MESH":
            layout.prop_search(settings, "field_attribute", obj.data, "attributes", text="Field")
        else:
            layout.prop(settings, "field_attribute")
        layout.operator(OBJECT_OT_meshquilt_decorate.bl_idname, text="Decorate", icon="MOD_PARTICLE_INSTANCE")


def _menu_entry(self, _context):
    self.layout.operator(OBJECT_OT_meshquilt_decorate.bl_idname, icon="MOD_PARTICLE_INSTANCE")


_CLASSES = (MESHQUILT_Settings, MESHQUILT_Preferences, OBJECT_OT_meshquilt_decorate, VIEW3D_PT_meshquilt)


def register():
    for cls in _CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.meshquilt = PointerProperty(type=MESHQUILT_Settings)
    bpy.types.VIEW3D_MT_object.append(_menu_entry)
    try:
        path = _prefs_module_path()
    except Exception:  # preferences not available yet
        path = ""
    load_meshquilt(path)  # failure is remembered and explained in the UI, not raised


def unregister():
    bpy.types.VIEW3D_MT_object.remove(_menu_entry)
    del bpy.types.Scene.meshquilt
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)


if __name__ == "__main__":
    register()
