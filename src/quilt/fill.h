// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Beyond the paper: bald spots. After the last placement, an output can hold bare spots where new
// elements collided with the old ones around them or lost their merges (the paper never refuses an
// element, so it has none; it has intersections instead). A bare spot is measured as the largest
// empty disc in the xy projection, and compared with the swatch's own largest one.

#include "meshquilt/mesh.h"

#include <vector>

namespace meshquilt::quilt {

/// What the xy projections of meshes cover, on a raster of square pixels over a rectangle.
class Coverage {
public:
    Coverage(double x0, double y0, double x1, double y1, double pixel);

    /// Marks the pixels whose centres the projection of a face of `m` covers (a face smaller than
    /// a pixel marks the pixel of its centroid; vertical faces cover nothing).
    void add(const Mesh& m);

    /// Per pixel, the distance from its centre to the nearest covered pixel centre (0 on covered
    /// pixels; a huge value when nothing is covered). Exact Euclidean distance transform (Felzenszwalb
    /// and Huttenlocher 2012), linear in the number of pixels.
    [[nodiscard]] std::vector<double> empty_distance() const;
    /// The same within pixels [i0, i1] x [j0, j1] only (covered pixels outside are not seen), row
    /// major over the window.
    [[nodiscard]] std::vector<double> empty_distance(int i0, int j0, int i1, int j1) const;

    /// Share of the pixels with centres in the disc (`c`, `radius`) that are covered (0 without any).
    [[nodiscard]] double covered_share(const Vec2& c, double radius) const;
    /// Share of the pixels with centres in [x0, x1] x [y0, y1] that are covered.
    [[nodiscard]] double covered_share(double x0, double y0, double x1, double y1) const;

    [[nodiscard]] int nx() const { return nx_; }
    [[nodiscard]] int ny() const { return ny_; }
    [[nodiscard]] double pixel() const { return pixel_; }
    [[nodiscard]] Vec2 centre(int i, int j) const { return {x0_ + (i + 0.5) * pixel_, y0_ + (j + 0.5) * pixel_}; }
    [[nodiscard]] bool covered(int i, int j) const { return covered_[static_cast<std::size_t>(j) * nx_ + i] != 0; }

private:
    double x0_, y0_, pixel_;
    int nx_, ny_;
    std::vector<char> covered_;
};

/// The sides of a convex polygon (counter-clockwise, as xy_hull gives it) worth measuring: edges of at
/// least 5% of its perimeter (a rounded corner is many short edges, not a side).
std::vector<std::size_t> hull_sides(const std::vector<Vec2>& hull);

/// How far side `edge` of `hull` (edge from vertex `edge` to the next) can move along its outward
/// normal before it meets one of `others` (convex polygons): the least distance along rays from
/// five points of the side's middle 80%. `limit` when no ray meets anything within it.
double side_clearance(const std::vector<Vec2>& hull, std::size_t edge, const std::vector<std::vector<Vec2>>& others, double limit);

/// The radius of the largest empty disc centred in [x0, x1] x [y0, y1] among the elements of `m`
/// (xy projection, pixel resolution), with geometry anywhere in `m` counting.
double largest_empty_radius(const Mesh& m, double x0, double y0, double x1, double y1, double pixel);

}  // namespace meshquilt::quilt
