// SPDX-License-Identifier: MIT
// A run's state taken and put back: the owned particles and bodies, the list's reference
// positions, the planes between domains and the walls' tallies, so that a continuation repeats
// the uninterrupted run bit for bit (same ranks).
#include <algorithm>
#include <stdexcept>

#include "core/engine.hpp"
#include "decomposition/reductions.hpp"
#include "emergent/error.hpp"

namespace emergent {

namespace {
/// The value kept for `id` in pairs sorted by id, or null.
template <class T>
const T* find_by_id(const std::vector<std::pair<std::int64_t, T>>& sorted, std::int64_t id) {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), id,
                                     [](const auto& entry, std::int64_t key) { return entry.first < key; });
    return it != sorted.end() && it->first == id ? &it->second : nullptr;
}
}  // namespace

StateSnapshot Simulation::snapshot() const {
    StateSnapshot snap;
    snapshot(snap);
    return snap;
}

void Simulation::snapshot(StateSnapshot& snap) const {
    const Engine& e = *engine_;
    // The owned part of each field the restore needs (ghosts are rebuilt). Forces are kept only
    // where they depend on velocities, which restore cannot recompute them from; conservative
    // forces are recomputed. Of the rigid fields spheres need only their body's id. Species and
    // diameters the same for every particle here are left to their fill values (0 and 1).
    const ParticleStore& s = e.store;
    const auto n = static_cast<std::ptrdiff_t>(s.n_owned());
    e.particles.host_reads(kPosition | kVelocity | kId | kImage | kBody | kForce | kSpecies | kDiameter);
    unsigned fields = kPosition | kVelocity | kId | kImage | kBody;
    if (e.ghost_fields & kVelocity) fields |= kForce;
    if (std::any_of(s.species.begin(), s.species.begin() + n, [](int k) { return k != 0; })) fields |= kSpecies;
    if (s.has_diameters() &&
        std::any_of(s.diameter.begin(), s.diameter.begin() + n, [](Real d) { return d != 1; }))
        fields |= kDiameter;
    snap.owned.copy_owned(s, fields);
    if (e.neighbourhood.moved_since_build())
        snap.reference = e.neighbourhood.reference_positions();
    else
        std::vector<Vec3>().swap(snap.reference);
    if (e.bodies()) {
        e.bodies_resident.host_reads(EngineState::kBodyFields);
        snap.bodies = e.rigid.bodies();
    }
    snap.domain_cuts = domain_cuts();
    snap.step = e.step;
    snap.time = e.time;
    snap.rebuilds = e.neighbourhood.rebuilds();
}

void Simulation::restore(const StateSnapshot& snapshot) {
    ParticleStore copy = snapshot.owned;
    const bool saved_forces = !copy.force.empty();
    copy.resize_owned(copy.n_owned());  // the arrays the snapshot left empty, at their fill values
    std::vector<Vec3> reference = snapshot.reference.empty() ? copy.position : snapshot.reference;
    ParticleStore bodies = snapshot.bodies;
    if (!snapshot.domain_cuts.empty()) set_domain_cuts(snapshot.domain_cuts);
    restore(std::move(copy), std::move(reference), snapshot.step, snapshot.time,
            snapshot.rebuilds, engine_->bodies() ? &bodies : nullptr, saved_forces);
}

namespace {
using SavedPoses = std::vector<std::pair<std::int64_t, std::pair<Vec3, Int3>>>;

/// Where each particle was in the saved state on this rank, by id.
class SavedIndex {
public:
    static constexpr std::size_t npos = ~std::size_t{0};
    explicit SavedIndex(const ParticleStore& owned) : by_id_(owned.n_owned()) {
        for (std::size_t i = 0; i < owned.n_owned(); ++i) by_id_[i] = {owned.id[i], i};
        std::sort(by_id_.begin(), by_id_.end());
    }
    /// The saved index of particle `id`, or npos: a body's spheres are placed by the rank that
    /// owns the body, which need not be the rank their saved copies were dealt to.
    std::size_t operator()(std::int64_t id) const {
        const auto it = std::lower_bound(by_id_.begin(), by_id_.end(), std::make_pair(id, std::size_t{0}));
        return it != by_id_.end() && it->first == id ? it->second : npos;
    }
    /// The saved list-reference positions by id (sorted).
    std::vector<std::pair<std::int64_t, Vec3>> by_id(const std::vector<Vec3>& reference) const {
        std::vector<std::pair<std::int64_t, Vec3>> at(by_id_.size());
        for (std::size_t k = 0; k < by_id_.size(); ++k) at[k] = {by_id_[k].first, reference[by_id_[k].second]};
        return at;
    }

private:
    std::vector<std::pair<std::int64_t, std::size_t>> by_id_;
};

/// The saved bodies become the engine's; their poses by id are kept for after the build (which
/// bins their spheres at the saved list references and leaves the bodies on the ranks they were
/// dealt to).
SavedPoses adopt_bodies(EngineState& e, ParticleStore& bodies, ParticleStore& owned) {
    SavedPoses poses;
    for (std::size_t b = 0; b < bodies.n_owned(); ++b)
        poses.push_back({bodies.id[b], {bodies.position[b], bodies.image[b]}});
    std::sort(poses.begin(), poses.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    e.rigid.store() = std::move(bodies);
    e.bodies_resident.host_wrote(EngineState::kBodyFields);
    if (!owned.has_rigid_fields()) owned.enable_rigid_fields();
    // Spheres not dealt with their bodies cannot be indexed: every rank stops with the first.
    const std::string problem = decomp::first_message(e.comm, e.rigid.check_constituents(owned));
    if (!problem.empty()) throw InputError(problem);
    return poses;
}

/// Each body where the saved state had it (unwrapped, with its image), and its spheres placed
/// from that pose: the run's positions, bit for bit.
void place_bodies(EngineState& e, const SavedPoses& poses) {
    ParticleStore &b = e.rigid.store(), &s = e.store;
    const auto& first = e.rigid.constituent_first();
    const auto& index = e.rigid.constituent_index();
    for (std::size_t k = 0; k < b.n_owned(); ++k) {
        if (const auto* pose = find_by_id(poses, b.id[k])) {
            b.position[k] = pose->first;
            b.image[k] = pose->second;
        }
        for (std::uint32_t j = first[k]; j < first[k + 1]; ++j) s.image[index[j]] = b.image[k];
    }
    e.bodies_resident.host_wrote(kPosition | kImage);
    e.rigid.place_at(exec::Target{}, e.rigid.host_arrays(), rigid::ConstituentIndex{first.data(), index.data()},
                     s.position.data(), s.velocity.data());
    e.particles.host_wrote(kPosition | kVelocity | kImage);
}

/// Spheres of bodies were placed afresh by the build; free particles get their positions back.
void put_back_positions(EngineState& e, const SavedIndex& saved, const std::vector<Vec3>& current) {
    ParticleStore& s = e.store;
    for (std::size_t i = 0; i < s.n_owned(); ++i) {
        if (!e.is_free(i)) continue;
        const std::size_t k = saved(s.id[i]);
        if (k == SavedIndex::npos)
            throw std::logic_error("restore: particle id " + std::to_string(s.id[i]) +
                                   " is not in this rank's saved state");
        s.position[i] = current[k];
    }
}

/// Forces that depend on velocities (damping, friction) were computed in the run from the
/// half-step velocities, which a saved state does not hold: the saved forces continue it exactly
/// (the sums for measure() come from the recomputation). A sphere whose saved copy is on another
/// rank (not from a checkpoint, whose reader deals spheres with their bodies) keeps the
/// recomputed force: with friction the continuation would then stray from the uninterrupted run.
void put_back_forces(EngineState& e, const SavedIndex& saved, const std::vector<Vec3>& forces) {
    ParticleStore& s = e.store;
    e.particles.host_reads(kForce | kPosition);
    for (std::size_t i = 0; i < s.n_owned(); ++i) {
        const std::size_t k = saved(s.id[i]);
        if (k != SavedIndex::npos) s.force[i] = forces[k];
    }
    e.particles.host_wrote(kForce);
    if (e.bodies()) {
        e.bodies_resident.host_reads(kPosition);
        e.rigid.sum_forces(exec::Target{}, e.rigid.host_arrays(), s.position.data(), s.force.data());
        e.bodies_resident.host_wrote(kForce | kTorque);
    }
}
}  // namespace

void Simulation::restore(ParticleStore&& owned, std::vector<Vec3>&& reference, long long step,
                         double time, long long rebuilds, ParticleStore* bodies, bool saved_forces) {
    Engine& e = *engine_;
    if (e.bodies() != (bodies != nullptr))
        throw InputError("restore: the saved state and this scene disagree about rigid bodies");
    const SavedPoses poses = bodies ? adopt_bodies(e, *bodies, owned) : SavedPoses{};
    if (reference.size() != owned.n_owned()) throw std::logic_error("restore: size mismatch");
    // The list is rebuilt from the positions it was originally built from, which reorders the
    // particles: their current positions and saved forces are kept by id meanwhile.
    const SavedIndex saved(owned);
    std::vector<Vec3> current = owned.position, forces = std::move(owned.force);
    owned.force.assign(current.size(), Vec3{0, 0, 0});  // every array whole: the build permutes all
    owned.position.assign(reference.begin(), reference.end());
    owned.position.resize(current.size());
    e.store = std::move(owned);
    e.particles.host_wrote(kAllFields);  // what lived on the back end belongs to the state left behind
    e.prepare();
    e.place_body_frames();
    if (bodies) e.neighbourhood.restore_bodies_at(saved.by_id(reference));
    e.neighbourhood.rebuild();
    if (bodies) place_bodies(e, poses);
    put_back_positions(e, saved, current);
    e.neighbourhood.gather_on_host();
    e.particles.host_wrote(kPosition | kVelocity);
    e.step = step;
    e.time = time;
    e.neighbourhood.set_rebuilds(rebuilds);
    e.count_bodies();
    e.forces.compute(true, e.time);
    if (saved_forces) put_back_forces(e, saved, forces);
}

void Simulation::restore_exchange_tallies(const std::vector<double>& t) {
    Engine& e = *engine_;
    if (t.size() != 6 * e.boundaries.size() + e.motion.wall_layers.size())
        throw InputError("checkpoint: exchange tallies of " + std::to_string(t.size()) +
                         " values do not fit this scene's walls");
    const bool keep = rank() == 0;
    std::size_t k = 0;
    for (auto& rule : e.boundaries) {
        WallExchange x;
        if (keep)
            x.hits = static_cast<long long>(t[k]), x.momentum = {t[k + 1], t[k + 2], t[k + 3]},
            x.angular_momentum = t[k + 4], x.energy = t[k + 5];
        rule->set_exchange(x);
        k += 6;
    }
    for (auto& layer : e.motion.wall_layers) layer->set_energy(t[k++]);
}

}  // namespace emergent
