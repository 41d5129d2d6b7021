// SPDX-License-Identifier: MIT
// GPU throughput of a periodic Lennard-Jones (or WCA) fluid: steps/s and atom-steps/s as the
// median of repeated timed runs, device memory per atom, neighbours per atom, and with
// --profile the device time per part of a step with the bytes each part must move.
//   emergent-gpu-bench --cells 63 --density 0.8 --cutoff 1.122462 --skin 0.3 --steps 2000
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "emergent/gpu.hpp"
#include "gpu_bench_support.hpp"
#include "support/fluid_start.hpp"

using namespace emergent;

namespace {

struct Options {
    int cells = 20;
    double density = 0.8, cutoff = 1.122462048309373, skin = 0.3, temperature = 1.0, dt = 0.005;
    long steps = 2000, warmup = 2000;
    int repeats = 5, block = 256, lanes = 0;
    gpu::Precision precision = gpu::Precision::Double;
    bool profile = false;
};

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument("option " + a + " needs a value");
            return argv[++i];
        };
        if (a == "--cells") o.cells = bench::number<int>(a, value());
        else if (a == "--density") o.density = bench::number<double>(a, value());
        else if (a == "--cutoff") o.cutoff = bench::number<double>(a, value());
        else if (a == "--skin") o.skin = bench::number<double>(a, value());
        else if (a == "--temperature") o.temperature = bench::number<double>(a, value());
        else if (a == "--dt") o.dt = bench::number<double>(a, value());
        else if (a == "--steps") o.steps = bench::number<long>(a, value());
        else if (a == "--warmup") o.warmup = bench::number<long>(a, value());
        else if (a == "--repeats") o.repeats = bench::number<int>(a, value());
        else if (a == "--block") o.block = bench::number<int>(a, value());
        else if (a == "--lanes") o.lanes = bench::number<int>(a, value());
        else if (a == "--profile") o.profile = true;
        else if (a == "--precision") {
            const std::string p = value();
            if (p == "double") o.precision = gpu::Precision::Double;
            else if (p == "mixed") o.precision = gpu::Precision::Mixed;
            else throw std::invalid_argument("precision=" + p + " must be one of: double, mixed");
        } else throw std::invalid_argument("unknown option '" + a + "'");
    }
    return o;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) try {
    const Options o = parse(argc, argv);
    const gpu::DeviceInfo dev = gpu::select_device();
    const std::size_t before = gpu::device_memory_in_use();
    const auto start = fixtures::fcc_fluid(o.cells, o.density, o.temperature, 0.0, 7);
    gpu::PairSystemSpec spec;
    spec.box = start.box;
    spec.cutoff = o.cutoff;
    spec.skin = o.skin;
    spec.dt = o.dt;
    spec.precision = o.precision;
    spec.block_size = o.block;
    spec.lanes_per_particle = o.lanes;
    gpu::PeriodicPairSystem sys(spec, start.x, start.v);
    const double n = double(sys.size());
    // Melt the lattice at the requested temperature (the last rescaling a tenth of the warm-up
    // before timing).
    bench::bring_to_temperature(sys, o.temperature, o.warmup);
    const std::size_t peak = gpu::device_memory_in_use() - before;

    std::vector<double> rates;
    long builds = 0;
    for (int r = 0; r < o.repeats; ++r) {
        const long b0 = sys.list_stats().builds;
        const auto t0 = std::chrono::steady_clock::now();
        sys.run(o.steps);
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        rates.push_back(o.steps / s);
        builds += sys.list_stats().builds - b0;
    }
    const double sps = median(rates);
    const gpu::ListStats ls = sys.list_stats();
    const gpu::Thermo th = sys.thermo();
    std::printf("device=\"%s\" N=%.0f density=%g cutoff=%g skin=%g precision=%s block=%d lanes=%d steps_per_s=%.1f "
                "atom_steps_per_s=%.4g min=%.1f max=%.1f repeats=%d steps=%ld neighbours=%.2f "
                "capacity=%u steps_per_build=%.1f system_bytes_per_atom=%.0f device_bytes_per_atom=%.0f "
                "T=%.4f\n",
                dev.name.c_str(), n, o.density, o.cutoff, o.skin,
                o.precision == gpu::Precision::Double ? "double" : "mixed", o.block, ls.lanes, sps, sps * n,
                *std::min_element(rates.begin(), rates.end()), *std::max_element(rates.begin(), rates.end()),
                o.repeats, o.steps, ls.mean_neighbours, ls.capacity,
                builds > 0 ? double(o.steps) * o.repeats / builds : 0.0, sys.device_bytes() / n, peak / n,
                2 * th.kinetic / (3 * n));

    if (o.profile) {
        // Fewest bytes each part must move through device memory per atom (8-byte reals,
        // 24-byte vectors), neighbours' positions assumed served from cache: the roofline.
        const double nb = ls.mean_neighbours;
        const double bytes_kick_drift = 24 * 3 + 4 + 24 * 2;   // read x v f species, write x v
        const double bytes_force = 24 + 4 + 4 * nb + 24;        // read x count indices, write f
        const double bytes_kick = 24 * 4 + 4 + 24;  // read v f x x_build species, write v
        sys.set_profiling(true);
        sys.run(o.steps);
        const gpu::StepProfile p = sys.profile();
        const double bw = gpu::copy_bandwidth(std::size_t(1) << 30, 10);
        auto row = [&](const char* name, double ms, double bytes) {
            const double per_step = ms * 1e-3 / p.steps;
            std::printf("  %-11s %8.2f us/step %6.1f %%", name, per_step * 1e6,
                        100 * ms / (p.kick_drift + p.rebuild + p.force + p.kick));
            if (bytes > 0)
                std::printf("  %6.0f B/atom  %6.2f TB/s = %3.0f %% of copy", bytes, bytes * n / per_step / 1e12,
                            100 * bytes * n / per_step / bw);
            std::printf("\n");
        };
        std::printf("profile over %ld steps (events per part: adds a sync per part), copy bandwidth %.2f TB/s\n",
                    p.steps, bw / 1e12);
        row("kick+drift", p.kick_drift, bytes_kick_drift);
        row("rebuild", p.rebuild, 0);
        row("force", p.force, bytes_force);
        row("kick+check", p.kick, bytes_kick);
    }
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "emergent-gpu-bench: %s\n", e.what());
    return 1;
}
