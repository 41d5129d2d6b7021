// SPDX-License-Identifier: MIT
// Out-of-tree scenes: a shared library that `emergent --plugin path.so` loads.
//
//   // my_scene.cpp, built as a shared library against these headers:
//   #include "emergent/plugin.hpp"
//   emergent::ProblemInfo my_scene_info() { ... }
//   EMERGENT_PLUGIN(my_scene_info)
//
// The library's undefined symbols resolve against the emergent executable, which exports the
// whole engine API. The ABI string is checked on load: a plugin built against other headers is
// refused with a clear error instead of crashing.
#pragma once

#include "emergent/problem.hpp"
#include "emergent/simulation.hpp"

/// Changes whenever the public headers change (tests/plugin/interface_digest.cmake enforces it).
#define EMERGENT_PLUGIN_ABI "emergent-plugin-33"  // 33: SiteBondRule::contact_range, BondCensus::contacts; 32: ParticleStore::reserve; 31: Problem::particles_from_parameters; 30: BlockAverage public (emergent/block_average.hpp); 29: ParamSpec::earlier_value, Schema::earlier_value; 28: ClusterEvents split, pieces, merged, assembled; 27: SiteDepths, Capsomer::site_depths, cage_frame, cage_rotations, closed_cage, PhaseTimes::collective_wait_after_build; 26: exec::Then returns its second functor's result, PhaseTimes::collective_wait, ForceContext::replace_forces, ForceTerm::stores_on_backend, BondCensus::closed_cluster_sizes; 25: exec::check_launch names the functor, the device profile, ParticleStore deferred resize, RunSettings::interior_order (24: Problem::observe_every/observe; 23: ForceTerm::pair_ranges; 22: ph_capsomer;
                                                 //    21: with Capsomer::shape;
                                                 //    19: load balance (RunSettings::balance,
                                                 //    Simulation::domain_cuts); 18: Problem::body_frame_values
                                                 //    for ::separate, cuda_launch.cuh and
                                                 //    cuda_algorithms.cuh public (10:
                                                 //    BackendParticles::overlap (9:
                                                 //    BackendParticles, ForceTerm::on_backend
                                                 //    and add_forces_on_backend, ListLayout,
                                                 //    exec::ElementOf, BackendParticles for
                                                 //    boundary rules and wall layers (8: Backend,
                                                 //    RunSettings::backend, Simulation::backend;
                                                 //    4-7: the execution layer; 3:
                                                 //    Problem::expected_particles, ParamSpec::restart,
                                                 //    ForceTerm::particle_fields)))

#define EMERGENT_PLUGIN(info_function)                                               \
    extern "C" const char* emergent_plugin_abi() { return EMERGENT_PLUGIN_ABI; }     \
    extern "C" void emergent_plugin_init(::emergent::ProblemRegistry& registry) {    \
        registry.add(info_function());                                               \
    }

namespace emergent {

/// Loads a plugin and registers its scenes; InputError naming the file on any failure.
void load_plugin(const std::string& path);

}  // namespace emergent
