#pragma once
/// Hereditary-integral viscoelastic stress of the paper (Deng et al. 2025, eq. 6), evaluated in
/// closed form for a piecewise-linear strain history.
///
/// Convention (checked against the paper's Table 2, see README "Calibration"): strain and stress are
/// nominal and COMPRESSION POSITIVE, and
///   sigma_v(t) = - Re sum_i alpha_i J(beta_i; t),   J(beta; t) = int_0^t exp(-beta (t - tau)) eps'(tau) dtau,
/// i.e. the paper's alpha_i are read in its tension-positive stress with compression-positive strain.
/// With this sign Table 2 gives a compressive viscous stress on loading (about +2.2 kPa at 75 %) and a
/// positive difference stress (loading above unloading); with the opposite sign the loading branch
/// would lie below the unloading branch (negative dissipation).
///
/// Closed form: on a piece [t_k, t_k + h] with constant rate r_k the strain increment is de = r_k h and
///   J(t_k + s) = exp(-beta s) J(t_k) + r_k s phi(beta s),   phi(z) = (1 - exp(-z)) / z,
/// with phi evaluated by its series near z = 0 (the beta -> 0 limit J = eps(t) - eps(0) is exact).
#include <complex>
#include <vector>

namespace cushion::calibration {

using cplx = std::complex<double>;

/// One residue/mode pair of eq. 6: alpha [MPa] (complex residue), beta [1/s] (complex mode, Re >= 0 decays).
struct HereditaryMode {
  cplx alpha;
  cplx beta;
};

/// phi(z) = (1 - e^{-z})/z and its derivative, stable for all z (series for |z| < 0.1).
cplx phi(cplx z);
cplx phi_prime(cplx z);

/// J(beta; t) and dJ/dbeta at query times for the piecewise-linear strain through (time, strain).
/// time [s] strictly increasing; strain [-]; query times in [time.front(), time.back()] (clamped).
/// The integral starts at time.front() (J = 0 there).
struct HereditaryKernel {
  std::vector<cplx> J;       ///< [-] J(beta; t_q)
  std::vector<cplx> dJ_dbeta;///< [s] dJ/dbeta (J is holomorphic in beta)
};
HereditaryKernel hereditary_kernel(const std::vector<double>& time, const std::vector<double>& strain,
                                   cplx beta, const std::vector<double>& query_times);

/// Indices of the samples where a piecewise-linear history (time [s] increasing, strain [-]) changes slope:
/// the first and last samples and every sample the chord between its neighbouring kept samples misses by
/// more than `tolerance` [-] (greedy, each chord as long as possible). The kernel over the kept samples equals
/// the kernel over all of them to within `tolerance` times the residues (exactly for collinear samples), at
/// a cost proportional to the number of pieces instead of samples.
std::vector<std::size_t> piecewise_linear_knots(const std::vector<double>& time, const std::vector<double>& strain,
                                                double tolerance);

/// Viscoelastic stress sigma_v(t_q) [MPa], nominal, compression positive (convention above).
std::vector<double> hereditary_stress(const std::vector<double>& time, const std::vector<double>& strain,
                                      const std::vector<HereditaryMode>& modes,
                                      const std::vector<double>& query_times);

/// The paper's Table 2 parameters in internal units: alpha read as kPa (converted to MPa), beta in 1/s.
std::vector<HereditaryMode> paper_table2_modes();

/// Canonical form of a parameter set: the response is unchanged by (alpha, beta) -> (conj alpha, conj beta)
/// and by swapping modes, so Im beta >= 0 and modes sorted by Re beta ascending.
std::vector<HereditaryMode> canonical(std::vector<HereditaryMode> modes);

}  // namespace cushion::calibration
