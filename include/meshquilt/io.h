// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file io.h
/// Mesh files. Readers: OBJ, PLY (ASCII and binary), STL (ASCII and binary), OFF, chosen by the
/// file's extension (case-insensitive). Writers: OBJ (one `o` group per element), PLY (binary), STL
/// (binary). Every write is atomic: the data goes to a temporary file in the target's directory,
/// which is renamed over the target only once complete, so a failed write never leaves a truncated
/// file and never replaces a good one.

#include "meshquilt/mesh.h"

#include <string>
#include <string_view>
#include <vector>

namespace meshquilt {

/// Reads a mesh as it is stored: no vertex merging (except STL, whose format has no shared
/// vertices: identical coordinates are merged), no repair. Polygons with more than three corners are
/// fan-triangulated. Unreferenced vertices are kept. OBJ: `v` and `f` records (any corner form,
/// negative indices); OFF: ASCII, with the ST/C/N prefixes; PLY: x, y, z of `vertex` and the
/// `vertex_indices` (or `vertex_index`) list of `face` or `tristrips`, any property types; STL:
/// binary when the size is 84 + 50 n, else ASCII if it reads as such (bytes after a binary STL's n
/// triangles are ignored). A file without faces is an error. Linear time; header counts that the
/// file size cannot back are rejected before any allocation.
/// \throw IoError       the file cannot be opened or read, or has an unknown extension
/// \throw InvalidInput  malformed content; the message names the file, line (or record) and problem,
///                      e.g. non-finite coordinates or face indices out of range
Mesh read_mesh(const std::string& path);

/// Parses a mesh from bytes already in memory, with the rules and errors of read_mesh(). The
/// format comes from the extension of `name`, which also starts every message (e.g. "upload.stl").
/// \throw IoError       unknown extension
/// \throw InvalidInput  malformed content
Mesh parse_mesh(const std::string& name, std::string_view data);

struct WriteOptions {
    /// Element id per face; OBJ writes one `o element_<id>` group per element, in increasing id
    /// order (faces keep their relative order within a group). May be empty.
    std::vector<int> element_of_face;
    /// Written as a header comment where the format allows (OBJ, PLY); may be empty.
    std::string comment;
    /// OBJ group name per element id, overriding `element_<id>` where given and not empty (e.g.
    /// "base"); names must not contain whitespace.
    std::vector<std::string> group_names;
    /// 3MF only: the element objects become the components of one assembly object, the only
    /// build item, so slicers place and arrange them as one piece (a print-in-place fabric keeps
    /// its rings together). Otherwise every element object is its own build item.
    bool assembly_3mf = false;
};

/// Writes by extension (.obj, .ply, .stl, .3mf), atomically. 3MF: lib3mf, millimetres (the
/// coordinates are taken as mm), one mesh object per element.
/// \throw IoError the directory is not writable or the disk is full; the target is untouched then
void write_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& options = {});

/// Writes `contents` to `path` atomically (temporary file + rename). Used for JSON reports too.
void write_file_atomic(const std::string& path, const std::string& contents);

}  // namespace meshquilt
