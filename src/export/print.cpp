// SPDX-License-Identifier: AGPL-3.0-or-later
// prepare_print(): closed bodies in, a printable model in millimetres out (fused solid or separate
// bodies), with the print checks. See print.h and docs/print.md.

#include "meshquilt/print.h"

#include "core/triangle_index.h"
#include "meshquilt/analysis.h"
#include "print_detail.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

namespace meshquilt {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string mm(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g mm", v);
    return buf;
}
std::string at(const Vec3& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.2f, %.2f, %.2f) mm", p.x(), p.y(), p.z());
    return buf;
}

double area(const Mesh& m) {
    double a = 0.0;
    for (std::size_t f = 0; f < m.faces.size(); ++f) a += face_area(m, f);
    return a;
}
void flip(Mesh& m) {
    for (Tri& t : m.faces) std::swap(t[1], t[2]);
}

/// Closed bodies of `mesh` (flipped outward where inside out) and, when `open_ok`, the open
/// components gathered into one sheet. Throws on what cannot be printed.
struct Parts {
    std::vector<Mesh> closed;
    Mesh open;
    int flipped = 0;
};
Parts classify(const Mesh& mesh, const std::string& name, bool open_ok) {
    if (mesh.faces.empty()) throw InvalidInput(name + ": the mesh has no faces; nothing to print");
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        if (!mesh.vertices[v].allFinite()) throw InvalidInput(name + ": vertex " + std::to_string(v) + " has a non-finite coordinate");
    int count = 0;
    const std::vector<int> comp = connected_components(mesh, &count);
    const MeshAnalysis a = analyse(mesh);
    std::vector<Mesh> parts = print_detail::split_elements(ElementMesh{mesh, comp, count});
    Parts out;
    for (int c = 0; c < count; ++c) {
        const ElementInfo& e = a.elements[static_cast<std::size_t>(c)];
        Mesh& p = parts[static_cast<std::size_t>(c)];
        const Box3 box = bounding_box(p);
        const Vec3 centre = 0.5 * (box.min + box.max);
        char where[96];
        std::snprintf(where, sizeof where, " (element %d, around (%.4g, %.4g, %.4g))", c, centre.x(), centre.y(), centre.z());
        if (!e.edge_manifold)
            throw InvalidInput(name + ": element " + std::to_string(c) + where +
                               " has non-manifold edges (an edge with more than two faces); it cannot be voxelised or printed. Repair the mesh.");
        if (e.closed) {
            if (print_detail::signed_volume(p) < 0.0) {
                flip(p);
                ++out.flipped;
            }
            out.closed.push_back(std::move(p));
        } else if (open_ok) {
            const int base = static_cast<int>(out.open.vertices.size());
            out.open.vertices.insert(out.open.vertices.end(), p.vertices.begin(), p.vertices.end());
            for (const Tri& t : p.faces) out.open.faces.push_back(t + Tri::Constant(base));
        } else {
            throw InvalidInput(name + ": element " + std::to_string(c) + where + " is open (" + std::to_string(e.boundary_loops) +
                               " boundary loop(s)) or not consistently oriented; printing needs closed bodies. Give an open base with "
                               "--base: it is thickened into a sheet.");
        }
    }
    return out;
}

void check_options(const PrintOptions& o) {
    const auto bad = [](const std::string& what) { throw InvalidInput("print options: " + what); };
    const auto finite_pos = [](double v) { return std::isfinite(v) && v > 0.0; };
    if (o.size_mm != 0.0 && !finite_pos(o.size_mm)) bad("--size-mm must be a positive length in mm, not " + std::to_string(o.size_mm));
    if (o.size_mm == 0.0 && !finite_pos(o.unit_mm))
        bad(o.unit_mm == 0.0 ? "give the print size: --size-mm (largest dimension) or --unit-mm (mm per model unit)"
                             : "--unit-mm must be positive, not " + std::to_string(o.unit_mm));
    if (o.size_mm > 1e5 || o.unit_mm > 1e9) bad("the print size is absurd (over 100 m)");
    if (!(std::isfinite(o.min_thickness_mm) && o.min_thickness_mm >= 0.0 && o.min_thickness_mm < 1e3)) bad("--min-thickness must be in [0, 1000) mm");
    if (!(std::isfinite(o.min_clearance_mm) && o.min_clearance_mm >= 0.0 && o.min_clearance_mm < 1e3)) bad("--min-clearance must be in [0, 1000) mm");
    if (!(std::isfinite(o.voxel_mm) && o.voxel_mm >= 0.0)) bad("--voxel-mm must be positive (or 0 to derive it)");
    if (!(o.adaptivity >= 0.0 && o.adaptivity <= 1.0)) bad("--adaptivity must be in [0, 1]");
    if (!finite_pos(o.base_thickness_mm) || o.base_thickness_mm > 1e3) bad("--base-thickness must be a positive length in mm (under 1 m)");
    if (!(std::isfinite(o.attach_mm) && o.attach_mm >= 0.0 && o.attach_mm < 1e3)) bad("--attach-mm must be in [0, 1000) mm");
    if (o.max_voxels == 0) bad("--max-voxels must be positive");
}

/// Weighted percentile of finite values.
double weighted_percentile(const std::vector<double>& v, const std::vector<double>& w, double q) {
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < v.size(); ++i)
        if (std::isfinite(v[i]) && w[i] > 0.0) idx.push_back(i);
    if (idx.empty()) return kInf;
    std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
    double total = 0.0;
    for (std::size_t i : idx) total += w[i];
    double acc = 0.0;
    for (std::size_t i : idx) {
        acc += w[i];
        if (acc >= q * total) return v[i];
    }
    return v[idx.back()];
}

/// To millimetres, rounded to float as the files will hold them (so the checks see the file).
void transform(Mesh& m, const Vec3& origin, double s) {
    for (Vec3& v : m.vertices) v = ((v - origin) * s).cast<float>().cast<double>();
}

}  // namespace

BodyChecks check_bodies(const ElementMesh& model, double min_thickness, double min_clearance) {
    BodyChecks out;
    const print_detail::ElementThickness th = print_detail::element_thickness(model);
    out.min_thickness = kInf;
    for (std::size_t e = 0; e < th.min_of_element.size(); ++e) {
        const double t = th.min_of_element[e];
        if (t < out.min_thickness) {
            out.min_thickness = t;
            out.min_thickness_at = th.at_of_element[e];
            out.min_thickness_body = static_cast<int>(e);
        }
        if (t < min_thickness) out.violations.push_back({PrintViolation::Kind::Thickness, t, th.at_of_element[e], static_cast<int>(e), -1});
    }
    const print_detail::Clearances c = print_detail::clearances(model, min_clearance);
    out.min_clearance = c.min;
    out.min_clearance_at = c.at;
    out.min_clearance_bodies[0] = c.a;
    out.min_clearance_bodies[1] = c.b;
    out.intersecting_pairs = c.intersecting_pairs;
    out.violations.insert(out.violations.end(), c.below.begin(), c.below.end());
    // Worst first: relative to its limit.
    const auto badness = [&](const PrintViolation& v) {
        const double limit = v.kind == PrintViolation::Kind::Clearance ? min_clearance : min_thickness;
        return limit > 0.0 ? v.value_mm / limit : v.value_mm;
    };
    std::stable_sort(out.violations.begin(), out.violations.end(), [&](const PrintViolation& x, const PrintViolation& y) { return badness(x) < badness(y); });
    return out;
}

PrintResult prepare_print(const Mesh& decoration, const Mesh* base, const PrintOptions& o, const std::string& name) {
    check_options(o);
    const auto t0 = Clock::now();
    PrintResult result;
    PrintReport& rep = result.report;
    rep.mode = o.mode;
    o.reporter.report("prepare", 0.0);

    Parts deco = classify(decoration, name, false);
    Parts basep;
    if (base) basep = classify(*base, "base", true);
    if (deco.flipped + basep.flipped > 0)
        result.warnings.push_back(std::to_string(deco.flipped + basep.flipped) + " inside-out bodies were turned outward");

    // Scale to millimetres and move to the positive octant.
    Box3 box;
    for (const Mesh& m : deco.closed) box.extend(bounding_box(m));
    for (const Mesh& m : basep.closed) box.extend(bounding_box(m));
    if (!basep.open.empty()) box.extend(bounding_box(basep.open));
    const double extent = box.size().maxCoeff();
    if (!(extent > 0.0)) throw InvalidInput(name + ": the model has no extent");
    const double s = o.size_mm > 0.0 ? o.size_mm / extent : o.unit_mm;
    if (!std::isfinite(s) || !(s > 0.0)) throw InvalidInput(name + ": cannot scale the model to millimetres");
    rep.mm_per_unit = s;
    for (Mesh& m : deco.closed) transform(m, box.min, s);
    for (Mesh& m : basep.closed) transform(m, box.min, s);
    transform(basep.open, box.min, s);
    rep.input_bodies = static_cast<int>(deco.closed.size() + basep.closed.size()) + (basep.open.empty() ? 0 : 1);
    rep.open_base_thickened = basep.open.empty() ? 0 : 1;

    rep.seconds_prepare = since(t0);

    if (o.mode == PrintMode::Fused) {
        double deco_area = 0.0, base_area = 0.0;
        for (const Mesh& m : deco.closed) deco_area += area(m);
        for (const Mesh& m : basep.closed) base_area += area(m);
        const Mesh* sheet = basep.open.empty() ? nullptr : &basep.open;
        const double sheet_area = sheet ? area(*sheet) : 0.0;
        const auto estimate = [&](double v) {
            // Voxels across each band: 2 x 3 for the elements, 2 x (attach + 4) for the base, the
            // sheet's thickness + 2 x 4 for the sheet (vdb_solid.cpp); saturating sums.
            const std::uint64_t parts[3] = {print_detail::estimate_band_voxels(deco_area, v, 6.0),
                                            print_detail::estimate_band_voxels(base_area, v, 2.0 * (o.attach_mm / v + 4.0)),
                                            sheet ? print_detail::estimate_band_voxels(sheet_area, v, o.base_thickness_mm / v + 8.0) : 0};
            std::uint64_t total = 0;
            for (std::uint64_t p : parts) total = p > UINT64_MAX - total ? UINT64_MAX : total + p;
            return total;
        };
        const Vec3 size_mm = box.size() * s;
        const auto refuse = [&](double voxel) {
            throw InvalidInput(name + ": a " + mm(voxel) + " voxel grid over this " + mm(size_mm.maxCoeff()) + " model needs about " +
                               std::to_string(estimate(voxel)) + " narrow-band voxels (about " +
                               std::to_string(estimate(voxel) / (1ull << 20) * 30) + " MiB), over the limit of " +
                               std::to_string(o.max_voxels) + "; use a larger --voxel-mm, a smaller --size-mm or raise --max-voxels");
        };
        // A given voxel size is judged before anything heavy runs.
        if (o.voxel_mm > 0.0 && (estimate(o.voxel_mm) > o.max_voxels || size_mm.maxCoeff() / o.voxel_mm > 1e8)) refuse(o.voxel_mm);
        // The decoration's thinnest features (they set a derived voxel size, and are warned about).
        const auto tp = Clock::now();
        const ElementMesh elements = concatenate(deco.closed);
        const print_detail::ElementThickness th = print_detail::element_thickness(elements);
        std::vector<double> face_w(elements.mesh.faces.size());
        for (std::size_t f = 0; f < face_w.size(); ++f) face_w[f] = face_area(elements.mesh, f);
        const double thin_robust = weighted_percentile(th.of_face, face_w, 0.05);
        rep.seconds_prepare += since(tp);
        double voxel = o.voxel_mm;
        rep.voxel_derived = voxel <= 0.0;
        if (rep.voxel_derived) {
            // Eight voxels across the thinnest feature that can print: the decoration's thin end (5th
            // percentile of the thickness under its faces, by area, so rims and slivers do not
            // decide) but no thinner than --min-thickness; at most 0.1 mm (a printer's resolution).
            const double feature = std::max(std::isfinite(thin_robust) ? thin_robust : 0.8, o.min_thickness_mm);
            voxel = std::clamp(feature / 8.0, 0.005, 0.1);
            if (estimate(voxel) > o.max_voxels) {
                // The band is about area / voxel^2 (the base's and the sheet's also widen as the
                // voxel shrinks): start from the square-root scaling, then step until it fits.
                double coarser = voxel * std::sqrt(static_cast<double>(estimate(voxel)) / static_cast<double>(o.max_voxels));
                while (estimate(coarser) > o.max_voxels) coarser *= 1.05;
                result.warnings.push_back("voxel size coarsened from " + mm(voxel) + " to " + mm(coarser) + " to stay within " +
                                          std::to_string(o.max_voxels) + " voxels (--max-voxels)");
                voxel = coarser;
            }
        }
        rep.voxel_mm = voxel;
        rep.voxels_estimated = estimate(voxel);
        if (rep.voxels_estimated > o.max_voxels || size_mm.maxCoeff() / voxel > 1e8) refuse(voxel);
        print_detail::VoxelInput vin;
        for (const Mesh& m : deco.closed) vin.closed.push_back(&m);
        for (const Mesh& m : basep.closed) vin.closed_base.push_back(&m);
        vin.sheet = sheet;
        vin.sheet_thickness = o.base_thickness_mm;
        vin.attach = o.attach_mm;
        vin.voxel = voxel;
        vin.adaptivity = o.adaptivity;
        print_detail::VoxelSolid solid = print_detail::voxel_union(vin, o.reporter);
        rep.voids_filled = solid.voids_filled;
        rep.scraps_dropped = solid.scraps_dropped;
        if (solid.mesh.faces.empty())
            throw InvalidInput(name + ": nothing is left of the model at " + mm(voxel) + " voxels: every part is thinner than a voxel; use a smaller "
                               "--voxel-mm or a larger --size-mm");
        rep.voxels_active = solid.active_voxels;
        rep.seconds_voxelise = solid.seconds_voxelise;
        rep.seconds_mesh = solid.seconds_mesh;
        int parts = 0;
        std::vector<int> comp = connected_components(solid.mesh, &parts);
        result.model.mesh = std::move(solid.mesh);
        result.model.element_of_face = std::move(comp);
        result.model.num_elements = parts;
        if (parts > 1) {
            std::vector<std::size_t> faces_of(static_cast<std::size_t>(parts), 0);
            for (int c : result.model.element_of_face) ++faces_of[static_cast<std::size_t>(c)];
            rep.loose_bodies = parts - 1;
            const std::string largest = std::to_string(*std::max_element(faces_of.begin(), faces_of.end())) + " of " +
                                        std::to_string(result.model.mesh.faces.size()) + " triangles are in the largest";
            result.warnings.push_back(
                std::to_string(rep.loose_bodies) + " part(s) of the fused print are loose (" + largest + "); " +
                (base ? "a larger --attach-mm joins elements that float above the base"
                      : "if the decoration holds its base (--with-base), give the base with --base instead, so elements attach to it"));
        }
        // Thin features are lost or weak in a fused print, but the solid is still valid: warn.
        rep.min_thickness_mm = kInf;
        for (std::size_t e = 0; e < th.min_of_element.size(); ++e)
            if (th.min_of_element[e] < rep.min_thickness_mm) {
                rep.min_thickness_mm = th.min_of_element[e];
                rep.min_thickness_at = th.at_of_element[e];
                rep.min_thickness_body = -1;  // a decoration element, not an output body
            }
        if (rep.min_thickness_mm < o.min_thickness_mm)
            result.warnings.push_back("the thinnest decoration feature is " + mm(rep.min_thickness_mm) + " at " + at(rep.min_thickness_at) +
                                      ", under --min-thickness " + mm(o.min_thickness_mm) + "; it may not print");
    } else {
        std::vector<Mesh> bodies = std::move(deco.closed);
        for (Mesh& m : basep.closed) bodies.push_back(std::move(m));
        if (!basep.open.empty()) {
            const double voxel = std::min(0.1, o.base_thickness_mm / 8.0);
            const std::uint64_t need = print_detail::estimate_band_voxels(area(basep.open), voxel, o.base_thickness_mm / voxel + 8.0);
            if (need > o.max_voxels)
                throw InvalidInput("base: thickening the open base at " + mm(voxel) + " voxels needs about " + std::to_string(need) +
                                   " voxels, over --max-voxels " + std::to_string(o.max_voxels));
            print_detail::VoxelInput vin;
            vin.sheet = &basep.open;
            vin.sheet_thickness = o.base_thickness_mm;
            vin.voxel = voxel;
            vin.adaptivity = o.adaptivity;
            print_detail::VoxelSolid sheet = print_detail::voxel_union(vin, o.reporter);
            rep.voxel_mm = voxel;
            rep.voxels_active = sheet.active_voxels;
            rep.seconds_voxelise = sheet.seconds_voxelise;
            rep.seconds_mesh = sheet.seconds_mesh;
            bodies.push_back(std::move(sheet.mesh));
        }
        result.model = concatenate(bodies);
        o.reporter.report("check", 0.0);
        const auto tc = Clock::now();
        BodyChecks c = check_bodies(result.model, o.min_thickness_mm, o.min_clearance_mm);
        rep.seconds_checks = since(tc);
        rep.min_thickness_mm = c.min_thickness;
        rep.min_thickness_at = c.min_thickness_at;
        rep.min_thickness_body = c.min_thickness_body;
        rep.min_clearance_mm = c.min_clearance;
        rep.min_clearance_at = c.min_clearance_at;
        rep.min_clearance_bodies[0] = c.min_clearance_bodies[0];
        rep.min_clearance_bodies[1] = c.min_clearance_bodies[1];
        rep.intersecting_pairs = c.intersecting_pairs;
        rep.violations = std::move(c.violations);
        rep.checks_passed = rep.violations.empty();
    }

    // What we write, checked as a slicer would: closed, edge-manifold, outward.
    Mesh& out = result.model.mesh;
    const Box3 ob = bounding_box(out);
    if (!ob.empty()) {
        // The print bed is z = 0: the thickened sheet or the voxel surface may reach below the input's box.
        for (Vec3& v : out.vertices) v -= ob.min;
        for (PrintViolation& v : rep.violations) v.location -= ob.min;
        rep.min_thickness_at -= ob.min;
        rep.min_clearance_at -= ob.min;
    }
    // The files hold floats: check what they will hold.
    for (Vec3& v : out.vertices) v = v.cast<float>().cast<double>();
    rep.size_mm = bounding_box(out).size();
    rep.bodies = result.model.num_elements;
    rep.triangles = out.faces.size();
    rep.vertices = out.vertices.size();
    const MeshAnalysis a = analyse(out);
    rep.boundary_edges = a.boundary_edges;
    rep.non_manifold_edges = a.non_manifold_edges;
    rep.inconsistent_edges = a.inconsistent_edges;
    rep.degenerate_faces = a.degenerate_faces;
    rep.volume_mm3 = 0.0;
    for (const ElementInfo& e : a.elements) {
        rep.volume_mm3 += e.volume;
        if (e.closed && e.volume < 0.0) ++rep.inside_out_bodies;
    }
    if (rep.boundary_edges + rep.non_manifold_edges + rep.inconsistent_edges + rep.inside_out_bodies > 0)
        throw BackendFailure(name + ": the printable mesh is not watertight (" + std::to_string(rep.boundary_edges) + " open edges, " +
                             std::to_string(rep.non_manifold_edges) + " non-manifold edges, " + std::to_string(rep.inconsistent_edges) +
                             " inconsistent edges, " + std::to_string(rep.inside_out_bodies) + " inside-out bodies); nothing written");

    if (!rep.checks_passed) {
        std::string msg = name + ": the print checks failed (" + std::to_string(rep.violations.size()) + " violation(s)):";
        const std::size_t shown = std::min<std::size_t>(rep.violations.size(), 5);
        for (std::size_t i = 0; i < shown; ++i) {
            const PrintViolation& v = rep.violations[i];
            if (v.kind == PrintViolation::Kind::Clearance)
                msg += "\n  clearance " + mm(v.value_mm) + (v.value_mm == 0.0 ? " (the bodies touch or cut)" : "") + " < --min-clearance " +
                       mm(o.min_clearance_mm) + " between bodies " + std::to_string(v.body_a) + " and " + std::to_string(v.body_b) + " at " + at(v.location);
            else
                msg += "\n  thickness " + mm(v.value_mm) + " < --min-thickness " + mm(o.min_thickness_mm) + " in body " +
                       std::to_string(v.body_a) + " at " + at(v.location);
        }
        if (rep.violations.size() > shown) msg += "\n  ... (all of them in --report)";
        msg += "\nNothing written; --force writes anyway.";
        if (!o.force) throw PrintCheckFailed(msg, rep);
        result.warnings.push_back(msg.substr(0, msg.rfind('\n')) + "\nwritten anyway (--force)");
    }
    o.reporter.report("prepare", 1.0);
    return result;
}

}  // namespace meshquilt
