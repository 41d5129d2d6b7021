// SPDX-License-Identifier: MIT
// A periodic pair system that lives on one GPU: the engine's velocity-Verlet and pair functors
// launched as kernels, a cell-sorted full neighbour list rebuilt on a skin criterion decided
// on the device, particle data reordered along a Z-order curve at every build.
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "emergent/gpu.hpp"
#include "emergent/error.hpp"
#include "emergent/execution.hpp"
#include "emergent/cuda_launch.cuh"
#include "force/lennard_jones.hpp"
#include "force/pair_full_list.hpp"
#include "gpu/build_list_split.cuh"
#include "gpu/device_buffer.cuh"
#include "gpu/device_cells.hpp"
#include "integrate/kick_drift.hpp"

namespace emergent::gpu {

namespace {

template <class T>
void upload(DeviceBuffer<T>& to, const std::vector<T>& from, cudaStream_t s) {
    to.resize(from.size());
    EMERGENT_CUDA_CHECK(cudaMemcpyAsync(to.data(), from.data(), from.size() * sizeof(T),
                                        cudaMemcpyHostToDevice, s));
}

template <class T>
std::vector<T> download(const DeviceBuffer<T>& from, cudaStream_t s) {
    std::vector<T> out(from.size());
    EMERGENT_CUDA_CHECK(cudaMemcpyAsync(out.data(), from.data(), from.bytes(), cudaMemcpyDeviceToHost, s));
    EMERGENT_CUDA_CHECK(cudaStreamSynchronize(s));
    return out;
}

/// Times parts of a step with CUDA events when profiling is on; free otherwise.
class PartTimer {
  public:
    PartTimer(bool on, cudaStream_t s, double& total) : on_(on), s_(s), total_(total) {
        if (!on_) return;
        EMERGENT_CUDA_CHECK(cudaEventCreate(&a_));
        EMERGENT_CUDA_CHECK(cudaEventCreate(&b_));
        EMERGENT_CUDA_CHECK(cudaEventRecord(a_, s_));
    }
    ~PartTimer() {
        if (!on_) return;
        float ms = 0;
        if (cudaEventRecord(b_, s_) == cudaSuccess && cudaEventSynchronize(b_) == cudaSuccess &&
            cudaEventElapsedTime(&ms, a_, b_) == cudaSuccess)
            total_ += ms;
        cudaEventDestroy(a_);
        cudaEventDestroy(b_);
    }

  private:
    bool on_;
    cudaStream_t s_;
    double& total_;
    cudaEvent_t a_{}, b_{};
};

std::string compact(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

}  // namespace

struct PeriodicPairSystem::Impl {
    PairSystemSpec spec;
    std::size_t n = 0;
    CellGrid grid;
    force::MinimumImage image;
    force::LennardJones lj;
    double list_cutoff = 0;
    cudaStream_t stream = nullptr;
    exec::Cuda on_device;

    DeviceBuffer<Vec3> x, v, f, x_build, x_spare, v_spare;
    DeviceBuffer<Int3> img, img_spare;
    DeviceBuffer<std::uint32_t> id, id_spare;
    DeviceBuffer<int> species, species_spare;
    DeviceBuffer<Real> inverse_mass, mass;
    DeviceBuffer<std::uint32_t> key, key_sorted, order, order_sorted;
    DeviceBuffer<std::uint32_t> cell_start, cell_end;
    DeviceBuffer<std::uint32_t> nb_count, nb_index;
    DeviceBuffer<Real> per_particle_a, per_particle_b;
    DeviceBuffer<Real> sums;
    DeviceBuffer<std::uint32_t> count_stats;
    DeviceBuffer<unsigned char> sort_scratch, reduce_scratch;
    DeviceBuffer<int> flag;
    std::unique_ptr<PinnedValue<int>> flag_host;  // made after the device is chosen
    cudaEvent_t flag_ready = nullptr;

    std::uint32_t capacity = 0;
    int multiprocessors = 1;
    long steps_done = 0;
    std::unique_ptr<Thermostat> thermostat;
    int thermostat_interval = 1;
    ListStats stats;
    bool profiling = false;
    StepProfile prof;

    Impl(const PairSystemSpec& s, const std::vector<Vec3>& x0, const std::vector<Vec3>& v0)
        : spec(s), n(x0.size()), lj(force::LennardJones::Params{s.epsilon, s.sigma, s.cutoff}) {
        if (v0.size() != n) throw std::invalid_argument("positions and velocities differ in number");
        if (n == 0 || n >= (std::size_t(1) << 31))
            throw std::invalid_argument("particle count " + std::to_string(n) + " outside 1 .. 2^31");
        if (!(s.skin > 0) || !(s.dt > 0) || !(s.mass > 0) || !(s.cutoff > 0))
            throw std::invalid_argument("skin, dt, mass and cutoff must be > 0");
        list_cutoff = s.cutoff + s.skin;
        for (int d = 0; d < 3; ++d) {
            const int cells = std::min(1024, static_cast<int>(std::floor(s.box[d] / list_cutoff)));
            if (cells < 3)
                throw std::invalid_argument("box side " + std::to_string(s.box[d]) +
                                            " must be at least 3 x (cutoff + skin) = " +
                                            std::to_string(3 * list_cutoff));
            grid.n[d] = cells;
            grid.inverse_width[d] = cells / s.box[d];
            image.length[d] = s.box[d];
            image.inverse[d] = 1 / s.box[d];
        }
        multiprocessors = select_device().multiprocessors;
        if (s.lanes_per_particle != 0 && (s.lanes_per_particle < 1 || s.lanes_per_particle > 32 ||
                                          (s.lanes_per_particle & (s.lanes_per_particle - 1)) != 0))
            throw std::invalid_argument("lanes_per_particle=" + std::to_string(s.lanes_per_particle) +
                                        " must be 0 (automatic) or a power of 2 up to 32");
        flag_host = std::make_unique<PinnedValue<int>>();
        EMERGENT_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
        EMERGENT_CUDA_CHECK(cudaEventCreateWithFlags(&flag_ready, cudaEventDisableTiming));
        on_device.stream = stream;
        if (s.block_size < 32 || s.block_size > 1024 || s.block_size % 32 != 0)
            throw std::invalid_argument("block_size=" + std::to_string(s.block_size) +
                                        " must be a multiple of 32 in 32 .. 1024");
        on_device.block_size = s.block_size;

        upload(x, x0, stream);
        upload(v, v0, stream);
        std::vector<std::uint32_t> ids(n);
        for (std::size_t i = 0; i < n; ++i) ids[i] = static_cast<std::uint32_t>(i);
        upload(id, ids, stream);
        upload(species, std::vector<int>(n, 0), stream);
        upload(img, std::vector<Int3>(n, Int3{0, 0, 0}), stream);
        upload(inverse_mass, std::vector<Real>{1 / s.mass}, stream);
        upload(mass, std::vector<Real>{s.mass}, stream);
        for (auto* b : {&f, &x_build, &x_spare, &v_spare}) b->resize(n);
        img_spare.resize(n);
        id_spare.resize(n);
        species_spare.resize(n);
        for (auto* b : {&key, &key_sorted, &order, &order_sorted, &nb_count}) b->resize(n);
        cell_start.resize(grid.cells());
        cell_end.resize(grid.cells());
        per_particle_a.resize(n);
        per_particle_b.resize(n);
        sums.resize(2);
        count_stats.resize(1);
        flag.resize(1);
        reserve_scratch();

        rebuild();
        force(false);
        with_rebuild_check(rebuild_check());
        EMERGENT_CUDA_CHECK(cudaStreamSynchronize(stream));
    }

    ~Impl() {
        if (flag_ready) cudaEventDestroy(flag_ready);
        if (stream) cudaStreamDestroy(stream);
    }

    void reserve_scratch() {
        std::size_t sort_bytes = 0, sum_bytes = 0, max_bytes = 0;
        EMERGENT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, sort_bytes, key.data(), key_sorted.data(),
                                                            order.data(), order_sorted.data(),
                                                            static_cast<int>(n), 0, 30, stream));
        EMERGENT_CUDA_CHECK(cub::DeviceReduce::Sum(nullptr, sum_bytes, per_particle_a.data(), sums.data(),
                                                   static_cast<int>(n), stream));
        EMERGENT_CUDA_CHECK(cub::DeviceReduce::Max(nullptr, max_bytes, nb_count.data(), count_stats.data(),
                                                   static_cast<int>(n), stream));
        sort_scratch.resize(sort_bytes);
        reduce_scratch.resize(std::max(sum_bytes, max_bytes));
    }

    /// Wrap, sort by cell along the Z curve, reorder every per-particle array, find the cell
    /// ranges and build the full list (growing it until every neighbour fits).
    void rebuild() {
        const int ni = static_cast<int>(n);
        exec::for_each(on_device, n, WrapIntoBox{x.data(), img.data(), spec.box});
        exec::for_each(on_device, n, CellKey{x.data(), grid, key.data(), order.data()});
        std::size_t bytes = sort_scratch.size();
        EMERGENT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(sort_scratch.data(), bytes, key.data(),
                                                            key_sorted.data(), order.data(), order_sorted.data(),
                                                            ni, 0, grid.key_bits(), stream));
        const std::uint32_t* o = order_sorted.data();
        exec::for_each(on_device, n, Gather<Vec3>{x.data(), x_spare.data(), o});
        exec::for_each(on_device, n, Gather<Vec3>{v.data(), v_spare.data(), o});
        exec::for_each(on_device, n, Gather<Int3>{img.data(), img_spare.data(), o});
        exec::for_each(on_device, n, Gather<std::uint32_t>{id.data(), id_spare.data(), o});
        exec::for_each(on_device, n, Gather<int>{species.data(), species_spare.data(), o});
        x.swap(x_spare);
        v.swap(v_spare);
        img.swap(img_spare);
        id.swap(id_spare);
        species.swap(species_spare);

        EMERGENT_CUDA_CHECK(cudaMemsetAsync(cell_start.data(), 0, cell_start.bytes(), stream));
        EMERGENT_CUDA_CHECK(cudaMemsetAsync(cell_end.data(), 0, cell_end.bytes(), stream));
        exec::for_each(on_device, n, CellRanges{x.data(), key_sorted.data(), n, grid, cell_start.data(),
                                                cell_end.data()});
        // Candidates per particle: the particles of 27 cells.
        const int build_lanes = spec.lanes_per_particle > 0
                                    ? spec.lanes_per_particle
                                    : lanes_for(n, 27.0 * double(n) / double(grid.cells()), multiprocessors);
        for (;;) {
            build_list_split(on_device, n, build_lanes,
                             BuildFullList{x.data(), grid, cell_start.data(), cell_end.data(), image,
                                           list_cutoff * list_cutoff, capacity, n, nb_count.data(),
                                           capacity > 0 ? nb_index.data() : nullptr});
            std::size_t rb = reduce_scratch.size();
            EMERGENT_CUDA_CHECK(cub::DeviceReduce::Max(reduce_scratch.data(), rb, nb_count.data(),
                                                       count_stats.data(), ni, stream));
            // The total in double: N x neighbours passes 2^32 at ~45 million LJ atoms.
            exec::for_each(on_device, n, Widen<std::uint32_t>{nb_count.data(), per_particle_a.data()});
            rb = reduce_scratch.size();
            EMERGENT_CUDA_CHECK(cub::DeviceReduce::Sum(reduce_scratch.data(), rb, per_particle_a.data(),
                                                       sums.data(), ni, stream));
            std::uint32_t host[1];
            double total = 0;
            EMERGENT_CUDA_CHECK(cudaMemcpyAsync(host, count_stats.data(), sizeof host, cudaMemcpyDeviceToHost, stream));
            EMERGENT_CUDA_CHECK(cudaMemcpyAsync(&total, sums.data(), sizeof total, cudaMemcpyDeviceToHost, stream));
            EMERGENT_CUDA_CHECK(cudaStreamSynchronize(stream));
            stats.mean_neighbours = total / double(n);
            if (host[0] <= capacity && capacity > 0) break;
            // Room for density fluctuations until the next build, in whole warps' worth of slots.
            capacity = ((host[0] + host[0] / 8 + 8) + 31) / 32 * 32;
            nb_index.resize(std::size_t(capacity) * n);
        }
        stats.capacity = capacity;
        stats.lanes = spec.lanes_per_particle > 0
                          ? spec.lanes_per_particle
                          : lanes_for(n, stats.mean_neighbours, multiprocessors);
        ++stats.builds;
        EMERGENT_CUDA_CHECK(cudaMemcpyAsync(x_build.data(), x.data(), x.bytes(), cudaMemcpyDeviceToDevice, stream));
    }

    template <class Evaluator, bool Sample>
    void pair_forces(const Evaluator& eval) {
        force::PairForceFullList<Evaluator, force::StridedNeighbours, force::MinimumImage, Sample> pf{
            x.data(), f.data(), {nb_count.data(), nb_index.data(), n}, eval, image};
        if constexpr (Sample) {
            pf.energy = per_particle_a.data();
            pf.virial = per_particle_b.data();
        }
        exec::for_each_split(on_device, n, stats.lanes, pf);
    }

    void force(bool sample) {
        if (spec.precision == Precision::Double) {
            if (sample) pair_forces<force::LennardJones, true>(lj);
            else pair_forces<force::LennardJones, false>(lj);
        } else {
            const auto lj32 = lj.as<float>();
            if (sample) pair_forces<force::LennardJonesT<float>, true>(lj32);
            else pair_forces<force::LennardJonesT<float>, false>(lj32);
        }
    }

    PredictedDisplacementExceeds rebuild_check() {
        // (skin/2)^2, lowered by 1 %: the prediction repeats the drift's arithmetic, but the
        // compiler may contract it differently; rebuilding a little early is always safe.
        const Real limit_sq = 0.99 * 0.25 * spec.skin * spec.skin;
        return {x.data(), v.data(), f.data(), species.data(), inverse_mass.data(), x_build.data(), spec.dt,
                limit_sq, spec.max_force > 0 ? spec.max_force * spec.max_force : HUGE_VAL, flag.data()};
    }

    /// Runs `pass` (which sets the flag when the next step must rebuild) and sends the flag to
    /// the host, where the next step reads it.
    template <class Pass>
    void with_rebuild_check(const Pass& pass) {
        EMERGENT_CUDA_CHECK(cudaMemsetAsync(flag.data(), 0, sizeof(int), stream));
        exec::for_each(on_device, n, pass);
        EMERGENT_CUDA_CHECK(cudaMemcpyAsync(flag_host->get(), flag.data(), sizeof(int), cudaMemcpyDeviceToHost, stream));
        EMERGENT_CUDA_CHECK(cudaEventRecord(flag_ready, stream));
    }

    void step() {
        {
            PartTimer t(profiling, stream, prof.kick_drift);
            exec::for_each(on_device, n,
                           integrate::KickDrift{x.data(), v.data(), f.data(), species.data(),
                                                inverse_mass.data(), 0.5 * spec.dt, spec.dt});
        }
        // The device decided at the end of the last step; the drift above runs meanwhile.
        EMERGENT_CUDA_CHECK(cudaEventSynchronize(flag_ready));
        const int found = flag_host->value();
        if (found & kNotFinite)
            throw InstabilityError("run stopped: a position, velocity or force on the GPU became "
                                   "non-finite after step " + std::to_string(steps_done) +
                                   " (the run went unstable: reduce dt or check the initial state)");
        if (found & kForceBound)
            throw InstabilityError("run stopped: a force on the GPU exceeds max_force=" +
                                   compact(spec.max_force) + " after step " + std::to_string(steps_done) +
                                   " (overlapping particles, or the run went unstable: reduce dt)");
        if (found & kRebuildNext) {
            PartTimer t(profiling, stream, prof.rebuild);
            rebuild();
        }
        {
            PartTimer t(profiling, stream, prof.force);
            force(false);
        }
        {
            // The second kick and the rebuild check in one pass over the particles.
            PartTimer t(profiling, stream, prof.kick);
            with_rebuild_check(exec::Then<integrate::Kick, PredictedDisplacementExceeds>{
                {v.data(), f.data(), species.data(), inverse_mass.data(), 0.5 * spec.dt}, rebuild_check()});
        }
        if (thermostat && (steps_done + 1) % thermostat_interval == 0) {
            // As the CPU engine: after the second kick, keyed by the index of the step before
            // it is counted.
            PartTimer t(profiling, stream, prof.kick);
            const double dof = 3.0 * double(n) - 3.0;  // total momentum is conserved
            rescale(thermostat->scale_factor(kinetic(), dof, steps_done, spec.dt * thermostat_interval));
        }
        ++steps_done;
        if (profiling) ++prof.steps;
    }

    /// v *= factor, then the rebuild check again: it ran on the velocities before.
    void rescale(double factor) {
        exec::for_each(on_device, n, integrate::ScaleVelocity{v.data(), factor});
        with_rebuild_check(rebuild_check());
    }

    double kinetic() {
        exec::for_each(on_device, n, KineticEnergy{v.data(), species.data(), mass.data(), per_particle_a.data()});
        return sum(per_particle_a);
    }

    double sum(const DeviceBuffer<Real>& a) {
        std::size_t rb = reduce_scratch.size();
        EMERGENT_CUDA_CHECK(cub::DeviceReduce::Sum(reduce_scratch.data(), rb, a.data(), sums.data(),
                                                   static_cast<int>(n), stream));
        Real host = 0;
        EMERGENT_CUDA_CHECK(cudaMemcpyAsync(&host, sums.data(), sizeof host, cudaMemcpyDeviceToHost, stream));
        EMERGENT_CUDA_CHECK(cudaStreamSynchronize(stream));
        return host;
    }
};

PeriodicPairSystem::PeriodicPairSystem(const PairSystemSpec& spec, const std::vector<Vec3>& x,
                                       const std::vector<Vec3>& v)
    : impl_(std::make_unique<Impl>(spec, x, v)) {}
PeriodicPairSystem::~PeriodicPairSystem() = default;

void PeriodicPairSystem::run(long steps) {
    for (long s = 0; s < steps; ++s) impl_->step();
    EMERGENT_CUDA_CHECK(cudaStreamSynchronize(impl_->stream));
}

Thermo PeriodicPairSystem::thermo() {
    Impl& m = *impl_;
    Thermo t;
    m.force(true);  // same forces as the step's; energy and virial beside them
    t.potential = m.sum(m.per_particle_a);
    t.virial = m.sum(m.per_particle_b);
    t.kinetic = m.kinetic();
    return t;
}

void PeriodicPairSystem::scale_velocities(double factor) {
    impl_->rescale(factor);
    EMERGENT_CUDA_CHECK(cudaStreamSynchronize(impl_->stream));
}

void PeriodicPairSystem::set_thermostat(std::unique_ptr<Thermostat> thermostat, int interval) {
    if (interval < 1) throw std::invalid_argument("thermostat interval must be >= 1");
    impl_->thermostat = std::move(thermostat);
    impl_->thermostat_interval = interval;
}

std::vector<Vec3> PeriodicPairSystem::positions() const {
    const auto x = download(impl_->x, impl_->stream);
    const auto img = download(impl_->img, impl_->stream);
    const auto id = download(impl_->id, impl_->stream);
    std::vector<Vec3> out(x.size());
    const Vec3 L = impl_->spec.box;
    for (std::size_t i = 0; i < x.size(); ++i)
        out[id[i]] = {x[i].x + img[i].x * L.x, x[i].y + img[i].y * L.y, x[i].z + img[i].z * L.z};
    return out;
}

std::vector<Vec3> PeriodicPairSystem::velocities() const {
    const auto v = download(impl_->v, impl_->stream);
    const auto id = download(impl_->id, impl_->stream);
    std::vector<Vec3> out(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) out[id[i]] = v[i];
    return out;
}

std::size_t PeriodicPairSystem::size() const { return impl_->n; }
ListStats PeriodicPairSystem::list_stats() const { return impl_->stats; }

std::size_t PeriodicPairSystem::device_bytes() const {
    const Impl& m = *impl_;
    std::size_t b = 0;
    for (const auto* a : {&m.x, &m.v, &m.f, &m.x_build, &m.x_spare, &m.v_spare}) b += a->bytes();
    b += m.img.bytes() + m.img_spare.bytes() + m.id.bytes() + m.id_spare.bytes();
    b += m.species.bytes() + m.species_spare.bytes() + m.inverse_mass.bytes() + m.mass.bytes();
    for (const auto* a : {&m.key, &m.key_sorted, &m.order, &m.order_sorted, &m.cell_start, &m.cell_end,
                          &m.nb_count, &m.nb_index, &m.count_stats})
        b += a->bytes();
    b += m.per_particle_a.bytes() + m.per_particle_b.bytes() + m.sums.bytes();
    b += m.sort_scratch.bytes() + m.reduce_scratch.bytes() + m.flag.bytes();
    return b;
}

void PeriodicPairSystem::set_profiling(bool on) {
    impl_->profiling = on;
    impl_->prof = StepProfile{};
}
StepProfile PeriodicPairSystem::profile() const { return impl_->prof; }

}  // namespace emergent::gpu
