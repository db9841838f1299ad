#pragma once
/// Exact fast forward model of the uniaxial calibration tests for a visco-hyperfoam whose terms share
/// one Poisson ratio nu (what `fit` produces), used by the consistency refit instead of the point driver.
///
/// Long-term base. The hyperfoam Kirchhoff stress is tau_a = 2 sum_i (mu_i/alpha_i)(l_a^alpha_i - J^(-alpha_i beta)),
/// beta = nu/(1 - 2 nu). With free lateral faces and l2 = l3 = l^(-nu): J = l^(1 - 2 nu), J^(-alpha beta) =
/// l^(-alpha nu) = l2^alpha, so tau_2 = tau_3 = 0 term by term: the uniaxial-free path is l2 = l^(-nu) for
/// ANY mu, alpha. With constrained lateral faces (l2 = l3 = 1) J = l. Either way the axial PK2 stress is
///   S11_inf(l) = sum_i (2 mu_i/alpha_i)(l^alpha_i - l^(-alpha_i c)) / l^2,   c = nu (free), nu/(1 - 2 nu) (constrained).
/// Prony (material/viscoelastic.hpp, FEBio form): S = S_inf + sum_k a_k H_k with H_k driven by S_inf. The
/// lateral S_inf is zero on the free path, so H_k and the total lateral stress stay zero: the point driver
/// (run_point, uniaxial_free) follows the same path, and while the platen touches (stretch imposed) the
/// nominal stress is, explicitly,
///   P11(t_n) = l_n [S11_inf(l_n) + sum_k a_k H_k(t_n)],
///   H_k(t_n) = e^{-x} H_k(t_{n-1}) + (1 - e^{-x})/x (S11_inf(l_n) - S11_inf(l_{n-1})),  x = (t_n - t_{n-1})/tau_k,
/// the recursion of material/viscoelastic.cpp on the same samples (H_k(t_0) = S11_inf(l_0): the first sample
/// is reached instantaneously from the virgin state). No Newton: linear in mu for fixed alpha and a, linear
/// in a for fixed mu. After a lift-off the platen no longer controls the stretch: only in-contact samples.
///
/// Dynamic test about the preload l_p (fit_model.hpp): E*(w) = S11(t_w) + K_v (1 + sum_k a_k i w tau_k/(1 + i w tau_k)),
/// K_v = l dS11_inf/dl at l_p (the condensed tangent l^2 C_c along the same path), S11(t_w) the total stress
/// at the measuring window along the schedule (or S11_inf(l_p) about a relaxed preload).
///
/// Templates so that ceres::Jet differentiates them. Strain and stress of the records are nominal and
/// compression positive; inside this header stretch l = 1 - strain and PK2 tension positive.
#include <cmath>
#include <complex>
#include <vector>

#include "calibration/hyperfoam_fit.hpp"

namespace cushion::calibration {

/// Lateral exponent c of the uniaxial path (see above) for Poisson ratio nu [-].
template <typename T>
T lateral_exponent(const T& nu, Lateral lateral) {
  return lateral == Lateral::free ? nu : nu / (1.0 - 2.0 * nu);
}

/// Axial long-term PK2 stress S11 [MPa], tension positive, of one hyperfoam term (mu [MPa], alpha) at stretch l.
template <typename T>
T term_S11(const T& mu, const T& alpha, const T& c, double l) {
  using std::exp;
  const double ln_l = std::log(l);  // l^p = e^{p ln l}: one exponential per power of a differentiated exponent
  return (2.0 * mu / alpha) * (exp((alpha - 2.0) * ln_l) - exp((-alpha * c - 2.0) * ln_l));
}

/// l dS11/dl [MPa] of one term at stretch l: its part of K_v.
template <typename T>
T term_l_dS11_dl(const T& mu, const T& alpha, const T& c, double l) {
  using std::exp;
  const double ln_l = std::log(l);
  return (2.0 * mu / alpha) * ((alpha - 2.0) * exp((alpha - 2.0) * ln_l) + (alpha * c + 2.0) * exp((-alpha * c - 2.0) * ln_l));
}

/// A sampled stretch history with the Prony recursion factors of every increment, prepared once.
struct UniaxialPath {
  std::vector<double> time;     ///< [s], strictly increasing
  std::vector<double> stretch;  ///< l = 1 - nominal compression [-]
  std::size_t modes = 0;        ///< Prony terms
  std::vector<double> decay, weight;  ///< e^{-x}, (1 - e^{-x})/x of increment n >= 1, mode k at [(n - 1) modes + k]
};

/// Path through (time [s], compression-positive nominal strain [-]) for Prony times tau [s]. Throws
/// std::invalid_argument if time is not strictly increasing or the arrays differ in length.
UniaxialPath make_uniaxial_path(const std::vector<double>& time, const std::vector<double>& strain,
                                const std::vector<double>& tau);

/// H_k at every sample (row n, column k; row-major n x modes) for the long-term stress S_inf at the samples.
template <typename T>
void viscous_states(const UniaxialPath& p, const T* S_inf, T* H) {
  const std::size_t M = p.modes;
  for (std::size_t k = 0; k < M; ++k) H[k] = S_inf[0];
  for (std::size_t n = 1; n < p.time.size(); ++n) {
    const T dS = S_inf[n] - S_inf[n - 1];
    for (std::size_t k = 0; k < M; ++k) {
      const std::size_t q = (n - 1) * M + k;
      H[n * M + k] = p.decay[q] * H[(n - 1) * M + k] + p.weight[q] * dS;
    }
  }
}

/// Total axial PK2 stress S11 = S_inf + sum_k a_k H_k [MPa] at every sample, for the long-term stress
/// S_inf [MPa] at the samples and the Prony moduli a_k relative to the long-term modulus.
template <typename T>
void total_S11(const UniaxialPath& p, const T* S_inf, const T* a, T* S11) {
  const std::size_t M = p.modes;
  std::vector<T> H(M, S_inf[0]);
  for (std::size_t n = 0; n < p.time.size(); ++n) {
    if (n > 0) {
      const T dS = S_inf[n] - S_inf[n - 1];
      for (std::size_t k = 0; k < M; ++k) {
        const std::size_t q = (n - 1) * M + k;
        H[k] = p.decay[q] * H[k] + p.weight[q] * dS;
      }
    }
    T s = S_inf[n];
    for (std::size_t k = 0; k < M; ++k) s += a[k] * H[k];
    S11[n] = s;
  }
}

/// Long-term S11 [MPa] at every sample of the path for N terms (mu [MPa], alpha) and lateral exponent c.
template <typename T>
std::vector<T> long_term_S11(const UniaxialPath& p, const T* mu, const T* alpha, std::size_t N, const T& c) {
  std::vector<T> S(p.time.size(), T(0.0));
  for (std::size_t n = 0; n < S.size(); ++n)
    for (std::size_t i = 0; i < N; ++i) S[n] += term_S11(mu[i], alpha[i], c, p.stretch[n]);
  return S;
}

/// Compression-positive nominal stress -P11 = -l S11 [MPa] at every sample (in contact throughout).
template <typename T>
std::vector<T> uniaxial_nominal_stress(const UniaxialPath& p, const T* mu, const T* alpha, std::size_t N, const T& c,
                                       const T* a) {
  const std::vector<T> S_inf = long_term_S11(p, mu, alpha, N, c);
  std::vector<T> S(S_inf.size());
  total_S11(p, S_inf.data(), a, S.data());
  for (std::size_t n = 0; n < S.size(); ++n) S[n] = -p.stretch[n] * S[n];
  return S;
}

/// The dynamic test's base path (fit_model.hpp dynamic_path): preload ramp, then the measuring-window
/// centre of each frequency as one more sample, `window[f]` its index; about a relaxed preload the path is
/// the single sample at the preload (no history) and every window is 0.
struct DynamicPath {
  UniaxialPath path;
  bool relaxed = false;           ///< S11 = S11_inf at the preload (no Prony history)
  double preload_stretch = 1.0;   ///< l_p [-]
  std::vector<double> frequency;  ///< [Hz]
  std::vector<double> amplitude;  ///< nominal strain amplitude delta_f [-] of the sine (0: small-amplitude limit)
  std::vector<std::size_t> window;
  std::vector<std::vector<std::complex<double>>> prony_weight;  ///< per frequency, harmonic h = 1, 2 (index
                                                                ///< 2 f + h - 1), mode k: i h w tau_k/(1 + i h w tau_k)
};

/// Samples of the sine cycle used for the harmonics of the finite-amplitude dynamic model.
inline constexpr int dynamic_cycle_samples = 16;

/// Storage and loss moduli [MPa] (nominal stress per nominal strain, compression positive) at the path's
/// frequencies, as a machine measures them (first harmonic of the stress over the strain amplitude) in
/// the periodic steady state of the sine e = e_p + delta sin(w t), finite delta:
///   S_inf(theta) = S11_inf(l_p - delta sin theta) sampled at `dynamic_cycle_samples` points -> harmonics 0, 1, 2
///   (A_h cos h theta + B_h sin h theta); the Prony series scales harmonic h by F_h = 1 + sum_k a_k i h w tau_k/(1 + i h w tau_k);
///   the mean adds the history part sum_k a_k H_k(t_w) of the schedule; sigma = -(l_p - delta sin theta) S11(theta),
///   whose first harmonic is  sin: -l_p B'_1 + delta (A'_0 - A'_2/2),  cos: -l_p A'_1 + delta B'_2/2,
///   E' = sin/delta, E'' = cos/delta. For delta -> 0 this is E* = S11(t_w) + K_v F_1 (fit_model.hpp), used when delta = 0.
template <typename T>
void uniaxial_dynamic_moduli(const DynamicPath& d, const T* mu, const T* alpha, std::size_t N, const T& c, const T* a,
                             T* storage, T* loss) {
  const std::size_t M = d.path.modes;
  const double lp = d.preload_stretch;
  T S_p(0.0), K_v(0.0);
  for (std::size_t i = 0; i < N; ++i) {
    S_p += term_S11(mu[i], alpha[i], c, lp);
    K_v += term_l_dS11_dl(mu[i], alpha[i], c, lp);
  }
  std::vector<T> S(d.path.time.size(), S_p);  // total S11 along the schedule
  if (!d.relaxed) {
    const std::vector<T> S_inf = long_term_S11(d.path, mu, alpha, N, c);
    total_S11(d.path, S_inf.data(), a, S.data());
  }
  // F_h = Fr + i Fi for harmonic h of frequency f.
  auto factor = [&](std::size_t f, int h, T& Fr, T& Fi) {
    Fr = T(1.0);
    Fi = T(0.0);
    for (std::size_t k = 0; k < M; ++k) {
      Fr += a[k] * d.prony_weight[2 * f + h - 1][k].real();
      Fi += a[k] * d.prony_weight[2 * f + h - 1][k].imag();
    }
  };
  for (std::size_t f = 0; f < d.frequency.size(); ++f) {
    const T history = S[d.window[f]] - S_p;  // sum_k a_k H_k(t_w) - (S11_inf(t_w) - S_p) = Prony part of the mean
    T Fr1, Fi1;
    factor(f, 1, Fr1, Fi1);
    const double delta = d.amplitude.empty() ? 0.0 : d.amplitude[f];
    if (delta == 0.0) {
      storage[f] = S_p + history + K_v * Fr1;
      loss[f] = K_v * Fi1;
      continue;
    }
    constexpr int K = dynamic_cycle_samples;
    T A0(0.0), A1(0.0), B1(0.0), A2(0.0), B2(0.0);
    for (int m = 0; m < K; ++m) {
      const double theta = 2.0 * 3.14159265358979323846 * m / K;
      const double l = lp - delta * std::sin(theta);
      T s(0.0);
      for (std::size_t i = 0; i < N; ++i) s += term_S11(mu[i], alpha[i], c, l);
      A0 += s / double(K);
      A1 += s * (2.0 / K * std::cos(theta));
      B1 += s * (2.0 / K * std::sin(theta));
      A2 += s * (2.0 / K * std::cos(2.0 * theta));
      B2 += s * (2.0 / K * std::sin(2.0 * theta));
    }
    T Fr2, Fi2;
    factor(f, 2, Fr2, Fi2);
    // Response to A cos + B sin with factor F: (Fr A + Fi B) cos + (Fr B - Fi A) sin.
    const T A0p = A0 + history;
    const T A1p = Fr1 * A1 + Fi1 * B1, B1p = Fr1 * B1 - Fi1 * A1;
    const T A2p = Fr2 * A2 + Fi2 * B2, B2p = Fr2 * B2 - Fi2 * A2;
    storage[f] = (-lp * B1p + delta * (A0p - 0.5 * A2p)) / delta;
    loss[f] = (-lp * A1p + 0.5 * delta * B2p) / delta;
  }
}

}  // namespace cushion::calibration
