// SPDX-License-Identifier: MIT
// `emergent-couette-stability`: the linear stability of circular Couette flow for planning and
// reading Taylor-Couette runs - the onset, and the growth rate of every axial mode a cylinder
// of the given length admits at each Reynolds number asked for.
#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "emergent/kit/couette_stability.hpp"

namespace po = boost::program_options;

int main(int argc, char** argv) {
    double eta = 2.0 / 3.0, length = 4;
    std::vector<double> reynolds;
    std::string ends = "closed";
    po::options_description options(
        "usage: emergent-couette-stability [--radius-ratio ETA] [--length L] [--ends closed|periodic] "
        "[--reynolds RE]...\n  lengths in units of the gap d, growth rates in nu/d^2");
    options.add_options()("help,h", "this text")(
        "radius-ratio", po::value(&eta)->default_value(eta, "0.6667"), "r_inner / r_outer, in (0, 1)")(
        "length", po::value(&length)->default_value(length), "cylinder length / gap")(
        "ends", po::value(&ends)->default_value(ends), "closed (stress-free caps: cos(m pi z/L)) or periodic")(
        "reynolds", po::value(&reynolds)->multitoken(), "Re = omega r_i d / nu (several allowed)");
    try {
        po::variables_map vm;
        po::store(po::parse_command_line(argc, argv, options), vm);
        po::notify(vm);
        if (vm.count("help")) {
            std::cout << options << "\n";
            return 0;
        }
        if (ends != "closed" && ends != "periodic") throw std::invalid_argument("--ends must be closed or periodic");
        if (!(length > 0)) throw std::invalid_argument("--length must be positive");
        const emergent::CouetteStability stability(eta);
        const auto onset = stability.onset();
        const double pi = std::acos(-1.0);
        std::printf("radius ratio %.6g: Re_c = %.4f, k_c = %.4f / d, lambda_c = %.4f d\n", eta, onset.reynolds,
                    onset.wavenumber, 2 * pi / onset.wavenumber);
        const bool periodic = ends == "periodic";
        const double step = (periodic ? 2 : 1) * pi / length;
        for (const double re : reynolds) {
            const auto fastest = stability.fastest_admissible_mode(re, length, periodic);
            std::printf("Re %.4g: fastest admissible mode m = %d (%d vortices, lambda = %.4f d, sigma = %.4f nu/d^2)\n",
                        re, fastest.index, fastest.vortices, 2 * pi / fastest.wavenumber, fastest.growth_rate);
            for (int m = std::max(1, fastest.index - 3); m <= fastest.index + 3; ++m)
                std::printf("  m = %d: %d vortices, lambda = %.4f d, sigma = %.4f\n", m, periodic ? 2 * m : m,
                            2 * pi / (m * step), stability.growth_rate(re, m * step));
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "emergent-couette-stability: error: %s\n", e.what());
        return 2;
    }
    return 0;
}
