// SPDX-License-Identifier: MIT
// The GPU entry points of a build without the CUDA back end: present nowhere, refused clearly.
#include <stdexcept>

#include "emergent/gpu.hpp"
#include "execution/array_memory.hpp"

namespace emergent::gpu {

namespace {
[[noreturn]] void refuse() {
    throw std::runtime_error("execution on the GPU was requested but emergent was built without "
                             "the CUDA back end (configure with -DEMERGENT_CUDA=ON)");
}
}  // namespace

bool device_present() { return false; }
DeviceInfo select_device() { refuse(); }
std::size_t device_memory_in_use() { refuse(); }
int lanes_for(std::size_t, double, int) { refuse(); }
double copy_bandwidth(std::size_t, int) { refuse(); }

struct PeriodicPairSystem::Impl {};
PeriodicPairSystem::PeriodicPairSystem(const PairSystemSpec&, const std::vector<Vec3>&,
                                       const std::vector<Vec3>&) {
    refuse();
}
PeriodicPairSystem::~PeriodicPairSystem() = default;
void PeriodicPairSystem::run(long) { refuse(); }
Thermo PeriodicPairSystem::thermo() { refuse(); }
void PeriodicPairSystem::scale_velocities(double) { refuse(); }
void PeriodicPairSystem::set_thermostat(std::unique_ptr<Thermostat>, int) { refuse(); }
std::vector<Vec3> PeriodicPairSystem::positions() const { refuse(); }
std::vector<Vec3> PeriodicPairSystem::velocities() const { refuse(); }
std::size_t PeriodicPairSystem::size() const { refuse(); }
ListStats PeriodicPairSystem::list_stats() const { refuse(); }
std::size_t PeriodicPairSystem::device_bytes() const { refuse(); }
void PeriodicPairSystem::set_profiling(bool) { refuse(); }
StepProfile PeriodicPairSystem::profile() const { refuse(); }

}  // namespace emergent::gpu

namespace emergent::exec {
std::unique_ptr<ArrayMemory> cuda_device_memory() { gpu::refuse(); }
}  // namespace emergent::exec
