// SPDX-License-Identifier: MIT
// Work-precision of the GPU path: wall time per tau against the errors of each time step in
// double and mixed precision, for WCA at rho = 0.8, T = 1 and a dense/hot state (rho = 1.0,
// T = 2) -- the states of benchmarks/work_precision.sh, at a size that fills a GPU.
// Every case starts from the same equilibrated state and runs NVE for `tau`; a double run at
// dt = 0.0005 is the reference. Errors: energy drift rate (slope of a linear fit) and
// fluctuation (standard deviation) of the total energy per particle, mean U and P against the
// reference with block standard errors (10 blocks), and the RMS position difference from the
// reference after 0.5 tau. Prints a Markdown table; --csv FILE also writes the rows.
//   emergent-gpu-work-precision --cells 40 --tau 10 --csv wp.csv
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "emergent/gpu.hpp"
#include "gpu_bench_support.hpp"
#include "support/fluid_start.hpp"

using namespace emergent;

namespace {

struct State {
    const char* name;
    double density, temperature;
};

struct Series {
    std::vector<double> t, e, u, p;
    std::vector<Vec3> x_half;  ///< unwrapped positions 0.5 tau after the start
    double wall_per_tau = 0;
    std::size_t bytes_per_atom = 0;
};

double mean(const std::vector<double>& a) {
    double s = 0;
    for (double v : a) s += v;
    return s / a.size();
}

double stddev(const std::vector<double>& a) {
    const double m = mean(a);
    double s = 0;
    for (double v : a) s += (v - m) * (v - m);
    return std::sqrt(s / (a.size() - 1));
}

double block_error(const std::vector<double>& a, int blocks = 10) {
    const std::size_t n = a.size() / blocks;
    std::vector<double> m;
    for (int b = 0; b < blocks; ++b) {
        double s = 0;
        for (std::size_t k = 0; k < n; ++k) s += a[b * n + k];
        m.push_back(s / n);
    }
    return stddev(m) / std::sqrt(double(blocks));
}

double slope(const std::vector<double>& t, const std::vector<double>& y) {
    const double tm = mean(t), ym = mean(y);
    double num = 0, den = 0;
    for (std::size_t k = 0; k < t.size(); ++k) {
        num += (t[k] - tm) * (y[k] - ym);
        den += (t[k] - tm) * (t[k] - tm);
    }
    return num / den;
}

/// NVE from (x, v) for `tau`, sampling every 0.1 tau; timed over the steps only.
Series run_case(const gpu::PairSystemSpec& spec, const std::vector<Vec3>& x, const std::vector<Vec3>& v,
                double tau) {
    const long per_sample = std::lround(0.1 / spec.dt);
    const long samples = std::lround(tau / 0.1);
    if (std::abs(per_sample * spec.dt - 0.1) > 1e-12)
        throw std::invalid_argument("dt=" + std::to_string(spec.dt) + " must divide 0.1");
    const std::size_t before = gpu::device_memory_in_use();
    gpu::PeriodicPairSystem sys(spec, x, v);
    Series s;
    const double n = double(sys.size());
    const double volume = spec.box.x * spec.box.y * spec.box.z;
    double wall = 0;
    for (long k = 1; k <= samples; ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        sys.run(per_sample);
        wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const gpu::Thermo th = sys.thermo();
        s.t.push_back(k * 0.1);
        s.e.push_back((th.kinetic + th.potential) / n);
        s.u.push_back(th.potential / n);
        s.p.push_back((2 * th.kinetic + th.virial) / (3 * volume));
        if (k == 5) s.x_half = sys.positions();
        if (k == 1) s.bytes_per_atom = (gpu::device_memory_in_use() - before) / sys.size();
    }
    s.wall_per_tau = wall / tau;
    return s;
}

}  // namespace

int main(int argc, char** argv) try {
    int cells = 40;
    double tau = 10;
    std::string csv;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (i + 1 >= argc) throw std::invalid_argument("option " + a + " needs a value");
        if (a == "--cells") cells = bench::number<int>(a, argv[++i]);
        else if (a == "--tau") tau = bench::number<double>(a, argv[++i]);
        else if (a == "--csv") csv = argv[++i];
        else throw std::invalid_argument("unknown option '" + a + "'");
    }
    const gpu::DeviceInfo dev = gpu::select_device();
    std::ofstream out;
    if (!csv.empty()) {
        out.open(csv);
        if (!out) throw std::runtime_error("cannot write " + csv);
        out << "state,precision,dt,wall_s_per_tau,bytes_per_atom,drift_per_tau,fluctuation,dU,dU_err,dP,dP_err,"
               "traj_error\n";
    }
    std::printf("device: %s, N = %d, NVE for %g tau per case, skin 0.3\n\n", dev.name.c_str(),
                4 * cells * cells * cells, tau);
    std::printf("| state | precision | dt | wall s per tau | B/atom | energy drift / tau | energy fluct. | "
                "U - U_ref | P - P_ref | traj. error at 0.5 tau |\n|---|---|---|---|---|---|---|---|---|---|\n");
    for (const State st : {State{"wca", 0.8, 1.0}, State{"dense_hot", 1.0, 2.0}}) {
        // Equilibrate: melt the lattice for 10 tau at dt 0.005, rescaling to T every tau.
        const auto start = fixtures::fcc_fluid(cells, st.density, st.temperature, 0.0, 11);
        gpu::PairSystemSpec spec;
        spec.box = start.box;
        std::vector<Vec3> x, v;
        {
            gpu::PeriodicPairSystem eq(spec, start.x, start.v);
            bench::bring_to_temperature(eq, st.temperature, 2000);
            eq.run(200);
            x = eq.positions();
            v = eq.velocities();
            for (Vec3& p : x)
                for (int d = 0; d < 3; ++d) p[d] -= spec.box[d] * std::floor(p[d] / spec.box[d]);
        }
        spec.dt = 0.0005;
        const Series ref = run_case(spec, x, v, tau);
        const double u_err = block_error(ref.u), p_err = block_error(ref.p);
        for (const gpu::Precision precision : {gpu::Precision::Double, gpu::Precision::Mixed})
            for (const double dt : {0.0005, 0.001, 0.002, 0.0025, 0.004, 0.005, 0.00625, 0.01}) {
                spec.dt = dt;
                spec.precision = precision;
                const Series s = run_case(spec, x, v, tau);
                double sq = 0;
                for (std::size_t i = 0; i < x.size(); ++i) {
                    const Vec3 d = s.x_half[i] - ref.x_half[i];
                    sq += dot(d, d);
                }
                const double traj = std::sqrt(sq / x.size());
                const double drift = slope(s.t, s.e), fluct = stddev(s.e);
                const double du = mean(s.u) - mean(ref.u), dp = mean(s.p) - mean(ref.p);
                const double due = std::hypot(block_error(s.u), u_err), dpe = std::hypot(block_error(s.p), p_err);
                const char* pname = precision == gpu::Precision::Double ? "double" : "mixed";
                std::printf("| %s | %s | %g | %.3g | %zu | %+.1e | %.1e | %+.1e ± %.0e | %+.1e ± %.0e | %.1e |\n",
                            st.name, pname, dt, s.wall_per_tau, s.bytes_per_atom, drift, fluct, du, due, dp,
                            dpe, traj);
                std::fflush(stdout);
                if (out)
                    out << st.name << ',' << pname << ',' << dt << ',' << s.wall_per_tau << ','
                        << s.bytes_per_atom << ',' << drift << ',' << fluct << ',' << du << ',' << due << ','
                        << dp << ',' << dpe << ',' << traj << '\n';
            }
    }
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "emergent-gpu-work-precision: %s\n", e.what());
    return 1;
}
