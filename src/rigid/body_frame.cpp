// SPDX-License-Identifier: MIT
// Principal frame of a rigid body.
#include "rigid/body_frame.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace emergent::rigid {

void symmetric_eigen(const double in[3][3], double values[3], double v[3][3]) {
    double a[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a[i][j] = in[i][j], v[i][j] = i == j;
    for (int sweep = 0; sweep < 50; ++sweep) {
        const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        if (off < 1e-30) break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                if (std::abs(a[p][q]) < 1e-300) continue;
                const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
                const double t = (theta >= 0 ? 1 : -1) / (std::abs(theta) + std::sqrt(theta * theta + 1));
                const double c = 1 / std::sqrt(t * t + 1), s = t * c;
                for (int k = 0; k < 3; ++k) {  // A <- J^T A J
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; ++k) {
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; ++k) {
                    const double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
    }
    // Sort ascending, keeping columns with their values.
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int i, int j) { return a[i][i] < a[j][j]; });
    double sorted[3][3];
    for (int c = 0; c < 3; ++c) {
        values[c] = a[order[c]][order[c]];
        for (int r = 0; r < 3; ++r) sorted[r][c] = v[r][order[c]];
    }
    // A right-handed frame: flip the last axis if the determinant is negative.
    const double det = sorted[0][0] * (sorted[1][1] * sorted[2][2] - sorted[1][2] * sorted[2][1]) -
                       sorted[0][1] * (sorted[1][0] * sorted[2][2] - sorted[1][2] * sorted[2][0]) +
                       sorted[0][2] * (sorted[1][0] * sorted[2][1] - sorted[1][1] * sorted[2][0]);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) v[r][c] = sorted[r][c] * (c == 2 && det < 0 ? -1 : 1);
}

namespace {
/// Quaternion of a proper rotation matrix (Shepperd's method).
Quat quaternion_of(const double m[3][3]) {
    const double tr = m[0][0] + m[1][1] + m[2][2];
    Quat q;
    if (tr > 0) {
        const double s = 2 * std::sqrt(tr + 1);
        q = {0.25 * s, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s};
    } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
        const double s = 2 * std::sqrt(1 + m[0][0] - m[1][1] - m[2][2]);
        q = {(m[2][1] - m[1][2]) / s, 0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s};
    } else if (m[1][1] > m[2][2]) {
        const double s = 2 * std::sqrt(1 + m[1][1] - m[0][0] - m[2][2]);
        q = {(m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s};
    } else {
        const double s = 2 * std::sqrt(1 + m[2][2] - m[0][0] - m[1][1]);
        q = {(m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s};
    }
    return normalized(q);
}
}  // namespace

BodyFrame principal_frame(const BodyShape& shape) {
    const std::size_t n = shape.positions.size();
    if (n == 0 || shape.masses.size() != n || shape.diameters.size() != n)
        throw std::invalid_argument("principal_frame: one mass and diameter per sphere");
    BodyFrame f;
    Vec3 com{0, 0, 0};
    for (std::size_t k = 0; k < n; ++k) {
        f.mass += shape.masses[k];
        com += shape.masses[k] * shape.positions[k];
    }
    com *= 1 / f.mass;
    double tensor[3][3] = {};
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3 r = shape.positions[k] - com;
        const double m = shape.masses[k], self = 0.1 * m * shape.diameters[k] * shape.diameters[k];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                tensor[i][j] += m * ((i == j) * dot(r, r) - r[i] * r[j]) + (i == j) * self;
    }
    double values[3], axes[3][3];
    symmetric_eigen(tensor, values, axes);
    f.inertia = {values[0], values[1], values[2]};
    f.orientation = quaternion_of(axes);
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3 body = rotate_back(f.orientation, shape.positions[k] - com);
        f.positions.push_back(body);
        f.extent = std::max(f.extent, std::sqrt(dot(body, body)) + 0.5 * shape.diameters[k]);
    }
    return f;
}

}  // namespace emergent::rigid
