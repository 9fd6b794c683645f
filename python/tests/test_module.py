# SPDX-License-Identifier: AGPL-3.0-or-later
"""The Python module: arrays in and out, options, progress and cancellation, the GIL, errors, and
equality with the command-line tool.

Run: python3 -m pytest python/tests  (with meshquilt installed, or PYTHONPATH=<build>/python).
The CLI comparison needs the `meshquilt` executable: $MESHQUILT_CLI, else `meshquilt` on PATH,
else build*/meshquilt in the repository; it is skipped only when none exists.
"""
import glob
import json
import os
import shutil
import subprocess
import threading

import numpy as np
import pytest

import meshquilt

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
BASE = os.path.join(ROOT, "tests", "data", "surface", "eight.obj")  # genus 2, 634 faces
RIVETS = os.path.join(ROOT, "swatches", "rivets.obj")
PEBBLES = os.path.join(ROOT, "swatches", "pebbles.obj")
FAST = dict(scale=0.5, embed="normal")  # about 2 s per call on the eight


@pytest.fixture(scope="module")
def base():
    return meshquilt.read_mesh(BASE)


@pytest.fixture(scope="module")
def rivets():
    return meshquilt.read_mesh(RIVETS)


@pytest.fixture(scope="module")
def decorated(base, rivets):
    return meshquilt.decorate(*base, *rivets, seed=7, **FAST)


def cube():
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v, f


# ---- arrays ---------------------------------------------------------------------------------

def test_read_write_round_trip_keeps_arrays_and_elements(tmp_path):
    v, f = cube()
    two_v = np.vstack([v, v + [3.0, 0.0, 0.125]])
    two_f = np.vstack([f, f + 8])
    ids = np.repeat([0, 1], 12)
    path = str(tmp_path / "two.obj")
    meshquilt.write_mesh(path, two_v, two_f, element_ids=ids)
    text = open(path).read()
    assert text.count("\no element_") == 2
    rv, rf = meshquilt.read_mesh(path)
    assert rv.dtype == np.float64 and rv.shape == (16, 3)
    assert rf.dtype == np.int32 and rf.shape == (24, 3)
    np.testing.assert_array_equal(rv, two_v)  # shortest round-trip printing: exact
    np.testing.assert_array_equal(rf, two_f)
    for ext in ("ply", "stl"):
        p = str(tmp_path / f"two.{ext}")
        meshquilt.write_mesh(p, two_v, two_f)
        bv, bf = meshquilt.read_mesh(p)
        assert bf.shape == (24, 3)
        # STL merges equal corners; PLY keeps the vertices as they are
        np.testing.assert_allclose(np.sort(bv[bf].reshape(-1, 3), axis=0), np.sort(two_v[two_f].reshape(-1, 3), axis=0))


def test_inputs_accept_lists_and_other_dtypes(base, rivets):
    bv, bf = base
    sv, sf = rivets
    ref = meshquilt.decorate(bv, bf, sv, sf, seed=3, **FAST)
    alt = meshquilt.decorate(bv.tolist(), bf.astype(np.uint32), sv.tolist(), sf.astype(np.int64), seed=3, **FAST)
    np.testing.assert_array_equal(ref.faces, alt.faces)
    np.testing.assert_array_equal(ref.vertices, alt.vertices)
    single = meshquilt.decorate(bv.astype(np.float32), bf.astype(np.int16), sv.astype(np.float32), sf, seed=3, **FAST)
    assert single.vertices.dtype == np.float64
    assert abs(single.num_elements - ref.num_elements) <= 0.05 * ref.num_elements
    # a Fortran-ordered, non-contiguous view is read correctly too
    fv = np.asfortranarray(np.hstack([bv, np.zeros((len(bv), 1))]))[:, :3]
    again = meshquilt.decorate(fv, bf, sv, sf, seed=3, **FAST)
    np.testing.assert_array_equal(ref.vertices, again.vertices)


def test_result_arrays_are_consistent(decorated, rivets):
    r = decorated
    assert r.vertices.dtype == np.float64 and r.vertices.ndim == 2 and r.vertices.shape[1] == 3
    assert r.faces.dtype == np.int32 and r.faces.shape[1] == 3
    assert r.element_ids.dtype == np.int32 and r.element_ids.shape == (len(r.faces),)
    assert r.faces.min() >= 0 and r.faces.max() < len(r.vertices)
    assert np.all(np.isfinite(r.vertices))
    assert r.num_elements > 20
    assert set(np.unique(r.element_ids)) == set(range(r.num_elements))
    # faces of one element are contiguous
    assert np.count_nonzero(np.diff(r.element_ids)) == r.num_elements - 1
    assert r.source_elements.shape == (r.num_elements,)
    swatch_elements = 45  # rivets.obj: see swatches/README.md
    assert r.source_elements.min() >= 0 and r.source_elements.max() < swatch_elements
    assert r.report["faces"] == len(r.faces) and r.report["elements"] == r.num_elements
    assert r.report["surface"]["coverage"] == 1.0
    assert r.report["surface"]["embedding"] == "normal"
    json.dumps(r.report)  # a plain dict of JSON types
    assert "elements" in repr(r)


def test_every_element_is_closed(decorated):
    r = decorated
    for e in range(0, r.num_elements, max(1, r.num_elements // 25)):
        faces = r.faces[r.element_ids == e]
        edges = np.sort(np.vstack([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
        _, counts = np.unique(edges, axis=0, return_counts=True)
        assert np.all(counts == 2), f"element {e} has boundary or non-manifold edges"


# ---- options --------------------------------------------------------------------------------

def test_seed_scale_and_embedding_change_the_output(base, rivets, decorated):
    other_seed = meshquilt.decorate(*base, *rivets, seed=8, **FAST)
    assert not np.array_equal(other_seed.vertices[:100], decorated.vertices[:100])
    same_seed = meshquilt.decorate(*base, *rivets, seed=7, **FAST)
    np.testing.assert_array_equal(same_seed.vertices, decorated.vertices)
    np.testing.assert_array_equal(same_seed.faces, decorated.faces)
    smaller = meshquilt.decorate(*base, *rivets, seed=7, scale=0.35, embed="normal")
    assert smaller.num_elements > 1.5 * decorated.num_elements
    shell = meshquilt.decorate(*base, *rivets, seed=7, scale=0.5)
    assert shell.report["surface"]["embedding"] == "shell"
    assert shell.report["stretch_l2_final"] <= shell.report["stretch_l2_initial"]


def test_swatch_size_is_in_base_units(base, rivets, decorated):
    bv = base[0]
    diagonal = np.linalg.norm(bv.max(axis=0) - bv.min(axis=0))
    by_size = meshquilt.decorate(*base, *rivets, seed=7, swatch_size=0.5 * diagonal, embed="normal")
    np.testing.assert_allclose(by_size.report["surface"]["base_units_per_swatch_unit"],
                               decorated.report["surface"]["base_units_per_swatch_unit"], rtol=1e-12)
    assert by_size.num_elements == decorated.num_elements


def test_height_option_sets_the_shell_height(base, rivets):
    r = meshquilt.decorate(*base, *rivets, seed=7, height=0.05, **FAST)
    assert r.report["surface"]["shell_height"] == pytest.approx(0.05)


def test_guidance_field_is_used(base, rivets, decorated):
    bv, bf = base
    field = np.zeros_like(bv)
    field[:, 0] = 1.0  # along x wherever it is tangent
    r = meshquilt.decorate(bv, bf, *rivets, seed=7, field_vertices=field, **FAST)
    assert not np.array_equal(r.vertices[:100], decorated.vertices[:100])
    face_field = np.tile([0.0, 1.0, 0.0], (len(bf), 1))
    r2 = meshquilt.decorate(bv, bf, *rivets, seed=7, field_faces=face_field, **FAST)
    assert r2.num_elements > 20
    with pytest.raises(ValueError, match="field_vertices must have one row per base vertex"):
        meshquilt.decorate(bv, bf, *rivets, field_vertices=field[:-1], **FAST)
    with pytest.raises(ValueError, match="no non-zero vector"):
        meshquilt.decorate(bv, bf, *rivets, field_vertices=np.zeros_like(bv), **FAST)


def test_repair_is_reported(base, rivets):
    bv, bf = base
    with_degenerate = np.vstack([bf, [[0, 0, 1]]])
    with pytest.raises(ValueError, match="degenerate"):
        meshquilt.decorate(bv, with_degenerate, *rivets, **FAST)
    r = meshquilt.decorate(bv, with_degenerate, *rivets, seed=7, repair=True, **FAST)
    assert any(x.startswith("base: ") and "degenerate" in x for x in r.repairs), r.repairs
    plain = meshquilt.decorate(bv, bf, *rivets, seed=7, **FAST)
    np.testing.assert_array_equal(r.vertices, plain.vertices)


# ---- progress, cancellation, threads ----------------------------------------------------------

def test_progress_reports_stages_in_order(base, rivets):
    calls = []
    meshquilt.decorate(*base, *rivets, seed=7, scale=0.5, progress=lambda s, f: calls.append((s, f)))
    stages = [s for s, _ in calls]
    assert "quilting" in stages and "shell map" in stages
    for stage in set(stages):
        fractions = [f for s, f in calls if s == stage]
        assert all(0.0 <= f <= 1.0 for f in fractions)
        assert fractions == sorted(fractions), stage
    assert [f for s, f in calls if s == "quilting"][-1] == 1.0


@pytest.mark.parametrize("stage", ["quilting", "shell map"])
def test_progress_returning_false_cancels(base, rivets, stage):
    seen = []

    def progress(s, f):
        seen.append(s)
        return s != stage

    with pytest.raises(meshquilt.CancelledError, match=stage):
        meshquilt.decorate(*base, *rivets, scale=0.5, progress=progress)
    assert seen[-1] == stage
    assert issubclass(meshquilt.CancelledError, meshquilt.Error)
    assert issubclass(meshquilt.Error, RuntimeError)


def test_exception_in_callback_cancels_and_is_reraised(base, rivets):
    class Stop(Exception):
        pass

    count = [0]

    def progress(s, f):
        count[0] += 1
        if count[0] == 3:
            raise Stop("from the callback")

    with pytest.raises(Stop, match="from the callback"):
        meshquilt.decorate(*base, *rivets, progress=progress, **FAST)
    assert count[0] == 3  # not called again after it raised


def test_log_callback_receives_warnings_and_info(base, rivets):
    logs = []
    vertices, faces = base
    inside_out = np.ascontiguousarray(faces[:, ::-1])  # the base turned inside out: fixed, with a warning
    r = meshquilt.decorate(vertices, inside_out, *rivets, seed=7, log=lambda level, text: logs.append((level, text)), **FAST)
    assert any("facing inwards" in w for w in r.warnings), r.warnings
    assert [t for lvl, t in logs if lvl == "warning"] == r.warnings
    assert any(lvl == "info" and f"{r.num_elements} elements" in t for lvl, t in logs), logs
    assert all(level in ("debug", "info", "warning") and isinstance(text, str) for level, text in logs)


def test_gil_is_released_while_computing(base, rivets):
    done = threading.Event()
    result = {}

    def work():
        result["r"] = meshquilt.decorate(*base, *rivets, seed=7, **FAST)
        done.set()

    worker = threading.Thread(target=work)
    ticks = 0
    worker.start()
    while not done.is_set():
        ticks += 1
        done.wait(0.001)
    worker.join()
    # about 2 s of computing: with the GIL held throughout, this thread could not have run
    assert ticks > 200, ticks
    assert result["r"].num_elements > 20


def test_cancel_from_another_thread(base, rivets):
    stop = threading.Event()
    errors = []

    def work():
        try:
            meshquilt.decorate(*base, *rivets, scale=0.3, progress=lambda s, f: not stop.is_set())
        except meshquilt.CancelledError as e:
            errors.append(e)

    worker = threading.Thread(target=work)
    worker.start()
    stop.set()
    worker.join(timeout=60)
    assert not worker.is_alive() and len(errors) == 1


# ---- bad input ------------------------------------------------------------------------------

@pytest.mark.parametrize("change, message", [
    (lambda bv, bf: (bv[:, :2], bf), r"base_vertices must have shape \(N, 3\), got \(315, 2\)"),
    (lambda bv, bf: (bv, bf.astype(float)), "base_faces must hold integers"),
    (lambda bv, bf: (np.where(np.arange(len(bv))[:, None] == 4, np.nan, bv), bf), r"base_vertices\[4\] is not finite"),
    (lambda bv, bf: (bv, np.vstack([bf, [[0, 1, 999]]])), r"base_faces\[634\] has vertex index 999 outside \[0, 315\)"),
    (lambda bv, bf: (bv, bf[:0]), "base"),
    (lambda bv, bf: ("not an array", bf), "base_vertices"),
    (lambda bv, bf: (bv, np.vstack([bf, bf[:1]])), "base.*non-manifold"),
    (lambda bv, bf: (bv, np.vstack([bf, [[0, 0, 1]]])), "base.*degenerate"),
])
def test_bad_base_raises_value_error(base, rivets, change, message):
    bv, bf = change(*base)
    with pytest.raises(ValueError, match=message):
        meshquilt.decorate(bv, bf, *rivets, **FAST)


def test_bad_input_is_an_invalid_input_error(base):
    v, f = cube()
    with pytest.raises(meshquilt.InvalidInputError, match="swatch.*thin axis"):
        meshquilt.decorate(*base, v, f)


@pytest.mark.parametrize("options, message", [
    (dict(scale=-1.0), "scale must be a positive finite number"),
    (dict(scale=float("nan")), "scale"),
    (dict(scale=1e-9), "scale"),
    (dict(swatch_size=0.0), "swatch_size"),
    (dict(height=-2.0), "height"),
    (dict(seed=-1), "seed"),
    (dict(symmetry=3), "symmetry"),
    (dict(embed="sideways"), "embed must be 'shell' or 'normal'"),
    (dict(progress=42), "progress must be callable"),
])
def test_bad_options_raise_value_error(base, rivets, options, message):
    with pytest.raises(ValueError, match=message):
        meshquilt.decorate(*base, *rivets, **options)


def test_unreadable_file_raises_os_error(tmp_path):
    with pytest.raises(OSError, match="nope.obj"):
        meshquilt.read_mesh(str(tmp_path / "nope.obj"))
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nf 1 2 7\n")
    with pytest.raises(ValueError, match="bad.obj"):
        meshquilt.read_mesh(str(bad))


def test_failed_write_keeps_the_existing_file(tmp_path):
    v, f = cube()
    path = tmp_path / "keep.obj"
    path.write_text("good\n")
    with pytest.raises(ValueError):
        meshquilt.write_mesh(str(path), v, f, element_ids=[0, 1])  # wrong length: nothing written
    assert path.read_text() == "good\n"


# ---- the same as the command-line tool ---------------------------------------------------------

def find_cli():
    candidates = [os.environ.get("MESHQUILT_CLI"), shutil.which("meshquilt")]
    candidates += sorted(glob.glob(os.path.join(ROOT, "build*", "meshquilt")), key=os.path.getmtime, reverse=True)
    return next((c for c in candidates if c and os.path.isfile(c) and os.access(c, os.X_OK)), None)


@pytest.mark.parametrize("swatch, options", [
    (RIVETS, ["--scale", "0.5", "--embed", "normal"]),
    (PEBBLES, ["--scale", "0.45"]),
])
def test_same_result_as_the_cli(tmp_path, base, swatch, options):
    cli = find_cli()
    if cli is None:
        pytest.skip("no meshquilt executable found (set MESHQUILT_CLI)")
    out = str(tmp_path / "cli.obj")
    report = str(tmp_path / "cli.json")
    subprocess.run([cli, "-q", BASE, swatch, "-o", out, "--seed", "11", "--report", report, *options], check=True)
    kwargs = dict(scale=float(options[1]), seed=11)
    if "--embed" in options:
        kwargs["embed"] = options[options.index("--embed") + 1]
    r = meshquilt.decorate(*base, *meshquilt.read_mesh(swatch), **kwargs)
    cv, cf = meshquilt.read_mesh(out)
    np.testing.assert_array_equal(cv, r.vertices)
    np.testing.assert_array_equal(cf, r.faces)
    text = open(out).read()
    assert text.count("\no element_") == r.num_elements
    cli_report = json.load(open(report))
    for key in ("faces", "vertices", "elements", "elements_closed", "patches", "output_density"):
        assert cli_report[key] == r.report[key], key
    assert cli_report["surface"] == r.report["surface"]


# ---- print export -------------------------------------------------------------------------------

def test_prepare_print_fused_is_watertight_and_round_trips_through_3mf(tmp_path, base, decorated):
    r = meshquilt.prepare_print(decorated.vertices, decorated.faces, *base, size_mm=40, voxel_mm=0.25)
    rep = r.report
    assert rep["mode"] == "fused" and rep["bodies"] == r.num_elements >= 1
    assert rep["boundary_edges"] == 0 and rep["non_manifold_edges"] == 0 and rep["inside_out_bodies"] == 0
    extent = r.vertices.max(axis=0) - r.vertices.min(axis=0)
    np.testing.assert_allclose(extent, rep["size_mm"], rtol=1e-5)
    assert extent.max() == pytest.approx(40, abs=0.5)  # the input scaled to 40 mm, remeshed at 0.25 mm
    path = str(tmp_path / "fused.3mf")
    meshquilt.write_mesh(path, r.vertices, r.faces, element_ids=r.element_ids)
    v, f = meshquilt.read_mesh(path)
    assert f.shape == r.faces.shape
    np.testing.assert_allclose(v, r.vertices, atol=1e-4)  # 3MF stores floats


def test_prepare_print_separate_checks_clearance(rivets):
    plane = meshquilt.quilt_plane(*rivets, 12, 12, seed=2)
    r = meshquilt.prepare_print(plane.vertices, plane.faces, mode="separate", size_mm=120, min_clearance_mm=0.1,
                                min_thickness_mm=0.3)
    assert r.num_elements == plane.num_elements
    assert r.report["checks_passed"] and r.report["min_clearance_mm"] > 0.1
    with pytest.raises(meshquilt.PrintCheckError) as failed:
        meshquilt.prepare_print(plane.vertices, plane.faces, mode="separate", size_mm=120, min_clearance_mm=40,
                                min_thickness_mm=0.3)
    assert isinstance(failed.value, ValueError)
    report = failed.value.report
    assert not report["checks_passed"] and report["violations"][0]["kind"] == "clearance"
    assert "clearance" in str(failed.value)
    forced = meshquilt.prepare_print(plane.vertices, plane.faces, mode="separate", size_mm=120, min_clearance_mm=40,
                                     min_thickness_mm=0.3, force=True)
    assert not forced.report["checks_passed"] and forced.num_elements == plane.num_elements


@pytest.mark.parametrize("options, message", [
    (dict(), "print size"),
    (dict(size_mm=40, mode="glued"), "mode must be 'fused' or 'separate'"),
    (dict(size_mm=-3), "size"),
])
def test_prepare_print_bad_options(decorated, options, message):
    with pytest.raises(ValueError, match=message):
        meshquilt.prepare_print(decorated.vertices, decorated.faces, **options)


def test_validate_checks_and_repairs_like_decorate(base, rivets):
    bv, bf = base
    v, f, repairs, warnings = meshquilt.validate(bv, bf, name="eight.obj")
    np.testing.assert_array_equal(v, bv)
    np.testing.assert_array_equal(f, bf)
    assert repairs == [] and warnings == []
    with pytest.raises(ValueError, match="eight.obj: .*degenerate"):
        meshquilt.validate(bv, np.vstack([bf, [[1, 1, 2]]]), name="eight.obj")
    v, f, repairs, _ = meshquilt.validate(bv, np.vstack([bf, [[1, 1, 2]]]), name="eight.obj", repair=True)
    assert len(f) == len(bf) and repairs
    with pytest.raises(ValueError, match="thin axis"):
        meshquilt.validate(*cube(), swatch=True)
    meshquilt.validate(*rivets, swatch=True)
    # A base whose faces disagree about their side is reoriented with a warning (to the side most
    # of them face: the eight again); a swatch so written is refused.
    partly = bf.copy()
    partly[::3] = partly[::3][:, [0, 2, 1]]
    v, f, repairs, warnings = meshquilt.validate(bv, partly, name="eight.obj")
    np.testing.assert_array_equal(f, bf)
    assert repairs == [] and len(warnings) == 1 and warnings[0].startswith("eight.obj: reoriented"), warnings
    sv, sf = rivets
    flipped = sf.copy()
    flipped[::3] = flipped[::3][:, [0, 2, 1]]
    with pytest.raises(ValueError, match="inconsistent orientation"):
        meshquilt.validate(sv, flipped, name="rivets.obj", swatch=True)


def test_flat_swatch_is_named_as_such(base):
    # three separate unit squares in the plane z = 0: a valid mesh, but nothing to grow
    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    flat_v = np.vstack([square + [2.0 * i, 0, 0] for i in range(3)])
    flat_f = np.vstack([np.array([[0, 1, 2], [0, 2, 3]]) + 4 * i for i in range(3)])
    with pytest.raises(ValueError, match="swatch: flat: its thin axis \\(z\\) has no thickness"):
        meshquilt.decorate(*base, flat_v, flat_f)


def test_numpy_scalars_paths_and_strict_types(tmp_path, base, rivets, decorated):
    r = meshquilt.decorate(*base, *rivets, seed=np.int64(7), scale=np.float32(0.5), embed="normal")
    np.testing.assert_array_equal(r.faces, decorated.faces)
    with pytest.raises(ValueError, match="seed must be an integer"):
        meshquilt.decorate(*base, *rivets, seed=True, **FAST)
    with pytest.raises(ValueError, match="seed must be an integer"):
        meshquilt.decorate(*base, *rivets, seed=7.0, **FAST)
    with pytest.raises(TypeError):
        meshquilt.decorate(*base, *rivets, swatch_size="1", **FAST)
    v, f = cube()
    path = tmp_path / "cube.ply"  # a pathlib.Path
    meshquilt.write_mesh(path, v, f)
    rv, rf = meshquilt.read_mesh(path)
    assert rf.shape == (12, 3)
    with pytest.raises(ValueError, match="element_ids must be a 1-D integer array"):
        meshquilt.write_mesh(path, v, f, element_ids=np.zeros(12))


def test_progress_answer_without_truth_value_is_reraised(base, rivets):
    with pytest.raises(ValueError, match="truth value"):
        meshquilt.decorate(*base, *rivets, progress=lambda s, f: np.array([True, False]), **FAST)


def test_result_carries_the_base_as_used(base, rivets, decorated):
    bv, bf = base
    np.testing.assert_array_equal(decorated.base_vertices, bv)
    np.testing.assert_array_equal(decorated.base_faces, bf)
    repaired = meshquilt.decorate(bv, np.vstack([bf, [[0, 0, 1]]]), *rivets, seed=7, repair=True, **FAST)
    np.testing.assert_array_equal(repaired.base_faces, bf)  # the degenerate face dropped
    plane = meshquilt.quilt_plane(*rivets, 6, 6)
    assert plane.base_vertices is None and plane.base_faces is None
