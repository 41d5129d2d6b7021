// SPDX-License-Identifier: MIT
// Particle snapshots and observables in H5MD 1.1, written collectively by all ranks.
#pragma once

#include <mpi.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "emergent/box.hpp"
#include "emergent/config.hpp"
#include "emergent/particle_store.hpp"
#include "emergent/problem.hpp"
#include "io/time_series.hpp"

namespace emergent::io {

/// What a trajectory file describes: the run's configuration and its box.
struct H5mdMetadata {
    const Config* config = nullptr;
    Box box;
    long long n_global = 0;
    long long n_bodies = 0;  ///< rigid bodies: written as /particles/bodies (with orientation)
    std::vector<std::string> elements;  ///< of: position, velocity, species, id, image
};

/// An H5MD file: /h5md (version, author, creator), /parameters (every resolved parameter,
/// build version and commit, rank count), /particles/all/{box, position, ...} and
/// /observables/<name>. Frames are stored in particle-id order whatever the rank count, since
/// particles are first sent to the rank that writes their id block. Beside it, STEM.xmf (XDMF,
/// rewritten after each frame) shows the particles, and STEM.bodies.xmf the rigid bodies, as a
/// time series of points with their elements as arrays: it points at per-frame views /particles/<group>/frames/<element>/
/// <frame> and at /particles/<group>/connectivity, the form every ParaView XDMF reader opens.
class H5mdWriter {
public:
    H5mdWriter(const std::string& path, MPI_Comm comm, const H5mdMetadata& meta);
    ~H5mdWriter();

    /// Appends one frame of every configured element. Collective.
    void write_particles(const ParticleStore& store, long long step, double time);

    /// Appends one frame of the rigid bodies (centre of mass, velocity, orientation, ...) and
    /// of `extra` per-body values (one per owned body, store order; float64), each named array
    /// becoming an element of its own at its first frame.
    void write_bodies(const ParticleStore& bodies, long long step, double time, const Measures& extra = {});

    /// Appends one value (scalar if size 1, else a vector) to /observables/<name>. Collective:
    /// every rank calls it with the same arguments; rank 0 writes.
    void write_observable(const std::string& name, long long step, double time,
                          const std::vector<double>& value);

    /// Writes everything appended so far to disk, so a run killed later keeps it. Collective.
    void flush();

    /// Marks the file complete (attribute /h5md/emergent_complete = 1) and closes it.
    void finish();

    static const std::vector<std::string>& known_elements();

private:
    void add_group(const std::string& name, const std::string& key, long long n_global,
                   const std::vector<std::string>& elements);
    void write_group(const std::string& key, const ParticleStore& store, long long n_global,
                     const std::vector<std::string>& elements, long long step, double time,
                     const Measures& extra = {});

    void write_sidecar() const;

    /// A particle group as the sidecar shows it.
    struct Shown {
        std::string name;  ///< "all" or "bodies"
        long long n_global = 0;
        std::vector<std::string> elements;
        std::vector<double> times;  ///< of the frames written
    };

    MPI_Comm comm_;
    H5mdMetadata meta_;
    std::string file_name_, sidecar_;  ///< the file's name; its path less the extension
    std::map<std::string, Shown> groups_;
    H5Id file_, particles_, observables_;
    std::map<std::string, std::unique_ptr<TimeSeries>> series_;
};

}  // namespace emergent::io
