// SPDX-License-Identifier: MIT
// Rescaling of the fluid layer next to a thermal wall.
#include <cmath>
#include <stdexcept>

#include "decomposition/reductions.hpp"
#include "emergent/execution.hpp"
#include "emergent/wall_layer.hpp"
#include "thermostat/wall_layer_rescale.hpp"

namespace emergent {

WallLayerThermostat::WallLayerThermostat(int axis, double lo, double hi, double temperature,
                                         long long interval)
    : axis_(axis), lo_(lo), hi_(hi), temperature_(temperature), interval_(interval) {
    if (axis < 0 || axis > 2 || !(hi > lo) || !(temperature > 0) || interval < 1)
        throw std::invalid_argument("WallLayerThermostat: needs axis 0-2, hi > lo, T > 0, interval >= 1");
}

void WallLayerThermostat::apply(const BackendParticles& p, MPI_Comm comm, long long step) {
    if (!due(step)) return;
    double all[kSums];
    measure(p, all);
    decomp::sum_in_place(comm, all, kSums);
    rescale(p, all);
}

void WallLayerThermostat::measure(const BackendParticles& p, double* sums) const {
    const thermostat::LayerSums local = exec::transform_sum<thermostat::LayerSums>(
        p.target, p.n_owned, thermostat::LayerMember{p.position, p.velocity, p.species, p.mass, {axis_, lo_, hi_}});
    const double mine[kSums] = {local.mass, local.momentum.x, local.momentum.y, local.momentum.z,
                                local.twice_kinetic, local.count};
    for (int k = 0; k < kSums; ++k) sums[k] = mine[k];
}

void WallLayerThermostat::rescale(const BackendParticles& p, const double* all) {
    // Mass, momentum, 2 x kinetic energy and number of the layer's particles.
    const double n = all[5];
    // Two constraints (the zeroed mean flow along the wall): 3 n - 2 degrees of freedom.
    if (n < 2) return;
    Vec3 drift{all[1] / all[0], all[2] / all[0], all[3] / all[0]};
    drift[axis_] = 0;  // the flow across the wall is kept
    const double twice_kinetic = all[4] - all[0] * dot(drift, drift);
    const double dof = 3 * n - 2;
    if (!(twice_kinetic > 0)) return;
    const double factor = std::sqrt(temperature_ * dof / twice_kinetic);
    exec::for_each(p.target, p.n_owned,
                   thermostat::RescaleLayer{p.position, p.velocity, {axis_, lo_, hi_}, factor, drift});
    energy_ += 0.5 * (factor * factor * twice_kinetic - all[4]);
}

}  // namespace emergent
