// SPDX-License-Identifier: MIT
// Rescaling of the fluid layer next to a thermal wall.
#include <cmath>
#include <stdexcept>

#include "decomposition/reductions.hpp"
#include "emergent/wall_layer.hpp"

namespace emergent {

WallLayerThermostat::WallLayerThermostat(int axis, double lo, double hi, double temperature,
                                         long long interval)
    : axis_(axis), lo_(lo), hi_(hi), temperature_(temperature), interval_(interval) {
    if (axis < 0 || axis > 2 || !(hi > lo) || !(temperature > 0) || interval < 1)
        throw std::invalid_argument("WallLayerThermostat: needs axis 0-2, hi > lo, T > 0, interval >= 1");
}

void WallLayerThermostat::apply(ParticleStore& store, const std::vector<double>& mass,
                                MPI_Comm comm, long long step) {
    if (step % interval_ != 0) return;
    auto inside = [&](std::size_t i) {
        const double s = store.position[i][axis_];
        return s >= lo_ && s < hi_;
    };
    // Mass, momentum, 2 x kinetic energy and number of the layer's particles.
    double all[6] = {0, 0, 0, 0, 0, 0};
    for (std::size_t i = 0; i < store.n_owned(); ++i) {
        if (!inside(i)) continue;
        const double m = mass[store.species[i]];
        const Vec3& v = store.velocity[i];
        all[0] += m;
        all[1] += m * v.x, all[2] += m * v.y, all[3] += m * v.z;
        all[4] += m * dot(v, v);
        all[5] += 1;
    }
    decomp::sum_in_place(comm, all, 6);
    const double n = all[5];
    // Two constraints (the zeroed mean flow along the wall): 3 n - 2 degrees of freedom.
    if (n < 2) return;
    Vec3 drift{all[1] / all[0], all[2] / all[0], all[3] / all[0]};
    drift[axis_] = 0;  // the flow across the wall is kept
    const double twice_kinetic = all[4] - all[0] * dot(drift, drift);
    const double dof = 3 * n - 2;
    if (!(twice_kinetic > 0)) return;
    const double factor = std::sqrt(temperature_ * dof / twice_kinetic);
    for (std::size_t i = 0; i < store.n_owned(); ++i)
        if (inside(i)) store.velocity[i] = factor * (store.velocity[i] - drift);
    energy_ += 0.5 * (factor * factor * twice_kinetic - all[4]);
}

}  // namespace emergent
