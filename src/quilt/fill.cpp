// SPDX-License-Identifier: AGPL-3.0-or-later
#include "quilt/fill.h"

#include "meshquilt/analysis.h"
#include "quilt/kernel.h"
#include "quilt/swatch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

namespace meshquilt::quilt {

namespace {

/// One-dimensional squared distance transform of sampled function `f` (lower envelope of parabolas,
/// Felzenszwalb and Huttenlocher, "Distance Transforms of Sampled Functions", 2012).
void distance_1d(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v, std::vector<double>& z) {
    const int n = static_cast<int>(f.size());
    constexpr double inf = std::numeric_limits<double>::infinity();
    int k = -1;
    for (int q = 0; q < n; ++q) {
        if (f[q] == inf) continue;  // a parabola at infinity never forms the envelope
        while (k >= 0) {
            const double s = ((f[q] + q * q) - (f[v[k]] + v[k] * v[k])) / (2.0 * (q - v[k]));
            if (s > z[k]) break;
            --k;
        }
        ++k;
        v[k] = q;
        z[k] = k == 0 ? -inf : ((f[q] + q * q) - (f[v[k - 1]] + v[k - 1] * v[k - 1])) / (2.0 * (q - v[k - 1]));
        z[k + 1] = inf;
    }
    if (k < 0) {
        std::fill(d.begin(), d.end(), inf);
        return;
    }
    int j = 0;
    for (int q = 0; q < n; ++q) {
        while (z[j + 1] < q) ++j;
        d[q] = (q - v[j]) * (q - v[j]) + f[v[j]];
    }
}

}  // namespace

Coverage::Coverage(double x0, double y0, double x1, double y1, double pixel, bool projected)
    : x0_(x0), y0_(y0), pixel_(pixel),
      nx_(std::max(1, static_cast<int>(std::ceil((x1 - x0) / pixel)))),
      ny_(std::max(1, static_cast<int>(std::ceil((y1 - y0) / pixel)))),
      covered_(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), 0),
      area_(covered_.size(), 0.0),
      projected_(projected) {}

void Coverage::add(const Mesh& m) {
    rasterise(m, [&](std::size_t k) { covered_[k] = 1; }, [&](std::size_t k, double a) { area_[k] += a; });
}

void Coverage::add(const std::vector<const Mesh*>& meshes) {
    struct Marks {
        std::vector<std::size_t> covered;
        std::vector<std::pair<std::size_t, double>> area;  // in face order
    };
    std::vector<Marks> marks(meshes.size());
    tbb::parallel_for(std::size_t{0}, meshes.size(), [&](std::size_t i) {
        Marks& mk = marks[i];
        rasterise(*meshes[i], [&](std::size_t k) { mk.covered.push_back(k); }, [&](std::size_t k, double a) { mk.area.emplace_back(k, a); });
    });
    for (const Marks& mk : marks) {
        for (std::size_t k : mk.covered) covered_[k] = 1;
        for (const auto& [k, a] : mk.area) area_[k] += a;
    }
}

template <class Cover, class Area>
void Coverage::rasterise(const Mesh& m, Cover&& cover, Area&& add_area) const {
    for (const Tri& f : m.faces) {
        const Vec3& p = m.vertices[f[0]];
        const Vec3& q = m.vertices[f[1]];
        const Vec3& r = m.vertices[f[2]];
        {
            const double cx = (p.x() + q.x() + r.x()) / 3.0, cy = (p.y() + q.y() + r.y()) / 3.0;
            const int i = column(cx), j = row(cy);
            const Vec3 n = (q - p).cross(r - p);
            if (i >= 0 && j >= 0 && i < nx_ && j < ny_) add_area(static_cast<std::size_t>(j) * nx_ + i, 0.5 * (projected_ ? std::abs(n.z()) : n.norm()));
        }
        const double area = (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
        const int i0 = std::max(0, static_cast<int>(std::floor((std::min({p.x(), q.x(), r.x()}) - x0_) / pixel_)));
        const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((std::max({p.x(), q.x(), r.x()}) - x0_) / pixel_)));
        const int j0 = std::max(0, static_cast<int>(std::floor((std::min({p.y(), q.y(), r.y()}) - y0_) / pixel_)));
        const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((std::max({p.y(), q.y(), r.y()}) - y0_) / pixel_)));
        if (i0 > i1 || j0 > j1 || std::abs(area) < 1e-300) continue;
        bool any = false;
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const Vec2 c = centre(i, j);
                const double w0 = (q.x() - c.x()) * (r.y() - c.y()) - (q.y() - c.y()) * (r.x() - c.x());
                const double w1 = (r.x() - c.x()) * (p.y() - c.y()) - (r.y() - c.y()) * (p.x() - c.x());
                const double w2 = (p.x() - c.x()) * (q.y() - c.y()) - (p.y() - c.y()) * (q.x() - c.x());
                if (area > 0 ? (w0 >= 0 && w1 >= 0 && w2 >= 0) : (w0 <= 0 && w1 <= 0 && w2 <= 0)) {
                    cover(static_cast<std::size_t>(j) * nx_ + i);
                    any = true;
                }
            }
        if (!any) {
            const double cx = (p.x() + q.x() + r.x()) / 3.0, cy = (p.y() + q.y() + r.y()) / 3.0;
            const int i = static_cast<int>(std::floor((cx - x0_) / pixel_)), j = static_cast<int>(std::floor((cy - y0_) / pixel_));
            if (i >= 0 && j >= 0 && i < nx_ && j < ny_) cover(static_cast<std::size_t>(j) * nx_ + i);
        }
    }
}

void Coverage::cover_outside(const Coverage& mask) {
    for (std::size_t k = 0; k < covered_.size() && k < mask.covered_.size(); ++k)
        if (!mask.covered_[k]) covered_[k] = 1;
}

void squared_distance_transform(std::vector<double>& sq, int w, int h) {
    if (w <= 0 || h <= 0) return;
    const int longest = std::max(w, h);
    std::vector<double> f, d;
    std::vector<double> z(static_cast<std::size_t>(longest) + 1);
    std::vector<int> v(static_cast<std::size_t>(longest));
    // One 1D transform along each of `lines` lines of `length` samples, sample k of line l at
    // sq[l * across + k * along].
    auto pass = [&](int lines, int length, std::size_t across, std::size_t along) {
        f.resize(static_cast<std::size_t>(length));
        d.resize(static_cast<std::size_t>(length));
        for (int l = 0; l < lines; ++l) {
            for (int k = 0; k < length; ++k) f[static_cast<std::size_t>(k)] = sq[l * across + k * along];
            distance_1d(f, d, v, z);
            for (int k = 0; k < length; ++k) sq[l * across + k * along] = d[static_cast<std::size_t>(k)];
        }
    };
    pass(w, h, 1, static_cast<std::size_t>(w));  // columns
    pass(h, w, static_cast<std::size_t>(w), 1);  // rows
}

std::vector<double> Coverage::empty_distance() const { return empty_distance(0, 0, nx_ - 1, ny_ - 1); }

std::vector<double> Coverage::empty_distance(int i0, int j0, int i1, int j1) const {
    constexpr double inf = std::numeric_limits<double>::infinity();
    i0 = std::max(i0, 0);
    j0 = std::max(j0, 0);
    i1 = std::min(i1, nx_ - 1);
    j1 = std::min(j1, ny_ - 1);
    const int w = i1 - i0 + 1, h = j1 - j0 + 1;
    if (w <= 0 || h <= 0) return {};
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    std::vector<double> sq(n);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) sq[static_cast<std::size_t>(j) * w + i] = covered(i0 + i, j0 + j) ? 0.0 : inf;
    squared_distance_transform(sq, w, h);
    std::vector<double> out(n);
    for (std::size_t k = 0; k < n; ++k) out[k] = sq[k] == inf ? std::numeric_limits<double>::max() : pixel_ * std::sqrt(sq[k]);
    return out;
}

double Coverage::covered_share(const Vec2& c, double radius) const {
    const int i0 = std::max(0, column(c.x() - radius)), i1 = std::min(nx_ - 1, column(c.x() + radius));
    const int j0 = std::max(0, row(c.y() - radius)), j1 = std::min(ny_ - 1, row(c.y() + radius));
    long in = 0, hit = 0;
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
            if ((centre(i, j) - c).squaredNorm() <= radius * radius) {
                ++in;
                hit += covered(i, j) ? 1 : 0;
            }
    return in > 0 ? static_cast<double>(hit) / static_cast<double>(in) : 0.0;
}

double Coverage::area_density(const Vec2& c, double radius, const Coverage* mask) const {
    const int i0 = std::max(0, column(c.x() - radius)), i1 = std::min(nx_ - 1, column(c.x() + radius));
    const int j0 = std::max(0, row(c.y() - radius)), j1 = std::min(ny_ - 1, row(c.y() + radius));
    long in = 0;
    double area = 0.0;
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
            if ((!mask || mask->covered(i, j)) && (centre(i, j) - c).squaredNorm() <= radius * radius) {
                ++in;
                area += area_[static_cast<std::size_t>(j) * nx_ + i];
            }
    return in > 0 ? area / (static_cast<double>(in) * pixel_ * pixel_) : 0.0;
}

bool is_blob_source(const SwatchData& sw, int source) {
    if (source < 0 || static_cast<std::size_t>(source) >= sw.elements.size()) return false;
    const auto s = static_cast<std::size_t>(source);
    return sw.element_closed[s] && sw.element_genus[s] == 0 && !is_elongated(sw.elements[s]) && !is_strand_source(sw, source);
}

bool is_strand_source(const SwatchData& sw, int source) {
    return source >= 0 && static_cast<std::size_t>(source) < sw.element_strand.size() && sw.element_strand[static_cast<std::size_t>(source)] != 0;
}

namespace {

/// May swatch element `source` fill a bald spot alone? A blob (is_blob_source), and since session 44
/// an open compact sheet with one rim and no handles (a cap, a leaf, a scale modelled as a single
/// surface), neither a thread nor a strand, which is no more bound to its neighbours than a blob is.
bool is_fill_source(const SwatchData& sw, int source) {
    if (is_blob_source(sw, source)) return true;
    if (source < 0 || static_cast<std::size_t>(source) >= sw.elements.size()) return false;
    const auto s = static_cast<std::size_t>(source);
    if (sw.element_closed[s] || is_elongated(sw.elements[s]) || is_strand_source(sw, source)) return false;
    const MeshAnalysis a = analyse(sw.elements[s]);
    return a.elements.size() == 1 && a.boundary_loops == 1 && a.genus == 0;
}

}  // namespace

FillSetup prepare_fill(const SwatchData& sw, double min_pixel, double sparse, double min_area, bool projected) {
    FillSetup s;
    s.projected = projected;
    s.sparse = sparse;
    s.min_area = min_area;
    s.layered = sw.layered;
    if (!sw.elements_disjoint || !(sw.near_gap > 0.0)) return s;
    double narrowest = 1e300;
    for (std::size_t e = 0; e < sw.elements.size(); ++e) {
        const Mesh& m = sw.elements[e];
        if (!is_fill_source(sw, static_cast<int>(e))) continue;
        const Vec3 c = area_centroid(m);
        const Vec3 size = bounding_box(m).size();
        s.smallest_blob_area = s.smallest_blob_area > 0.0 ? std::min(s.smallest_blob_area, mesh_area(m)) : mesh_area(m);
        s.reach = std::max(s.reach, 0.5 * size.head<2>().norm());
        narrowest = std::min(narrowest, std::min(size.x(), size.y()));
        for (const double f : {1.0, kFillScale}) {
            FillSetup::Shape shape{static_cast<int>(e), m, 0.0, f, mesh_area(m)};
            for (Vec3& v : shape.mesh.vertices) v = Vec3(f * (v.x() - c.x()), f * (v.y() - c.y()), v.z());
            shape.area = mesh_area(shape.mesh);
            s.shapes.push_back(std::move(shape));
        }
    }
    // Strands go in whole (a strand squeezed or shrunk is thinner than its kind): those no larger
    // than the median strand or the largest blob, as a spot seldom holds more.
    std::vector<std::pair<double, std::size_t>> strands;
    for (std::size_t e = 0; e < sw.elements.size(); ++e)
        if (is_strand_source(sw, static_cast<int>(e))) strands.push_back({0.5 * bounding_box(sw.elements[e]).size().head<2>().norm(), e});
    if (!strands.empty()) {
        std::vector<double> half;
        for (const auto& [h, e] : strands) half.push_back(h);
        std::nth_element(half.begin(), half.begin() + static_cast<std::ptrdiff_t>(half.size() / 2), half.end());
        const double cap = std::max(half[half.size() / 2], s.reach);
        for (const auto& [h, e] : strands) {
            if (h > cap) continue;
            const Mesh& m = sw.elements[e];
            const Vec3 c = area_centroid(m);
            const Vec3 size = bounding_box(m).size();
            s.reach = std::max(s.reach, h);
            narrowest = std::min(narrowest, std::min(size.x(), size.y()));
            FillSetup::Shape shape{static_cast<int>(e), m, 0.0, 1.0, mesh_area(m), true};
            for (Vec3& v : shape.mesh.vertices) v = Vec3(v.x() - c.x(), v.y() - c.y(), v.z());
            shape.area = mesh_area(shape.mesh);
            s.shapes.push_back(std::move(shape));
        }
    }
    if (s.shapes.empty()) return s;
    // Largest first: a try that cannot beat the best so far is skipped.
    std::stable_sort(s.shapes.begin(), s.shapes.end(), [](const FillSetup::Shape& a, const FillSetup::Shape& b) { return a.area > b.area; });
    s.gap = sw.near_gap;
    s.pixel = std::max(0.5 * sw.near_gap, min_pixel);
    const double lx = sw.box.size().x(), ly = sw.box.size().y();
    const double mx = kDensityInset * lx, my = kDensityInset * ly;
    if (projected) {
        Coverage window(mx, my, lx - mx, ly - my, s.pixel, true);
        window.add(sw.mesh);
        s.swatch_density = window.area_density(Vec2(0.5 * lx, 0.5 * ly), lx + ly);
    } else {
        s.swatch_density = window_density(sw.mesh, mx, my, lx - mx, ly - my);
    }
    s.smallest_spot = std::max(largest_empty_radius(sw.mesh, mx, my, lx - mx, ly - my, s.pixel),
                               sw.near_gap + 0.5 * kFillScale * (1.0 - kFillPush) * narrowest);
    return s;
}

int fill_spots(Coverage& cov, const FillSetup& setup, const std::function<bool(const Vec2&)>& may_centre,
               const std::function<double(const Vec2&, double)>& density,
               const std::function<std::vector<std::vector<Vec2>>(const Vec2&, double)>& around,
               const std::function<bool(Mesh&, int)>& fits, const std::function<void(const Mesh&, int)>& add) {
    if (setup.shapes.empty()) return 0;
    const int nx = cov.nx(), ny = cov.ny();
    const double pixel = cov.pixel();
    std::vector<double> d = cov.empty_distance();
    std::vector<char> allowed(d.size(), 0);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) allowed[static_cast<std::size_t>(j) * nx + i] = may_centre(cov.centre(i, j)) ? 1 : 0;
    int added = 0;
    for (;;) {
        double widest = 0.0;
        std::size_t at = 0;
        for (std::size_t k = 0; k < d.size(); ++k)
            if (allowed[k] && d[k] > widest) {
                widest = d[k];
                at = k;
            }
        if (widest <= setup.smallest_spot) break;
        const int ci = static_cast<int>(at % static_cast<std::size_t>(nx)), cj = static_cast<int>(at / static_cast<std::size_t>(nx));
        const Vec2 c = cov.centre(ci, cj);
        const int rp = static_cast<int>(std::ceil(std::min(widest, 1e6 * pixel) / pixel));
        auto leave = [&] {  // no more tries centred in this spot
            for (int j = std::max(0, cj - rp); j <= std::min(ny - 1, cj + rp); ++j)
                for (int i = std::max(0, ci - rp); i <= std::min(nx - 1, ci + rp); ++i)
                    if ((cov.centre(i, j) - c).norm() <= widest) allowed[static_cast<std::size_t>(j) * nx + i] = 0;
            allowed[at] = 0;
        };
        if (density(c, kFillWindow * setup.reach) >= setup.sparse * setup.swatch_density) {
            leave();
            continue;
        }
        const std::vector<std::vector<Vec2>> hulls = around(c, std::min(widest, 4.0 * setup.reach) + 2.0 * setup.reach);
        Mesh best;
        int best_source = -1;
        double best_area = 0.0;
        for (const FillSetup::Shape& s : setup.shapes) {
            if (s.area <= best_area) break;
            Mesh placed = translated(s.mesh, Vec3(c.x(), c.y(), 0.0));
            if (!setup.layered && !s.whole && !squeeze_clear(placed, hulls, setup.gap, setup.min_area / (s.scale * s.scale), kFillPush)) continue;
            const double a = mesh_area(placed);
            if (a <= best_area || a < setup.min_area * s.swatch_area || a < setup.area_floor || !fits(placed, s.source)) continue;
            const double kept = mesh_area(placed);  // `fits` may have cut it
            if (kept <= best_area) continue;
            best = std::move(placed);
            best_source = s.source;
            best_area = kept;
        }
        if (best_source < 0) {
            leave();
            continue;
        }
        add(best, best_source);
        ++added;
        cov.add(best);
        // Distances only shrink, and only within the widest spot's radius of the new element.
        const Box3 b = bounding_box(best);
        const int i0 = cov.column(b.min.x()) - rp - 1, i1 = cov.column(b.max.x()) + rp + 1;
        const int j0 = cov.row(b.min.y()) - rp - 1, j1 = cov.row(b.max.y()) + rp + 1;
        const std::vector<double> local = cov.empty_distance(i0, j0, i1, j1);
        const int w = std::min(i1, nx - 1) - std::max(i0, 0) + 1;
        for (std::size_t k = 0; k < local.size(); ++k) {
            const std::size_t g = static_cast<std::size_t>(std::max(j0, 0) + static_cast<int>(k) / w) * nx + std::max(i0, 0) + static_cast<int>(k) % w;
            d[g] = std::min(d[g], local[k]);
        }
    }
    return added;
}

namespace {

/// Distance from p to polygon `poly`'s boundary.
double distance_to_polygon(const Vec2& p, const std::vector<Vec2>& poly) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i], e = poly[(i + 1) % poly.size()] - a;
        const double l2 = e.squaredNorm();
        const double t = l2 > 0.0 ? std::clamp((p - a).dot(e) / l2, 0.0, 1.0) : 0.0;
        best = std::min(best, (a + t * e - p).norm());
    }
    return best;
}

/// Where the ray from c along the unit vector u crosses the boundary of polygon `poly`: the first
/// crossing (`last` false; infinity if none) or the last (`last` true; 0 if none).
double ray_crossing(const Vec2& c, const Vec2& u, const std::vector<Vec2>& poly, bool last) {
    double best = last ? 0.0 : std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec2 p = poly[i], d = poly[(i + 1) % poly.size()] - p;
        // c + t u = p + w d: Cramer's rule.
        const double den = u.x() * (-d.y()) - u.y() * (-d.x());
        if (std::abs(den) < 1e-300) continue;
        const Vec2 r = p - c;
        const double t = (r.x() * (-d.y()) - r.y() * (-d.x())) / den;
        const double w = (u.x() * r.y() - u.y() * r.x()) / den;
        if (t >= 0.0 && w >= -1e-12 && w <= 1.0 + 1e-12) best = last ? std::max(best, t) : std::min(best, t);
    }
    return best;
}

}  // namespace

std::vector<std::size_t> hull_sides(const std::vector<Vec2>& hull) {
    double perimeter = 0.0;
    for (std::size_t i = 0; i < hull.size(); ++i) perimeter += (hull[(i + 1) % hull.size()] - hull[i]).norm();
    std::vector<std::size_t> sides;
    for (std::size_t i = 0; i < hull.size(); ++i)
        if ((hull[(i + 1) % hull.size()] - hull[i]).norm() >= 0.05 * perimeter) sides.push_back(i);
    return sides;
}

double side_clearance(const std::vector<Vec2>& hull, std::size_t edge, const std::vector<std::vector<Vec2>>& others, double limit) {
    const Vec2 a = hull[edge], b = hull[(edge + 1) % hull.size()];
    const Vec2 e = b - a;
    if (!(e.norm() > 0.0)) return limit;
    const Vec2 n = Vec2(e.y(), -e.x()).normalized();  // outward for a counter-clockwise polygon
    double best = limit;
    for (int k = 0; k < 5; ++k)
        for (const auto& poly : others) best = std::min(best, ray_crossing(a + (0.1 + 0.2 * k) * e, n, poly, false));
    return best;
}

JointSetup prepare_joints(const SwatchData& sw) {
    JointSetup s;
    if (!sw.elements_disjoint || !(sw.near_gap > 0.0) || sw.layered) return s;
    std::vector<std::vector<Vec2>> hulls;
    for (const Mesh& m : sw.elements) hulls.push_back(xy_hull(m));
    std::vector<std::size_t> blobs;
    double reach = 0.0;
    for (std::size_t e = 0; e < sw.elements.size(); ++e) {
        if (!is_blob_source(sw, static_cast<int>(e))) continue;
        blobs.push_back(e);
        reach = std::max(reach, 0.5 * bounding_box(sw.elements[e]).size().head<2>().norm());
    }
    std::vector<double> joints, sizes;
    for (std::size_t e : blobs) {
        std::vector<std::vector<Vec2>> others;
        for (std::size_t o = 0; o < hulls.size(); ++o)
            if (o != e) others.push_back(hulls[o]);
        for (std::size_t side : hull_sides(hulls[e])) {
            const double f = side_clearance(hulls[e], side, others, reach);
            if (f < reach) joints.push_back(f);
        }
        sizes.push_back(std::sqrt(polygon_area(hulls[e])));
    }
    if (joints.size() < 8) return s;
    std::sort(joints.begin(), joints.end());
    std::sort(sizes.begin(), sizes.end());
    s.typical = joints[joints.size() / 2];
    s.wide = joints[static_cast<std::size_t>(0.9 * static_cast<double>(joints.size() - 1))];
    s.limit = kJointReach * s.wide;
    s.reach = reach;
    s.paving = s.typical <= kPavingJoint * sizes[sizes.size() / 2];
    return s;
}

bool grow_into_joints(const Mesh& m, const std::vector<std::vector<Vec2>>& around, const JointSetup& setup, double source_area,
                      const std::function<bool(const Mesh&)>& accept, Mesh* grown) {
    if (!setup.paving) return false;
    const std::vector<Vec2> hull = xy_hull(m);
    struct Grow { Vec2 inward; double by; };
    std::vector<Grow> grows;
    for (std::size_t s : hull_sides(hull)) {
        const double f = side_clearance(hull, s, around, setup.limit);
        if (f <= setup.wide || f >= setup.limit) continue;
        const Vec2 e = hull[(s + 1) % hull.size()] - hull[s];
        grows.push_back({Vec2(-e.y(), e.x()).normalized(), f - setup.typical});
    }
    for (double share = 1.0; share > 0.2 && !grows.empty(); share *= 0.5) {
        Mesh g = m;
        for (const Grow& gr : grows) {
            double lo = 1e300, hi = -1e300;
            for (const Vec3& v : g.vertices) {
                lo = std::min(lo, gr.inward.dot(v.head<2>()));
                hi = std::max(hi, gr.inward.dot(v.head<2>()));
            }
            push_side(g, gr.inward, lo, hi, -std::min(share * gr.by, 0.3 * (hi - lo)));
        }
        if (mesh_area(g) > kMaxGrowth * source_area || !accept(g)) continue;
        *grown = std::move(g);
        return true;
    }
    return false;
}

bool grow_into_gaps(const Mesh& m, const std::vector<std::vector<Vec2>>& around, const JointSetup& setup, double source_area,
                    const std::function<bool(const Mesh&)>& accept, Mesh* grown) {
    if (!setup.paving) return false;
    const std::vector<Vec2> hull = xy_hull(m);
    if (hull.size() < 3) return false;
    Vec2 c = Vec2::Zero();
    for (const Vec2& p : hull) c += p;
    c /= static_cast<double>(hull.size());
    constexpr int K = kGapDirections;
    std::array<double, K> radius{}, move{};
    for (int k = 0; k < K; ++k) {
        const double a = 2.0 * M_PI * k / K;
        const Vec2 u(std::cos(a), std::sin(a));
        radius[k] = ray_crossing(c, u, hull, true);
        const Vec2 b = c + radius[k] * u;
        // Ahead: the nearest hull that rays along u and 30 degrees either side of it meet.
        const std::array<Vec2, 3> ahead{u, Vec2(std::cos(a - kGapConeHalfAngle), std::sin(a - kGapConeHalfAngle)),
                                        Vec2(std::cos(a + kGapConeHalfAngle), std::sin(a + kGapConeHalfAngle))};
        double free = setup.reach, across = setup.reach;
        for (const auto& o : around) {
            free = std::min(free, distance_to_polygon(b, o));
            for (const Vec2& w : ahead) across = std::min(across, ray_crossing(b, w, o, false));
        }
        move[k] = across >= setup.reach || free <= setup.wide ? 0.0 : std::min(free - setup.typical, kGapRadialShare * radius[k]);
    }
    // Eroded over the neighbouring directions: a move between a joint and a gap is the joint's.
    std::array<double, K> eroded{};
    double gain = 0.0, area = 0.0;
    for (int k = 0; k < K; ++k) {
        eroded[k] = std::min({move[k], move[(k + 1) % K], move[(k + K - 1) % K]});
        gain += eroded[k] * radius[k];
        area += 0.5 * radius[k] * radius[k];
    }
    if (!(gain >= kMinGapGain * area)) return false;
    for (double share : {1.0, 0.75, 0.5, 0.25}) {
        Mesh g = m;
        for (Vec3& v : g.vertices) {
            const Vec2 q = v.head<2>() - c;
            const double r = q.norm();
            if (!(r > 0.0)) continue;
            double t = std::atan2(q.y(), q.x()) / (2.0 * M_PI) * K;
            if (t < 0.0) t += K;
            const int k0 = std::min(static_cast<int>(t), K - 1), k1 = (k0 + 1) % K;
            const double w = t - k0;
            const double rk = (1.0 - w) * radius[static_cast<std::size_t>(k0)] + w * radius[static_cast<std::size_t>(k1)];
            if (!(rk > 0.0)) continue;
            const double s = std::min(r / rk, 1.0);
            const double to = r + share * ((1.0 - w) * eroded[static_cast<std::size_t>(k0)] + w * eroded[static_cast<std::size_t>(k1)]) * s * s;
            v.x() = c.x() + q.x() / r * to;
            v.y() = c.y() + q.y() / r * to;
        }
        if (mesh_area(g) > kMaxGrowth * source_area || !accept(g)) continue;
        *grown = std::move(g);
        return true;
    }
    return false;
}

double largest_empty_radius(const Mesh& m, double x0, double y0, double x1, double y1, double pixel) {
    const Box3 b = bounding_box(m);
    if (b.empty()) return 0.0;
    Coverage cov(b.min.x(), b.min.y(), b.max.x(), b.max.y(), pixel);
    cov.add(m);
    const std::vector<double> d = cov.empty_distance();
    double best = 0.0;
    for (int j = 0; j < cov.ny(); ++j)
        for (int i = 0; i < cov.nx(); ++i) {
            const Vec2 c = cov.centre(i, j);
            if (c.x() >= x0 && c.x() <= x1 && c.y() >= y0 && c.y() <= y1) best = std::max(best, d[static_cast<std::size_t>(j) * cov.nx() + i]);
        }
    return best;
}

}  // namespace meshquilt::quilt
