// SPDX-License-Identifier: MIT
// Periodic Voronoi polygons from CGAL's Delaunay triangulation of the points and their images.
//
// CGAL's own periodic triangulation needs a square domain; triangulating the points together
// with enough periodic images works for any rectangle, and keeps CGAL's exact predicates (the
// topology is exact; only the circumcentres, used for edge lengths, are rounded).
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "emergent/kit/cell_pattern.hpp"

namespace emergent {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, DataStructure>;
using Point = Kernel::Point_2;
}  // namespace

VoronoiPattern periodic_voronoi(const std::vector<Point2>& points, double lx, double ly) {
    VoronoiPattern pattern;
    const int n = static_cast<int>(points.size());
    if (n == 0) return pattern;
    if (!(lx > 0) || !(ly > 0)) throw std::invalid_argument("periodic_voronoi: empty rectangle");
    // A polygon lies within the lx x ly rectangle centred on its point (its own images bound
    // it), so its neighbours lie within sqrt(lx^2 + ly^2) of it. Images out to `reach` periods
    // cover that; few points mean large polygons and need the wider ring.
    const int reach = n < 32 ? 2 : 1;
    std::vector<std::pair<Point, int>> sites;
    sites.reserve(static_cast<std::size_t>(n) * (2 * reach + 1) * (2 * reach + 1));
    for (int a = -reach; a <= reach; ++a)
        for (int b = -reach; b <= reach; ++b)
            for (int k = 0; k < n; ++k) {
                // info: the point's index for the original copy, -1 for an image.
                const int info = (a == 0 && b == 0) ? k : -1;
                sites.emplace_back(Point(points[k][0] + a * lx, points[k][1] + b * ly), info);
            }
    Delaunay triangulation;
    triangulation.insert(sites.begin(), sites.end());

    pattern.cells = n;
    pattern.edges.assign(n, 0);
    pattern.inradius.assign(n, 0.0);
    pattern.radial_range.assign(n, 0.0);
    // Dual edges shorter than this are the one vertex of four or more cocircular centres.
    const double tiny = 1e-9 * std::max(lx, ly);
    for (auto v = triangulation.finite_vertices_begin(); v != triangulation.finite_vertices_end(); ++v) {
        const int k = v->info();
        if (k < 0) continue;
        const Delaunay::Vertex_handle centre = v;
        double sum = 0, lo = HUGE_VAL, hi = -HUGE_VAL;
        int edges = 0;
        auto e = triangulation.incident_edges(centre), end = e;
        do {
            if (triangulation.is_infinite(e))
                throw std::logic_error("periodic_voronoi: a centre's polygon reaches the hull");
            const auto face = e->first;
            const auto twin = face->neighbor(e->second);
            const Point a = triangulation.dual(face), b = triangulation.dual(twin);
            if (std::sqrt(CGAL::squared_distance(a, b)) <= tiny) continue;
            const auto w = face->vertex(Delaunay::cw(e->second)) == centre
                               ? face->vertex(Delaunay::ccw(e->second))
                               : face->vertex(Delaunay::cw(e->second));
            const double d = 0.5 * std::sqrt(CGAL::squared_distance(centre->point(), w->point()));
            sum += d, lo = std::min(lo, d), hi = std::max(hi, d);
            ++edges;
        } while (++e != end);
        pattern.edges[k] = edges;
        pattern.inradius[k] = edges ? sum / edges : 0;
        pattern.radial_range[k] = edges ? hi - lo : 0;
    }

    double edge_sum = 0, six = 0, radius = 0, range = 0, range2 = 0;
    for (int k = 0; k < n; ++k) {
        edge_sum += pattern.edges[k];
        six += pattern.edges[k] == 6;
        radius += pattern.inradius[k];
        range += pattern.radial_range[k];
        range2 += pattern.radial_range[k] * pattern.radial_range[k];
        ++pattern.edge_histogram[std::min(pattern.edges[k], 13)];
    }
    pattern.mean_edges = edge_sum / n;
    pattern.six_sided_fraction = six / n;
    pattern.mean_inradius = radius / n;
    pattern.mean_radial_range = range / n;
    pattern.radial_range_spread =
        std::sqrt(std::max(0.0, range2 / n - pattern.mean_radial_range * pattern.mean_radial_range));
    return pattern;
}

}  // namespace emergent
