// SPDX-License-Identifier: MIT
// The problem (scene) plugin API and the static registry scenes add themselves to.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "emergent/config.hpp"
#include "emergent/field_grid.hpp"

namespace emergent {

class Simulation;

/// Named values a scene records (a scalar is a vector of one), into /observables/<name>.
using Measures = std::vector<std::pair<std::string, std::vector<double>>>;

/// How many particles a scene will place (spheres of rigid bodies included), and the
/// parameters that set the number ("n_cells=40"), known from the configuration alone.
struct ParticleEstimate {
    double count = -1;   ///< -1: the scene cannot tell before placing them
    std::string set_by;  ///< the parameters to name when the run is too large
};

/// A scene: composes engine parts into one physical system. It holds only what is special to
/// it; integration, neighbour search, decomposition and output belong to the engine.
class Problem {
public:
    virtual ~Problem() = default;
    /// Sets the box, species, force terms, thermostat and rigid-body kinds of `sim`: everything
    /// but the particles and bodies themselves (a continued run gets those from a checkpoint).
    virtual void build(Simulation& sim) = 0;
    /// Adds the initial particles (not called when a run continues from a checkpoint).
    virtual void place_particles(Simulation& sim) = 0;
    /// The particle count place_particles() will reach, asked after build() so that a run too
    /// large for the machine is refused before anything is allocated.
    virtual ParticleEstimate expected_particles(const Simulation& /*sim*/) const { return {}; }
    /// The same from the parameters alone, asked before build(): for a scene whose build()
    /// already holds every particle (a start drawn whole, the box fitted to it), so that a run
    /// too large is refused before build() allocates it. Unknown (-1) by default.
    virtual ParticleEstimate particles_from_parameters() const { return {}; }
    /// Grids the scene coarse-grains on, besides the run's `fields.grid` box grid.
    virtual std::vector<FieldGrid> field_grids(const Simulation& /*sim*/) const { return {}; }
    /// Called once as the measured phase begins (at step equilibration_steps, before its first
    /// sample; not again when a run continues past it): the place to leave what settling left
    /// behind that the measured phase must not inherit, e.g. the net drift a layer picked up
    /// while it landed. Collective.
    virtual void on_equilibrated(Simulation& /*sim*/) {}
    /// A scene's look at the state between samples: observe() is called after every step whose
    /// index is a multiple of observe_every() (0: never), before that step's sample if it has
    /// one. It writes nothing; it is for tallies that need a finer interval than the written
    /// samples (e.g. how clusters grow and shrink), reported by measures() and kept by
    /// saved_state(). Collective.
    virtual long long observe_every() const { return 0; }
    virtual void observe(Simulation& /*sim*/) {}
    /// The scene's own measures at a sample step. Collective: the values must be the same on
    /// every rank. The last ones also go into the run summary.
    virtual Measures measures(Simulation& /*sim*/) { return {}; }
    /// Analysis of a completed interval of one of the scene's field grids (frames are the same
    /// on every rank), recorded at the frame's step. Called only when the run writes output.
    virtual Measures analyse_fields(const FieldGrid& /*grid*/, const FieldFrame& /*frame*/) {
        return {};
    }
    /// Per-body values the scene adds to each trajectory frame of its rigid bodies (e.g. which
    /// cluster a body is in), written as /particles/bodies/<name> and shown in the bodies' XDMF
    /// sidecar: one value per body this rank owns, in the order of sim.bodies(). The same names
    /// at every frame. Collective; called only when the run writes output.
    virtual Measures body_frame_values(Simulation& /*sim*/) { return {}; }
    /// The scene's own running state (accumulated averages, the last frame's tallies) that a
    /// checkpoint keeps, as named arrays; the same on every rank. restore_state() gets them back
    /// on a continued run, after build().
    virtual Measures saved_state() const { return {}; }
    virtual void restore_state(const std::map<std::string, std::vector<double>>& /*state*/) {}
    /// A few words for the run's progress line, from this sample's `measures` and the scene's
    /// own latest analysis; by default the turns or shakes done ("revolutions", "cycles") when
    /// the scene measures them. Called on the printing rank only, so never collective.
    virtual std::string progress_note(const Measures& measures) const;
};

/// Named sets of parameter values, e.g. presets["tiny"]["n_cells"] = "4".
using Presets = std::map<std::string, std::map<std::string, std::string>>;

/// What a scene tells the registry about itself.
struct ProblemInfo {
    std::string name;
    std::string description;
    Schema schema;  ///< engine run parameters plus the scene's own
    Presets presets;
    std::function<std::unique_ptr<Problem>(const Config&)> factory;
};

/// All scenes known to this executable.
class ProblemRegistry {
public:
    static ProblemRegistry& instance();
    bool add(ProblemInfo info);
    const ProblemInfo* find(const std::string& name) const;
    std::vector<const ProblemInfo*> all() const;

private:
    std::map<std::string, ProblemInfo> problems_;
};

/// Parameters every run has (time step, skin, step counts, seed, sampling, rank grid).
Schema run_schema();

/// Resolves a run's parameters, later sources overriding earlier ones: schema defaults, then
/// `base` (a checkpoint's parameters, for a continued run), then the preset, then each INI
/// file, then each `key=value`. Unknown keys and invalid values throw InputError naming the
/// scene, the key and where it was set (file and line).
Config resolve_config(const ProblemInfo& info, const std::string& preset,
                      const std::vector<std::string>& ini_files,
                      const std::vector<std::string>& assignments,
                      const std::map<std::string, std::string>& base = {});

}  // namespace emergent

#define EMERGENT_CONCAT_DETAIL(a, b) a##b
#define EMERGENT_CONCAT(a, b) EMERGENT_CONCAT_DETAIL(a, b)

/// Registers a scene: `info_function` returns its ProblemInfo. Used once, at the end of the
/// scene's .cpp file.
#define EMERGENT_REGISTER_PROBLEM(info_function)                                    \
    static const bool EMERGENT_CONCAT(emergent_registered_, __LINE__) =             \
        ::emergent::ProblemRegistry::instance().add(info_function())
