// SPDX-License-Identifier: AGPL-3.0-or-later
// The fused print solid through OpenVDB: narrow-band level sets of the closed bodies (one
// meshToLevelSet over all of them: OpenVDB supports self-intersecting closed input, so overlapping
// bodies come out as their union), an unsigned-distance sheet around an open base, csgUnion, and
// adaptive volumeToMesh. OpenVDB was chosen over hand-written voxel code: it is sparse (memory
// follows the surface, not the box), parallel (TBB), and its mesher yields closed meshes.

#include "meshquilt/analysis.h"
#include "meshquilt/errors.h"
#include "print_detail.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/ChangeBackground.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <array>
#include <atomic>
#include <map>
#include <chrono>
#include <cmath>
#include <mutex>

namespace meshquilt::print_detail {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Forwards OpenVDB's interruption polls to the Reporter. OpenVDB may poll from worker threads, so
/// the answer is an atomic flag; Cancelled is thrown by us after OpenVDB returns, never through it.
class Interrupter : public openvdb::util::NullInterrupter {
public:
    Interrupter(const Reporter& r, std::string stage, double fraction) : r_(r), stage_(std::move(stage)), fraction_(fraction) {}
    bool wasInterrupted(int /*percent*/ = -1) override {
        if (cancelled_.load()) return true;
        if (!r_.progress) return false;
        // OpenVDB polls once per polygon from every worker: ask the Reporter at most every 0.1 s,
        // from whichever thread gets the lock, and never wait for it.
        const auto now = Clock::now().time_since_epoch().count();
        if (now - last_.load() < 100'000'000) return false;
        std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
        if (!lock.owns_lock()) return false;
        last_ = now;
        if (!r_.progress(stage_, fraction_)) cancelled_ = true;
        return cancelled_.load();
    }
    void check() const {
        if (cancelled_.load()) throw Cancelled("cancelled during " + stage_);
    }

private:
    const Reporter& r_;
    std::string stage_;
    double fraction_;
    std::mutex mutex_;
    std::atomic<bool> cancelled_{false};
    std::atomic<Clock::rep> last_{0};
};

void append(const Mesh& m, std::vector<openvdb::Vec3s>& pts, std::vector<openvdb::Vec3I>& tris) {
    const auto base = static_cast<openvdb::Index32>(pts.size());
    for (const Vec3& v : m.vertices)
        pts.emplace_back(static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()));
    for (const Tri& t : m.faces)
        tris.emplace_back(base + static_cast<openvdb::Index32>(t[0]), base + static_cast<openvdb::Index32>(t[1]),
                          base + static_cast<openvdb::Index32>(t[2]));
}


}  // namespace

std::uint64_t estimate_band_voxels(double area, double voxel, double band_voxels) {
    if (!(voxel > 0.0)) return UINT64_MAX;
    const double n = area / (voxel * voxel) * band_voxels;
    return n >= 1.8e19 ? UINT64_MAX : static_cast<std::uint64_t>(n);
}

VoxelSolid voxel_union(const VoxelInput& in, const Reporter& reporter) {
    static std::once_flag init;
    std::call_once(init, [] { openvdb::initialize(); });
    VoxelSolid out;
    const auto t0 = Clock::now();
    const double voxel = in.voxel;
    const openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(voxel);
    constexpr float kHalfWidth = 3.0f;  // voxels on each side of the surface
    const auto background = static_cast<float>(kHalfWidth * voxel);

    // A level set shifted outward by `grow` (world units): its band is widened first so the
    // shifted surface still has kHalfWidth voxels on each side; then clamped back to that band so
    // every grid agrees on the background for the union.
    const auto shifted = [&](openvdb::FloatGrid::Ptr g, double grow) {
        const auto d = static_cast<float>(grow);
        if (d != 0.0f) {
            for (auto it = g->tree().beginValueOn(); it; ++it) it.setValue(*it - d);
            openvdb::tools::changeBackground(g->tree(), g->background() - d);
        }
        for (auto it = g->tree().beginValueOn(); it; ++it)
            if (*it > background) it.setValue(background);
            else if (*it < -background) it.setValue(-background);
        openvdb::tools::changeLevelSetBackground(g->tree(), background);
        g->setGridClass(openvdb::GRID_LEVEL_SET);
        return g;
    };
    const auto merge = [](openvdb::FloatGrid::Ptr& into, openvdb::FloatGrid::Ptr g) {
        if (into)
            openvdb::tools::csgUnion(*into, *g);
        else
            into = std::move(g);
    };

    openvdb::FloatGrid::Ptr grid;
    try {
        if (!in.closed.empty()) {
            std::vector<openvdb::Vec3s> pts;
            std::vector<openvdb::Vec3I> tris;
            for (const Mesh* m : in.closed) append(*m, pts, tris);
            Interrupter intr(reporter, "voxelise", 0.1);
            grid = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(intr, *xform, pts, tris, kHalfWidth);
            intr.check();
        }
        if (!in.closed_base.empty()) {
            std::vector<openvdb::Vec3s> pts;
            std::vector<openvdb::Vec3I> tris;
            for (const Mesh* m : in.closed_base) append(*m, pts, tris);
            Interrupter intr(reporter, "voxelise", 0.4);
            const auto half = static_cast<float>(in.attach / voxel + kHalfWidth + 1.0);
            auto g = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(intr, *xform, pts, tris, half);
            intr.check();
            merge(grid, shifted(g, in.attach));
        }
        if (in.sheet) {
            // |distance| - t/2 is a level set of the sheet; the band must reach across all of it.
            // Elements rest on the surface, inside the sheet's upper half: no attach growth needed.
            const double h = 0.5 * in.sheet_thickness;
            const auto band = static_cast<float>(h / voxel + kHalfWidth + 1.0);
            std::vector<openvdb::Vec3s> pts;
            std::vector<openvdb::Vec3I> tris;
            append(*in.sheet, pts, tris);
            Interrupter intr(reporter, "voxelise", 0.7);
            auto udf = openvdb::tools::meshToUnsignedDistanceField<openvdb::FloatGrid>(intr, *xform, pts, tris, {}, band);
            intr.check();
            merge(grid, shifted(udf, h));
        }
    } catch (const openvdb::Exception& e) {
        throw BackendFailure(std::string("OpenVDB failed while voxelising: ") + e.what());
    }
    if (!grid) throw InvalidInput("nothing to voxelise");
    out.active_voxels = grid->activeVoxelCount();
    out.seconds_voxelise = since(t0);
    reporter.report("mesh solid", 0.0);

    const auto t1 = Clock::now();
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
    try {
        openvdb::tools::volumeToMesh(*grid, points, tris, quads, 0.0, in.adaptivity, true);
    } catch (const openvdb::Exception& e) {
        throw BackendFailure(std::string("OpenVDB failed while meshing: ") + e.what());
    }
    grid.reset();
    Mesh& m = out.mesh;
    m.vertices.reserve(points.size());
    // The mesher may emit two points at exactly the same place (seams of adaptive polygons); they
    // are one vertex, or a slicer sees a zero-area facet there.
    std::vector<int> weld(points.size());
    {
        std::map<std::array<float, 3>, int> at;
        for (std::size_t i = 0; i < points.size(); ++i) {
            const auto [it, fresh] = at.emplace(std::array<float, 3>{points[i].x(), points[i].y(), points[i].z()}, static_cast<int>(m.vertices.size()));
            if (fresh) m.vertices.emplace_back(points[i].x(), points[i].y(), points[i].z());
            weld[i] = it->second;
        }
    }
    m.faces.reserve(tris.size() + 2 * quads.size());
    // Adaptive meshing collapses some polygons: a quad may repeat a corner (a triangle) and a
    // triangle may repeat one (no area; its two edges cancel). Drop the repeats, keep the rest.
    const auto add_triangle = [&](int a, int b, int c) {
        if (a != b && b != c && c != a) m.faces.emplace_back(a, b, c);
    };
    for (const auto& t : tris) add_triangle(weld[t[0]], weld[t[1]], weld[t[2]]);
    for (const auto& q : quads) {
        int c[4];
        int n = 0;
        for (int k = 0; k < 4; ++k) {
            const int v = weld[q[k]];
            if (n == 0 || v != c[n - 1]) c[n++] = v;
        }
        if (n > 1 && c[n - 1] == c[0]) --n;
        if (n == 3) {
            add_triangle(c[0], c[1], c[2]);
        } else if (n == 4) {
            // The shorter diagonal gives the better-shaped pair of triangles.
            if ((m.vertices[c[0]] - m.vertices[c[2]]).squaredNorm() <= (m.vertices[c[1]] - m.vertices[c[3]]).squaredNorm()) {
                add_triangle(c[0], c[1], c[2]);
                add_triangle(c[0], c[2], c[3]);
            } else {
                add_triangle(c[0], c[1], c[3]);
                add_triangle(c[1], c[2], c[3]);
            }
        }
    }
    // OpenVDB's winding depends on the sign convention; make it outward (positive volume).
    if (signed_volume(m) < 0.0)
        for (Tri& t : m.faces) std::swap(t[1], t[2]);
    // A part with negative volume is the inner wall of an enclosed void (air trapped between
    // elements and the base): fill it, as a slicer would print it anyway only as a weak pocket.
    int parts = 0;
    const std::vector<int> comp = connected_components(m, &parts);
    if (parts > 1) {
        std::vector<double> volume(static_cast<std::size_t>(parts), 0.0);
        for (std::size_t f = 0; f < m.faces.size(); ++f) {
            const Tri& t = m.faces[f];
            volume[static_cast<std::size_t>(comp[f])] += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]]));
        }
        // Adaptive meshing can also leave a flat closed scrap (two triangles back to back, say)
        // whose volume is zero up to rounding: any part under a hundredth of a voxel goes too.
        const double scrap = 6.0 * 0.01 * voxel * voxel * voxel;  // `volume` holds 6 x the volume
        std::vector<char> drop(volume.size(), 0);
        for (std::size_t c = 0; c < volume.size(); ++c) {
            if (volume[c] < -scrap) ++out.voids_filled, drop[c] = 1;
            else if (volume[c] < scrap) ++out.scraps_dropped, drop[c] = 1;
        }
        if (out.voids_filled + out.scraps_dropped > 0) {
            std::size_t kept = 0;
            for (std::size_t f = 0; f < m.faces.size(); ++f)
                if (!drop[static_cast<std::size_t>(comp[f])]) m.faces[kept++] = m.faces[f];
            m.faces.resize(kept);
        }
    }
    // Keep only the vertices faces use (dropped voids and scraps leave some behind).
    std::vector<int> renum(m.vertices.size(), -1);
    std::vector<Vec3> used;
    used.reserve(m.vertices.size());
    for (Tri& t : m.faces)
        for (int k = 0; k < 3; ++k) {
            int& r = renum[static_cast<std::size_t>(t[k])];
            if (r < 0) {
                r = static_cast<int>(used.size());
                used.push_back(m.vertices[static_cast<std::size_t>(t[k])]);
            }
            t[k] = r;
        }
    m.vertices = std::move(used);
    out.seconds_mesh = since(t1);
    return out;
}

}  // namespace meshquilt::print_detail
