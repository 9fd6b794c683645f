// SPDX-License-Identifier: AGPL-3.0-or-later
// Planar mesh quilting, Zhou et al. 2006 Section 2: grids, seed finding, geometry matching, and the
// kernel (correspondences, deformation, merging) applied patch after patch.

#include "core/intersect.h"
#include "core/triangle_index.h"
#include "meshquilt/analysis.h"
#include "meshquilt/errors.h"
#include "meshquilt/quilt.h"
#include "quilt/fill.h"
#include "quilt/kernel.h"
#include "quilt/match.h"
#include "quilt/swatch.h"
#include "quilt/trim.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <sstream>

namespace meshquilt {

Mesh normalize_swatch(const Mesh& swatch) {
    const Box3 box = bounding_box(swatch);
    const ThinAxis thin = thin_axis_of(box);
    // Cyclic permutation (keeps orientation): the thin axis becomes z.
    const int ax = (thin.axis + 1) % 3, ay = (thin.axis + 2) % 3, az = thin.axis;
    Mesh out;
    out.faces = swatch.faces;
    out.vertices.reserve(swatch.vertices.size());
    for (const Vec3& v : swatch.vertices)
        out.vertices.emplace_back(v[ax] - box.min[ax], v[ay] - box.min[ay], v[az] - box.min[az]);
    return out;
}

namespace {

using quilt::area_centroid;
using quilt::mesh_area;
using quilt::num;
using quilt::SwatchData;
using quilt::window_density;

using quilt::Clock;
using quilt::kDensityInset;
using quilt::kMaxOutputFaces;
using quilt::seconds_since;

/// Below this share of the swatch's density (the report's window densities) the result carries a
/// warning. Every bundled swatch reaches 0.91 or more.
constexpr double kSparseOutput = 0.75;

/// Output grid with a margin of cells around the footprint, so that placements near the border
/// keep track of what they cover.
struct Grid {
    int nx = 0, ny = 0;          ///< footprint cells
    int margin_x = 0, margin_y = 0;
    double cell = 1.0;
    std::vector<char> processed;
    std::vector<int> occupied;   ///< number of alive element triangles touching the cell
    std::vector<std::vector<int>> bucket;  ///< element ids whose triangles touch the cell

    void init(int nx_, int ny_, int mx, int my, double c) {
        nx = nx_;
        ny = ny_;
        margin_x = mx;
        margin_y = my;
        cell = c;
        const std::size_t n = static_cast<std::size_t>(width()) * static_cast<std::size_t>(height());
        processed.assign(n, 0);
        occupied.assign(n, 0);
        bucket.assign(n, {});
    }
    [[nodiscard]] int width() const { return nx + 2 * margin_x; }
    [[nodiscard]] int height() const { return ny + 2 * margin_y; }
    /// Cell coordinates are relative to the footprint origin: footprint cells are [0, nx) x [0, ny).
    [[nodiscard]] bool valid(int i, int j) const { return i >= -margin_x && i < nx + margin_x && j >= -margin_y && j < ny + margin_y; }
    [[nodiscard]] std::size_t at(int i, int j) const {
        return static_cast<std::size_t>(j + margin_y) * static_cast<std::size_t>(width()) + static_cast<std::size_t>(i + margin_x);
    }
    [[nodiscard]] int cell_of(double x) const { return static_cast<int>(std::floor(x / cell)); }
};

struct OutputElement {
    Mesh mesh;
    int source = -1;
    bool alive = false;
    int collider_id = -1;
    std::vector<std::size_t> cells;  ///< grid cells its triangles touch (with multiplicity per triangle)
};

/// The faces of `result` that are not, vertex for vertex and bit for bit, faces of `before`. A change
/// to an element (a stitch, a deformation of threads) leaves the parts away from its seam exactly where
/// they were; those parts were tested against every element around when the later of the two went
/// in, so only the changed faces need a collision test.
Mesh changed_faces(const Mesh& result, const Mesh& before) {
    using Key = std::array<double, 9>;
    auto key = [](const Mesh& m, const Tri& f) {
        int first = 0;  // rotate so that the smallest corner comes first (orientation is kept)
        for (int k = 1; k < 3; ++k) {
            const Vec3& a = m.vertices[f[k]];
            const Vec3& b = m.vertices[f[first]];
            if (std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3)) first = k;
        }
        Key out;
        for (int k = 0; k < 3; ++k)
            for (int d = 0; d < 3; ++d) out[static_cast<std::size_t>(3 * k + d)] = m.vertices[f[(first + k) % 3]][d];
        return out;
    };
    std::set<Key> old_faces;
    for (const Tri& f : before.faces) old_faces.insert(key(before, f));
    Mesh out;
    out.vertices = result.vertices;
    for (const Tri& f : result.faces)
        if (!old_faces.count(key(result, f))) out.faces.push_back(f);
    return out;
}

class PlanarQuilter {
public:
    PlanarQuilter(const Mesh& swatch, const PlanarQuiltOptions& o) : opt_(o) {
        validate_options();
        auto t0 = Clock::now();
        sw_ = quilt::prepare_swatch(swatch);
        const ThinAxis thin = thin_axis_of(bounding_box(swatch));
        if (!thin.is_thin)
            throw InvalidInput("swatch has no thin axis: its smallest extent is more than half the middle one; a swatch must be a slab");
        index_ = TriangleIndex(sw_.mesh);
        const double lx = sw_.box.max.x(), ly = sw_.box.max.y();
        cell_ = opt_.cell_size > 0 ? opt_.cell_size : std::max(lx, ly) / 24.0;
        sx_ = static_cast<int>(std::floor(lx / cell_ + 1e-9));
        sy_ = static_cast<int>(std::floor(ly / cell_ + 1e-9));
        if (sx_ < 2 || sy_ < 2)
            throw InvalidInput("cell size " + num(cell_) + " is too large for the swatch footprint (" + num(lx) + " x " +
                               num(ly) + "): the swatch must span at least 2 cells each way");
        k_ = opt_.subpatch_cells > 0 ? opt_.subpatch_cells : std::max(2, static_cast<int>(std::lround(std::min(sx_, sy_) / 3.0)));
        k_ = std::min({k_, sx_, sy_});
        // Refuse outputs that would exhaust memory or run for hours, before any work.
        const double footprints = (opt_.width * opt_.height) / (lx * ly);
        const double estimated_faces = footprints * static_cast<double>(sw_.mesh.faces.size());
        if (estimated_faces > kMaxOutputFaces)
            throw InvalidInput("an output of " + num(opt_.width) + " x " + num(opt_.height) + " holds about " +
                               std::to_string(static_cast<long long>(footprints)) + " swatch footprints, about " +
                               std::to_string(static_cast<long long>(estimated_faces / 1e6)) + " million faces (limit " +
                               std::to_string(static_cast<long long>(kMaxOutputFaces / 1e6)) + " million): choose a smaller output");
        const int nx = static_cast<int>(std::ceil(opt_.width / cell_ - 1e-9));
        const int ny = static_cast<int>(std::ceil(opt_.height / cell_ - 1e-9));
        const double cells = static_cast<double>(nx) * ny;
        if (cells > 4.0e6)
            throw InvalidInput("output of " + num(opt_.width) + " x " + num(opt_.height) + " needs " +
                               std::to_string(static_cast<long long>(cells)) + " grid cells of size " + num(cell_) +
                               " (limit 4,000,000): choose a smaller output or a larger --cell");
        grid_.init(nx, ny, sx_, sy_, cell_);
        params_.metric.lambda = opt_.lambda;
        params_.metric.unit = sw_.mean_edge;
        params_.mu = opt_.mu;
        // A layered swatch's blobs overlap in projection: no squeeze by footprints (Swatch::layered).
        params_.blob_gap = sw_.elements_disjoint && !sw_.layered ? sw_.near_gap : 0.0;
        params_.layered = sw_.layered;
        params_.layer_gap = sw_.elements_disjoint && sw_.layered ? sw_.near_gap : 0.0;
        params_.strands = sw_.element_strand;
        params_.strand_losers = std::any_of(sw_.element_strand.begin(), sw_.element_strand.end(), [](char c) { return c != 0; });
        rng_.seed(opt_.seed);
        stage_seconds_["prepare"] += seconds_since(t0);
    }

    QuiltResult run() {
        QuiltResult result;
        const int total = grid_.nx * grid_.ny;
        int done = 0;
        const int max_steps = 8 * total + 16;
        for (int step = 0; step < max_steps && done < total; ++step) {
            const auto [si, sj] = find_seed();
            place_patch(si, sj);
            done = count_processed();
            opt_.reporter.report("quilting", static_cast<double>(done) / total);
        }
        if (done < total) throw meshquilt::Error(ErrorCode::Internal, "planar quilting did not cover the output grid");
        finish(result);
        return result;
    }

private:
    void validate_options() const {
        auto bad = [](double v) { return !std::isfinite(v) || v <= 0.0; };
        if (bad(opt_.width) || bad(opt_.height))
            throw InvalidInput("output size must be positive and finite (got " + num(opt_.width) + " x " + num(opt_.height) + ")");
        if (!std::isfinite(opt_.cell_size)) throw InvalidInput("cell size must be finite");
        if (bad(opt_.lambda)) throw InvalidInput("lambda must be positive");
        if (bad(opt_.mu)) throw InvalidInput("mu must be positive");
        if (!std::isfinite(opt_.tolerance) || opt_.tolerance < 0) throw InvalidInput("tolerance must be >= 0");
    }

    int count_processed() const {
        int n = 0;
        for (int j = 0; j < grid_.ny; ++j)
            for (int i = 0; i < grid_.nx; ++i) n += grid_.processed[grid_.at(i, j)];
        return n;
    }

    /// Section 2.3: the unprocessed footprint cell with the most processed neighbours (8-neighbourhood);
    /// ties are broken at random (from the seed), the very first seed is random.
    std::pair<int, int> find_seed() {
        int best = -1;
        std::vector<std::pair<int, int>> ties;
        for (int j = 0; j < grid_.ny; ++j)
            for (int i = 0; i < grid_.nx; ++i) {
                if (grid_.processed[grid_.at(i, j)]) continue;
                int n = 0;
                for (int dj = -1; dj <= 1; ++dj)
                    for (int di = -1; di <= 1; ++di)
                        if ((di || dj) && grid_.valid(i + di, j + dj)) n += grid_.processed[grid_.at(i + di, j + dj)];
                if (n > best) {
                    best = n;
                    ties.clear();
                }
                if (n == best) ties.emplace_back(i, j);
            }
        std::uniform_int_distribution<std::size_t> pick(0, ties.size() - 1);
        return ties[pick(rng_)];
    }

    std::vector<int> elements_in_rect(double x0, double y0, double x1, double y1) const {
        std::vector<int> ids;
        const int i0 = grid_.cell_of(x0), i1 = grid_.cell_of(x1), j0 = grid_.cell_of(y0), j1 = grid_.cell_of(y1);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i)
                if (grid_.valid(i, j))
                    for (int id : grid_.bucket[grid_.at(i, j)])
                        if (elems_[static_cast<std::size_t>(id)].alive) ids.push_back(id);
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        return ids;
    }

    void place_patch(int si, int sj) {
        auto t0 = Clock::now();
        // P_out: k x k cells around the seed.
        const int pi0 = si - k_ / 2, pj0 = sj - k_ / 2;
        const double px0 = pi0 * cell_, py0 = pj0 * cell_, px1 = (pi0 + k_) * cell_, py1 = (pj0 + k_) * cell_;
        std::vector<quilt::Sample> samples;
        for (int id : elements_in_rect(px0, py0, px1, py1)) {
            const Mesh& m = elems_[static_cast<std::size_t>(id)].mesh;
            const std::vector<Vec3> n = vertex_normals(m);
            for (std::size_t v = 0; v < m.vertices.size(); ++v) {
                const Vec3& p = m.vertices[v];
                if (p.x() >= px0 && p.x() < px1 && p.y() >= py0 && p.y() < py1) samples.push_back({p, n[v]});
            }
        }
        // Whole-cell translations that cover P_out completely (Section 2.4), and the placed patch.
        quilt::Placement pl = quilt::place_swatch(sw_, index_, params_.metric, samples, pi0, pj0, k_, sx_, sy_, cell_, opt_.tolerance, rng_);
        const int ti = pl.ti, tj = pl.tj;
        ++phase_count_[{((ti % sx_) + sx_) % sx_, ((tj % sy_) + sy_) % sy_}];
        std::vector<quilt::NewElement> fresh = std::move(pl.fresh);
        stage_seconds_["matching"] += seconds_since(t0);
        t0 = Clock::now();

        // The overlapping region.
        const double fx0 = ti * cell_, fy0 = tj * cell_, fx1 = (ti + sx_) * cell_, fy1 = (tj + sy_) * cell_;
        const Grid& g = grid_;
        quilt::Overlap overlap;
        overlap.old_side = [fx0, fy0, fx1, fy1](double x, double y) { return x >= fx0 && x < fx1 && y >= fy0 && y < fy1; };
        overlap.new_side = [&g](double x, double y) {
            const int i = g.cell_of(x), j = g.cell_of(y);
            if (!g.valid(i, j)) return false;
            const std::size_t c = g.at(i, j);
            return g.occupied[c] > 0;
        };
        std::vector<quilt::OldElement> old;
        std::vector<int> old_ids = elements_in_rect(fx0, fy0, fx1, fy1);
        for (int id : old_ids) old.push_back({id, elems_[static_cast<std::size_t>(id)].mesh, elems_[static_cast<std::size_t>(id)].source});
        const quilt::PatchPlan plan = quilt::plan_patch(old, fresh, overlap, params_);
        stage_seconds_["merging"] += seconds_since(t0);
        t0 = Clock::now();

        report_.stitch_failures += plan.stitch_failures;
        report_.elements_crowded_out += plan.crowding;
        for (const auto& [why, n] : plan.failure_reasons) failure_reasons_[why] += n;
        apply(plan);
        for (int j = tj; j < tj + sy_; ++j)
            for (int i = ti; i < ti + sx_; ++i)
                if (grid_.valid(i, j)) grid_.processed[grid_.at(i, j)] = 1;
        ++report_.patches;
        stage_seconds_["collisions"] += seconds_since(t0);
    }

    /// Applies a plan. Each change replaces its old element only if the result collides with nothing
    /// else; the old element stays otherwise. Refused changes are retried after the others (a new
    /// weave thread may cross an old thread that the same plan replaces), until no more go in.
    void apply(const quilt::PatchPlan& plan) {
        using Kind = quilt::PatchPlan::Change::Kind;
        std::vector<const quilt::PatchPlan::Change*> pending;
        for (const auto& ch : plan.changes) pending.push_back(&ch);
        // The plan's `squeezed` changes from `squeezed_from` on are losers kept (see plan_patch): extras,
        // not counted as avoided collisions when they do not fit.
        const quilt::PatchPlan::Change* first_squeezed = plan.changes.data() + plan.squeezed_from;
        auto is_squeezed = [&](const quilt::PatchPlan::Change* ch) { return ch >= first_squeezed && ch < first_squeezed + plan.squeezed; };
        for (int pass = 0; pass < 4 && !pending.empty(); ++pass) {
            std::vector<const quilt::PatchPlan::Change*> refused;
            for (const auto* ch : pending) {
                std::vector<int> ignore;
                if (ch->old_id >= 0) ignore.push_back(elems_[static_cast<std::size_t>(ch->old_id)].collider_id);
                const Mesh* mesh = &ch->mesh;
                Kind kind = ch->kind;
                // Faces the change kept exactly as they were need no new test (see changed_faces).
                const Mesh probe = ch->old_id >= 0 ? changed_faces(*mesh, elems_[static_cast<std::size_t>(ch->old_id)].mesh) : Mesh();
                if (collider_.collides(ch->old_id >= 0 ? probe : *mesh, ignore)) {
                    if (ch->fallback.faces.empty() || collider_.collides(ch->fallback, ignore)) {
                        refused.push_back(ch);
                        continue;
                    }
                    // The partner whole instead of the stitched element; an addition squeezed to fit.
                    mesh = &ch->fallback;
                    if (kind != Kind::Added) kind = Kind::Replaced;
                }
                if (kind == Kind::Added) {
                    // Beyond the paper: a blob keeps the swatch's clearance (a collision test alone let
                    // pebbles crowd 5-9% denser than the swatch).
                    if (!keeps_gap(*mesh, ch->source)) {
                        refused.push_back(ch);
                        continue;
                    }
                    add_element(*mesh, ch->source);
                    // A layered swatch's losers come back whole (KernelParams::layer_gap), not squeezed.
                    if (is_squeezed(ch) && (sw_.layered || quilt::is_strand_source(sw_, ch->source))) ++report_.losers_kept;
                    else if (is_squeezed(ch) || mesh == &ch->fallback) ++report_.elements_squeezed;
                    continue;
                }
                const int source = ch->source >= 0 ? ch->source : elems_[static_cast<std::size_t>(ch->old_id)].source;
                remove_element(ch->old_id);
                add_element(*mesh, source);
                if (kind == Kind::Stitched) ++report_.elements_stitched;
                if (kind == Kind::Replaced) ++report_.elements_replaced;
            }
            if (refused.size() == pending.size()) break;
            pending = std::move(refused);
        }
        for (const auto* ch : pending) {
            if (ch->kind == Kind::Added && add_strand_pieces(ch->mesh, ch->source)) continue;
            if (ch->kind == Kind::Stitched) ++report_.stitch_failures;
            else if (ch->kind != Kind::Deformed && !is_squeezed(ch)) ++report_.collisions_avoided;
        }
    }

    /// Beyond the paper: a strand (knot work) that cannot go in whole goes in cut across itself
    /// where it meets the output or comes closer to it than the swatch's clearance, as an
    /// under-crossing of knot work stops short of the strand over it (quilt::strand_pieces): the
    /// pieces at least quilt::kStrandPieceGirths of its girths long that then collide with nothing
    /// and keep half the clearance (the cuts lie half of it beyond the faces too close). None when
    /// the faces left unflagged hold less than `min_share` of its area.
    std::vector<Mesh> clear_strand_pieces(const Mesh& m, int source, double min_share = 0.0) const {
        if (!quilt::is_strand_source(sw_, source) || !(sw_.near_gap > 0.0)) return {};
        const double g = sw_.near_gap;
        std::vector<char> bad = collider_.colliding_faces(m);
        const Box3 box = bounding_box(m);
        const std::vector<int> around = elements_in_rect(box.min.x() - g, box.min.y() - g, box.max.x() + g, box.max.y() + g);
        std::vector<const Mesh*> near;
        for (int id : around) near.push_back(&elems_[static_cast<std::size_t>(id)].mesh);
        const std::vector<char> close = quilt::faces_near(m, near, g);
        for (std::size_t f = 0; f < m.faces.size(); ++f) bad[f] = static_cast<char>(bad[f] | close[f]);
        if (min_share > 0.0 && quilt::unflagged_area(m, bad) < min_share * quilt::mesh_area(m)) return {};
        quilt::ThreadCut cut;
        cut.margin = 0.5 * g;
        cut.min_girths = quilt::kStrandPieceGirths;
        std::vector<Mesh> pieces;
        for (Mesh& piece : quilt::strand_pieces(m, bad, cut)) {
            if (collider_.collides(piece)) continue;
            const Box3 pb = bounding_box(piece);
            if (std::any_of(near.begin(), near.end(), [&](const Mesh* o) { return quilt::element_gap(piece, pb, *o, g) < 0.5 * g; })) continue;
            pieces.push_back(std::move(piece));
        }
        return pieces;
    }

    /// Adds the pieces of strand `m` that clear the output (clear_strand_pieces); true when any went in.
    bool add_strand_pieces(const Mesh& m, int source) {
        bool any = false;
        for (Mesh& piece : clear_strand_pieces(m, source)) {
            add_element(piece, source);
            ++report_.strand_pieces;
            any = true;
        }
        return any;
    }

    /// A blob (genus-0 swatch element) added to the output keeps the swatch's clearance from the
    /// elements around it; rings and threads interlock or cross, and come closer.
    bool keeps_gap(const Mesh& m, int source, int ignore = -1) const {
        if (source < 0 || sw_.element_genus[static_cast<std::size_t>(source)] > 0 || !(sw_.near_gap > 0.0) || quilt::is_elongated(m)) return true;
        const Box3 box = bounding_box(m);
        const double g = sw_.near_gap;
        for (int id : elements_in_rect(box.min.x() - g, box.min.y() - g, box.max.x() + g, box.max.y() + g))
            if (id != ignore && !quilt::keeps_gap(quilt::element_gap(m, box, elems_[static_cast<std::size_t>(id)].mesh, g), g)) return false;
        return true;
    }

    /// Grid cells the triangles of `mesh` touch (by their boxes), one entry per triangle and cell.
    std::vector<std::size_t> cells_touched(const Mesh& mesh) const {
        std::vector<std::size_t> cells;
        for (const Tri& f : mesh.faces) {
            const Vec3& a = mesh.vertices[f[0]];
            const Vec3& b = mesh.vertices[f[1]];
            const Vec3& c = mesh.vertices[f[2]];
            const int i0 = grid_.cell_of(std::min({a.x(), b.x(), c.x()})), i1 = grid_.cell_of(std::max({a.x(), b.x(), c.x()}));
            const int j0 = grid_.cell_of(std::min({a.y(), b.y(), c.y()})), j1 = grid_.cell_of(std::max({a.y(), b.y(), c.y()}));
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i)
                    if (grid_.valid(i, j)) cells.push_back(grid_.at(i, j));
        }
        return cells;
    }

    void add_element(const Mesh& mesh, int source) {
        OutputElement e;
        e.mesh = mesh;
        e.source = source;
        e.alive = true;
        e.collider_id = collider_.add(mesh);
        const int id = static_cast<int>(elems_.size());
        e.cells = cells_touched(mesh);
        std::vector<std::size_t> unique_cells = e.cells;
        std::sort(unique_cells.begin(), unique_cells.end());
        unique_cells.erase(std::unique(unique_cells.begin(), unique_cells.end()), unique_cells.end());
        for (std::size_t c : e.cells) ++grid_.occupied[c];
        for (std::size_t c : unique_cells) grid_.bucket[c].push_back(id);
        elems_.push_back(std::move(e));
    }

    void remove_element(int id) {
        OutputElement& e = elems_[static_cast<std::size_t>(id)];
        if (!e.alive) return;
        e.alive = false;
        collider_.remove(e.collider_id);
        for (std::size_t c : e.cells) --grid_.occupied[c];
        std::vector<std::size_t> unique_cells = e.cells;
        std::sort(unique_cells.begin(), unique_cells.end());
        unique_cells.erase(std::unique(unique_cells.begin(), unique_cells.end()), unique_cells.end());
        for (std::size_t c : unique_cells) {
            auto& b = grid_.bucket[c];
            b.erase(std::remove(b.begin(), b.end(), id), b.end());
        }
        e.mesh = Mesh();
    }

    /// Beyond the paper: bald spots left where new elements collided or lost their merges are filled
    /// one blob at a time after the last patch (quilt/fill.h: fill_spots, centred in the footprint).
    /// Rings and threads are never used: they must interlock or continue, which a lone element
    /// cannot.
    void fill_bald_spots() {
        // Spots in ground sparser than 90% of the swatch's density: the 10% the planar stage allows.
        const quilt::FillSetup setup = quilt::prepare_fill(sw_, std::sqrt(opt_.width * opt_.height / 4e6), 0.9, 0.4);
        if (setup.shapes.empty()) return;
        auto t0 = Clock::now();
        const double reach = setup.reach;
        quilt::Coverage cov(-reach, -reach, opt_.width + reach, opt_.height + reach, setup.pixel);
        for (const OutputElement& e : elems_)
            if (e.alive) cov.add(e.mesh);
        std::vector<Mesh> cut_tries;  // strands `fits` cut to their pieces, told apart in `add`
        report_.bald_spots_filled += quilt::fill_spots(
            cov, setup, [&](const Vec2& c) { return c.x() >= 0 && c.y() >= 0 && c.x() <= opt_.width && c.y() <= opt_.height; },
            [&](const Vec2& c, double r) { return cov.area_density(c, r); },
            [&](const Vec2& c, double r) {
                std::vector<std::vector<Vec2>> hulls;
                for (int id : elements_in_rect(c.x() - r, c.y() - r, c.x() + r, c.y() + r))
                    hulls.push_back(quilt::xy_hull(elems_[static_cast<std::size_t>(id)].mesh));
                return hulls;
            },
            // A layered swatch's shape, and a strand, come unsqueezed (FillSetup::layered, Shape::whole):
            // they must keep the clearance themselves.
            [&](Mesh& m, int source) {
                if (!collider_.collides(m) && ((!sw_.layered && !quilt::is_strand_source(sw_, source)) || keeps_gap(m, source))) return true;
                // A strand that does not fit whole may go in as its pieces that do, if they keep
                // kFillPieceShare of it (clear_strand_pieces).
                if (!quilt::is_strand_source(sw_, source)) return false;
                const std::vector<Mesh> pieces = clear_strand_pieces(m, source, quilt::kFillPieceShare);
                double kept = 0.0;
                for (const Mesh& p : pieces) kept += quilt::mesh_area(p);
                if (pieces.empty() || kept < quilt::kFillPieceShare * quilt::mesh_area(m)) return false;
                m = quilt::join_meshes(pieces);
                cut_tries.push_back(m);
                return true;
            },
            [&](const Mesh& m, int source) {
                const std::vector<Mesh> parts = quilt::split_components(m);
                const bool cut = std::any_of(cut_tries.begin(), cut_tries.end(), [&](const Mesh& c) { return c.vertices == m.vertices; });
                cut_tries.clear();
                for (const Mesh& p : parts) {
                    add_element(p, source);
                    report_.strand_pieces += cut;
                }
            });
        stage_seconds_["bald spots"] += seconds_since(t0);
    }

    /// Beyond the paper: joints. Where two patches' elements meet, the joints between blobs come out
    /// wider than the swatch's (two tessellations do not fit). Each blob side (hull edge, see
    /// hull_sides) that faces a joint wider than the swatch's 90th percentile (and narrower than
    /// kJointReach times it: wider ground is a bald spot) grows into it, leaving the swatch's median
    /// joint, by the smooth map of push_side; the element must stay within kMaxGrowth of its swatch
    /// element's area, collide with nothing and keep the clearance, or the growth is halved (twice)
    /// and then dropped. A porous pattern (pebbles) has a wide 90th percentile, and barely grows.
    /// With `gaps`, stones grow radially into the holes where several meet (quilt::grow_into_gaps).
    void close_wide_joints(bool gaps) {
        if (!joints_.paving) return;
        auto t0 = Clock::now();
        const double reach = joints_.reach, limit = std::max(joints_.limit, gaps ? reach : 0.0);
        std::vector<int> ids;
        for (std::size_t id = 0; id < elems_.size(); ++id)
            if (elems_[id].alive && quilt::is_blob_source(sw_, elems_[id].source)) ids.push_back(static_cast<int>(id));
        for (int id : ids) {
            const OutputElement& el = elems_[static_cast<std::size_t>(id)];
            const Box3 box = bounding_box(el.mesh);
            const Vec3 mid = 0.5 * (box.min + box.max);
            if (mid.x() < -reach || mid.y() < -reach || mid.x() > opt_.width + reach || mid.y() > opt_.height + reach) continue;
            std::vector<std::vector<Vec2>> around;
            for (int o : elements_in_rect(box.min.x() - limit, box.min.y() - limit, box.max.x() + limit, box.max.y() + limit))
                if (o != id) around.push_back(quilt::xy_hull(elems_[static_cast<std::size_t>(o)].mesh));
            const int source = el.source;
            Mesh grown;
            const double source_area = mesh_area(sw_.elements[static_cast<std::size_t>(source)]);
            auto accept = [&](const Mesh& g) { return !collider_.collides(g, {el.collider_id}) && keeps_gap(g, source, id); };
            if (!(gaps ? quilt::grow_into_gaps(el.mesh, around, joints_, source_area, accept, &grown)
                       : quilt::grow_into_joints(el.mesh, around, joints_, source_area, accept, &grown)))
                continue;
            remove_element(id);
            add_element(grown, source);
            ++report_.joints_closed;
        }
        stage_seconds_["joints"] += seconds_since(t0);
    }

    void finish(QuiltResult& result) {
        fill_bald_spots();
        // Twice: a side held back by the growth cap or a neighbour's growth gets a second chance.
        // Then the holes where several stones meet, twice too.
        joints_ = quilt::prepare_joints(sw_);
        for (int pass = 0; pass < 2; ++pass) close_wide_joints(false);
        for (int pass = 0; pass < 2; ++pass) close_wide_joints(true);
        auto t0 = Clock::now();
        // Keep elements whose centroid lies in the footprint; remove those that are not whole.
        std::vector<int> kept;
        for (std::size_t id = 0; id < elems_.size(); ++id) {
            OutputElement& e = elems_[id];
            if (!e.alive) continue;
            const Vec3 c = area_centroid(e.mesh);
            if (c.x() < 0 || c.y() < 0 || c.x() >= opt_.width || c.y() >= opt_.height) continue;
            const bool source_closed = e.source >= 0 && sw_.element_closed[static_cast<std::size_t>(e.source)];
            if (source_closed && !quilt::is_closed_oriented(e.mesh)) {
                ++report_.elements_removed;
                continue;
            }
            kept.push_back(static_cast<int>(id));
        }
        // Elements that still intersect another (the swatch's own did not) are removed, smaller first.
        std::vector<const Mesh*> kept_meshes;
        for (int id : kept) kept_meshes.push_back(&elems_[static_cast<std::size_t>(id)].mesh);
        std::vector<char> drop(kept.size(), 0);
        if (sw_.elements_disjoint) drop = quilt::intersecting_to_remove(kept_meshes);
        for (char d : drop) report_.elements_removed += d;
        std::vector<const Mesh*> final_meshes;
        for (std::size_t k = 0; k < kept.size(); ++k) {
            if (drop[k]) continue;
            const OutputElement& e = elems_[static_cast<std::size_t>(kept[k])];
            final_meshes.push_back(&e.mesh);
            result.source_element.push_back(e.source);
            if (quilt::is_closed_oriented(e.mesh)) ++report_.elements_closed;
        }
        ElementMesh out = concatenate(final_meshes);
        result.mesh = std::move(out.mesh);
        result.element_of_face = std::move(out.element_of_face);
        stage_seconds_["finish"] += seconds_since(t0);
        for (const auto& [why, n] : failure_reasons_) opt_.reporter.debug("stitch failed " + std::to_string(n) + " times: " + why);

        QualityReport& r = report_;
        r.faces = static_cast<int>(result.mesh.faces.size());
        r.vertices = static_cast<int>(result.mesh.vertices.size());
        r.elements = static_cast<int>(result.source_element.size());
        r.cell_size = cell_;
        // Densities by the same estimator on both sides: face area (by face centroid) per area of a
        // window inset from the border, which keeps ragged swatch margins out of the figure.
        const double mx = kDensityInset * sw_.box.size().x(), my = kDensityInset * sw_.box.size().y();
        r.swatch_density = window_density(sw_.mesh, mx, my, sw_.box.size().x() - mx, sw_.box.size().y() - my);
        r.output_density = (opt_.width > 2 * mx && opt_.height > 2 * my)
                               ? window_density(result.mesh, mx, my, opt_.width - mx, opt_.height - my)
                               : mesh_area(result.mesh) / (opt_.width * opt_.height);
        for (const auto& [phase, n] : phase_count_) r.largest_translation_share = std::max(r.largest_translation_share, n);
        for (const auto& [stage, s] : stage_seconds_) r.seconds.emplace_back(stage, s);
        result.report = r;
        if (const std::string turned = sw_.turn_warning(); !turned.empty()) result.warnings.push_back(turned);
        if (const std::string w = sw_.solidify_warning(); !w.empty()) result.warnings.push_back(w);
        if (r.elements_removed > 0)
            result.warnings.push_back(std::to_string(r.elements_removed) + " element(s) could not be made whole or intersected others and were removed");
        // A sparse output is no silent result: say how sparse, and what the merges said. (A swatch
        // that is one large connected net, such as a grid of bars, cannot be merged where two
        // placements overlap; each placement's copy then stands whole or not at all.)
        if (r.swatch_density > 0.0 && r.output_density < kSparseOutput * r.swatch_density) {
            std::string most;
            int most_n = 0;
            for (const auto& [why, n] : failure_reasons_)
                if (n > most_n) {
                    most = why;
                    most_n = n;
                }
            std::string text = "the output is sparse: it holds " + num(r.output_density / r.swatch_density) + " of the swatch's density";
            if (r.stitch_failures > 0)
                text += "; " + std::to_string(r.stitch_failures) + " merge(s) of overlapping elements failed (most often: " + most +
                        "), and an element that cannot be merged with its neighbour leaves bare ground";
            if (sw_.spans_swatch())
                text += "; the swatch's largest element covers " + num(sw_.largest_element_cover) +
                        " of its footprint: a connected net or lattice can only be placed whole (a swatch of separate elements, such as "
                        "threads, rings or tiles, covers fully)";
            result.warnings.push_back(text);
        }
        // A thinned swatch (its elements intersect, or its rings are tight): the output thickened
        // back, after every measure, which compares thinned elements with the thinned swatch.
        if (const std::string w = sw_.intersect_warning(); !w.empty()) result.warnings.push_back(w);
        const auto t_thick = Clock::now();
        const std::vector<double> offset(result.source_element.size(), sw_.thinned);
        if (const int less = quilt::thicken_output(sw_, &result.mesh, result.element_of_face, offset); less > 0)
            result.warnings.push_back(std::to_string(less) + " of " + std::to_string(offset.size()) +
                                      " elements were thickened back less, since in full they would meet a neighbour the swatch's elements do not meet");
        if (sw_.thinned > 0.0) result.report.seconds.emplace_back("thicken back", seconds_since(t_thick));
    }

    PlanarQuiltOptions opt_;
    SwatchData sw_;
    quilt::JointSetup joints_;
    TriangleIndex index_;
    quilt::KernelParams params_;
    double cell_ = 1.0;
    int sx_ = 0, sy_ = 0, k_ = 0;
    Grid grid_;
    std::vector<OutputElement> elems_;
    ElementCollider collider_;
    std::mt19937_64 rng_;
    QualityReport report_;
    std::map<std::pair<int, int>, int> phase_count_;
    std::map<std::string, double> stage_seconds_;
    std::map<std::string, int> failure_reasons_;
};

}  // namespace

QuiltResult quilt_plane(const Mesh& swatch, const PlanarQuiltOptions& options) {
    if (swatch.faces.empty()) throw InvalidInput("swatch has no faces");
    PlanarQuilter q(swatch, options);
    return q.run();
}

}  // namespace meshquilt
