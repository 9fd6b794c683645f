# SPDX-License-Identifier: AGPL-3.0-or-later
"""meshquilt: cover triangle meshes with geometric textures grown from a swatch.

The main call::

    import meshquilt
    r = meshquilt.decorate(base_vertices, base_faces, swatch_vertices, swatch_faces,
                           scale=0.08, seed=1, progress=lambda stage, fraction: True)
    r.vertices      # (N, 3) float64
    r.faces         # (F, 3) int32
    r.element_ids   # (F,) int32, one id per grown element
    r.report        # dict: the CLI's --report

Arrays are anything NumPy can read as (N, 3) floats and (F, 3) integers. ``progress(stage,
fraction)`` is called from time to time (from worker threads, holding the GIL); returning False
cancels the call, which then raises :class:`CancelledError`. The GIL is released while meshquilt
computes, so other Python threads keep running.

Errors: bad meshes or options raise :class:`InvalidInputError` (a ``ValueError``), a failed print
check :class:`PrintCheckError` (an ``InvalidInputError`` with the print report as ``.report``),
unreadable files :class:`MeshIOError` (an ``OSError``), cancellation :class:`CancelledError`, other
failures :class:`Error` (a ``RuntimeError``). An exception raised by a callback cancels the call and is
re-raised as it was.

Also: ``quilt_plane`` (planar quilting), ``prepare_print`` (printable solids in mm), ``validate``,
``read_mesh`` and ``write_mesh`` (file names may be str, bytes or os.PathLike). See
docs/library.md for every option.
"""

from ._meshquilt import (  # noqa: F401
    CancelledError,
    Error,
    InvalidInputError,
    MeshIOError,
    PrintCheckError,
    Result,
    __version__,
    decorate,
    prepare_print,
    quilt_plane,
    read_mesh,
    validate,
    write_mesh,
)

__all__ = [
    "CancelledError",
    "Error",
    "InvalidInputError",
    "MeshIOError",
    "PrintCheckError",
    "Result",
    "__version__",
    "decorate",
    "prepare_print",
    "quilt_plane",
    "read_mesh",
    "validate",
    "write_mesh",
]
