// SPDX-License-Identifier: MIT
// Linear stability of circular Couette flow between coaxial cylinders (outer one at rest)
// against axisymmetric Taylor vortices: where the vortices appear, and which of them grows
// fastest once they can.
#pragma once

#include <vector>

namespace emergent {

/// The axisymmetric perturbation equations of the viscous flow v_theta = A r + B / r in the
/// gap, with no-slip walls, solved on a Chebyshev grid across the gap. Lengths are in units of
/// the gap d, times in d^2 / nu, the Reynolds number is Re = omega r_i d / nu, and a mode of
/// axial wavenumber k (units 1/d) grows as exp(sigma t). The leading mode is taken to be real
/// (exchange of stabilities, established for this flow when the outer cylinder is at rest).
class CouetteStability {
public:
    /// `radius_ratio` = r_i / r_o, in (0, 1); `points` across the gap (32 resolve Re_c to
    /// ~1e-8 relative for radius ratios 0.5 to 0.95).
    explicit CouetteStability(double radius_ratio, int points = 32);

    /// Growth rate sigma (units nu / d^2) of the leading axisymmetric mode of wavenumber k at
    /// Reynolds number Re. A mode that decays faster than k^2 + 9 returns -(k^2 + 9).
    double growth_rate(double reynolds, double wavenumber) const;

    /// The Reynolds number at which the mode of wavenumber k neither grows nor decays.
    double marginal_reynolds(double wavenumber) const;

    /// The minimum of the marginal curve: the critical Reynolds number and the wavenumber
    /// of the vortices that appear there (wavelength 2 pi / k in units of d).
    struct Onset {
        double reynolds = 0;
        double wavenumber = 0;
    };
    Onset onset() const;

    /// Of the axial modes a cylinder of length L (in units of d) admits, the one that grows
    /// fastest at Re: k = m pi / L with closed, stress-free ends (cos(k z) in v_r: m vortices),
    /// k = 2 pi m / L with periodic ends (2 m vortices).
    struct AdmissibleMode {
        int index = 0;            ///< m
        double wavenumber = 0;    ///< k (1/d)
        double growth_rate = 0;   ///< sigma (nu / d^2)
        int vortices = 0;         ///< vortices it makes along the length
    };
    AdmissibleMode fastest_admissible_mode(double reynolds, double length, bool periodic) const;

private:
    /// Largest eigenvalue of the operator whose eigenvalue is 1 where sigma is a growth rate
    /// (u = [(L - sigma) L]^-1 2 k^2 Omega (L - sigma)^-1 2 A u), at Re = 1 (it scales as Re^2).
    double coupling_eigenvalue(double sigma, double wavenumber) const;

    double eta_;
    int n_;                     ///< grid points (Chebyshev order + 1)
    std::vector<double> r_;     ///< Chebyshev points across the gap, r_o first
    std::vector<double> ddr_;   ///< d/dr on them (n x n, row-major)
};

}  // namespace emergent
