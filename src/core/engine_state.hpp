// SPDX-License-Identifier: MIT
// What the parts of the engine share: the run's settings and box, the rank grid, the particles
// and the rigid bodies where the loops find them, the species' masses, the clock. The parts
// (Neighbourhood, ForceEvaluation, Integration) each hold a reference to it and own the rest.
#pragma once
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "decomposition/rank_grid.hpp"
#include "emergent/execution.hpp"
#include "emergent/simulation.hpp"
#include "integrate/particle_sums.hpp"
#include "particles/resident.hpp"
#include "rigid/rigid_bodies.hpp"

namespace emergent {

/// Adds the seconds since construction to `slot` when it goes out of scope.
class PhaseTimer {
public:
    /// Adds the time to `slot`, and to `*also` where given.
    explicit PhaseTimer(double& slot, double* also = nullptr)
        : slot_(slot), also_(also), start_(std::chrono::steady_clock::now()) {}
    ~PhaseTimer() {
        const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        slot_ += t;
        if (also_) *also_ += t;
    }
    PhaseTimer(const PhaseTimer&) = delete;
    PhaseTimer& operator=(const PhaseTimer&) = delete;

private:
    double& slot_;
    double* also_;
    std::chrono::steady_clock::time_point start_;
};

/// The ledger's counts since `before` (exec::Transfers: scalars are read-backs).
inline StepWork work_since(const exec::Transfers& before) {
    const exec::Transfers& now = exec::transfers();
    StepWork w;
    w.passes = now.passes - before.passes;
    w.read_backs = now.scalars - before.scalars;
    w.collectives = now.collectives - before.collectives;
    w.arrays = now.arrays - before.arrays;
    w.array_bytes = now.array_bytes - before.array_bytes;
    return w;
}
/// Each count of `most` at least that of `w`.
inline void keep_most(StepWork& most, const StepWork& w) {
    most.passes = std::max(most.passes, w.passes);
    most.read_backs = std::max(most.read_backs, w.read_backs);
    most.collectives = std::max(most.collectives, w.collectives);
    most.arrays = std::max(most.arrays, w.arrays);
    most.array_bytes = std::max(most.array_bytes, w.array_bytes);
}

struct EngineState {
    EngineState() = default;
    // The residents point into this object.
    EngineState(const EngineState&) = delete;
    EngineState& operator=(const EngineState&) = delete;

    MPI_Comm comm = MPI_COMM_WORLD;
    RunSettings settings;
    Box box;
    std::unique_ptr<decomp::RankGrid> grid;
    /// Where the loops run (exec::Target): the host's loops, or CUDA kernels.
    exec::Target target;
    PhaseTimes times;
    /// A list build happened and no global sum has waited since: the next one's wait also goes
    /// to times.collective_wait_after_build (the ranks that built slower hold it up).
    bool sum_after_build_pending = false;
    double* after_build_slot() {
        if (!sum_after_build_pending) return nullptr;
        sum_after_build_pending = false;
        return &times.collective_wait_after_build;
    }
    StepLedger ledger;
    long long n_global = 0, n_free = 0, n_bodies = 0, step = 0;
    double time = 0;
    std::vector<double> mass{1.0}, inverse_mass{1.0};
    /// What the force terms read of ghosts and of owned particles.
    unsigned ghost_fields = kPosition;
    unsigned particle_fields = kPosition;
    std::vector<std::unique_ptr<BoundaryRule>> boundaries;
    std::string boundary_fault;  ///< first particle a rule could not return, since last check

    ParticleStore store;
    Resident particles{store};
    rigid::RigidBodies rigid;
    Resident bodies_resident{rigid.store()};

    // The bodies' fields, like the particles': where the step's loops over bodies read and
    // write them. A body's kBody is the id of its first sphere (RigidBodies' append).
    static constexpr unsigned kBodyFields = kPosition | kVelocity | kForce | kSpecies | kId | kImage |
                                            kBody | kOrientation | kAngularMomentum | kTorque;
    /// The kinds' frames and the constituent index where the back end reads them.
    rigid::FrameTable frames_on_backend{};
    rigid::ConstituentIndex constituents_on_backend{};
    const int* frame_species_on_backend = nullptr;
    const double* frame_diameters_on_backend = nullptr;

    // The particle mirror's tables, uploads and scratch buffers, and the body mirror's uploads
    // (each part of the engine uses its own slots).
    enum Table : std::size_t { kMassTable, kInverseMassTable, kPairRangeTable };
    enum Upload : std::size_t { kListOffsets, kListIndex, kHaloIndex, kReference };
    // kHaloPack and the two after it: BackendHalo::gather's.
    enum Scratch : std::size_t { kEnergy, kVirial, kOverlap, kHaloPack, kFieldKeys = kHaloPack + 3,
                                 kFieldMembers, kFieldStart, kFieldSums };
    enum BodyUpload : std::size_t { kFrameInertia, kFrameFirst, kFramePositions, kConstituentFirst,
                                    kConstituentIndex, kFrameSpecies, kFrameDiameters };

    exec::ParticleMirror* mirror() const { return particles.mirror(); }
    /// The array of `field` the back end's loops work on.
    template <class T>
    T* data(FieldMask field, const std::vector<T>& host) const {
        return particles.data(field, host);
    }
    /// Per-species masses where the back end's loops read them.
    const double* masses() const { return particles.table(kMassTable, mass); }
    const double* inverse_masses() const { return particles.table(kInverseMassTable, inverse_mass); }

    bool bodies() const { return !rigid.empty_everywhere(); }
    bool is_free(std::size_t i) const { return !store.has_rigid_fields() || store.body[i] < 0; }
    /// The bodies' arrays where the loops run, holding the current values of `fields`.
    rigid::RigidBodies::Arrays body_arrays(unsigned fields) const;
    /// The kinds' frames where the back end reads them (once: they are fixed by initialise).
    void place_body_frames();
    /// The constituent index where the back end reads it (after each build).
    void place_constituents();
    /// Constituents of a body owned here may stick out of the domain by the body's extent.
    double ghost_width(double list_cutoff) const { return list_cutoff + rigid.max_extent(); }

    /// A free particle's kinetic energy, on the back end's arrays.
    integrate::FreeKineticEnergy kinetic_energy() const;
    /// Kinetic energy of free particles and bodies (spheres of bodies count through them).
    double local_kinetic() const;
    double dof() const;
    /// Counts free particles and bodies over the ranks. Collective.
    void count_bodies();
    /// Stops every rank together if some boundary rule could not keep a particle inside.
    void agree_on_boundary_faults();
    void require_grid(const char* what) const {
        if (!grid) throw std::logic_error(std::string(what) + ": set_box first");
    }
};

}  // namespace emergent
