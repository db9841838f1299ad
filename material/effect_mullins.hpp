#pragma once
/// Ogden-Roxburgh stress softening (Mullins effect; ABAQUS "foam energy dissipation" form, docs/physics.md
/// 5.2, where the damage variable scales the whole stress):
///   S = eta S_inner,  eta = 1 - (1/r) erf((W_max - W) / (m + beta W_max)),
/// W: strain energy of the ELASTIC BASE at F (the long-term base when the inner model is viscoelastic),
/// W_max: largest W reached so far (own state, 1 double). On first loading W = W_max and eta = 1
/// (the base response is unchanged); below W_max (unloading, reloading) eta < 1, so the stress is
/// lower than on first loading. Unloading and reloading follow the SAME curve (no hysteresis below
/// W_max): the effect dissipates only when W_max grows. Tangent (unsymmetric):
///   dS/dE = eta C_inner + S_inner (x) deta/dE,  deta/dE = (2 / (r sqrt(pi) (m + beta W_max))) e^{-z^2} S_base,
/// z = (W_max - W)/(m + beta W_max), S_base = dW/dE; deta/dE = 0 while loading (W >= W_max^n).
/// Strain driver (strain_scale m_e > 0, docs/physics.md 5.2): the softening is driven by the Biot strain norm of F
/// instead of the energy, D = ||U - I|| = sqrt(sum (l_a - 1)^2) [-] (the nominal strain e = 1 - l of a uniaxial
/// compression with fixed lateral stretches), with
///   eta = 1 - (1/r) erf((D_max - D) / (m_e + beta D_max)),  dD/dE = (I - U^-1) / D  (PK2 frame, D > 0),
/// in place of W, W_max, m and S_base = dW/dE in every formula of this header (the state stores D_max); m is unused.
/// The energy form softens by how far the energy fell below its maximum, which in a foam's densification drops fast;
/// the strain form by how far the strain fell, the softening shape of strain-based damage models (Qi-Boyce-like,
/// exponential damage in the largest strain) that the energy form follows only to about 0.05-0.1 in eta
/// (tools/mullins_shapes.py).
/// Damage in the largest strain (damage_limit d_inf > 0, docs/physics.md 5.2): a factor that falls on FIRST loading
/// too and never recovers multiplies eta, and the product takes eta's place in every formula of this header
/// (relaxation share included):
///   eta -> eta (1 - d),  d = d_inf (1 - exp(-N_max/e_d)),  N = ||U - I|| (the Biot strain norm), N_max its largest value,
///   deta/dE -> (1 - d) deta/dE - eta dd/dE,  dd/dE = (d_inf/e_d) exp(-N/e_d) dN/dE while N_max grows (N >= N_max^n),
///   else 0; dN/dE = (I - U^-1)/N.
/// With r -> infinity it is pure damage. The state then holds N_max after D_max. complex_tangent: (1 - d(N(F_base)))
/// times the form above (the damage is constant below its maximum); viscous_stress with the stored N_max.
/// complex_tangent: NOT a linear effect. It returns the tangent of the preconditioned (shaken-down)
/// state at W_max = W(F_base) approached from below, i.e. the reversible tangent that a small
/// vibration about a held preload sees after its first cycle:
///   C* = C*_inner + (2 / (r sqrt(pi) (m + beta W_b))) S_base (x) S_base   (real: no loss; strain driver:
///   C* = C*_inner + (2 / (r sqrt(pi) (m_e + beta D_b))) S_base (x) dD/dE, unsymmetric),
/// with S_inner at the relaxed base taken as the base stress S_base (exact when the inner model
/// relaxes to the base: hyperelastic or viscoelastic inner).
///
/// Relaxation share w in [0, 1] (docs/physics.md 5.2), only directly over a Prony memory (material/viscoelastic.hpp
/// PronyMemory: a Viscoelastic, or strain_dependent_prony over one): the memory is driven by the softened long-term
/// stress zeta S_e, zeta = eta^w, and the rest of the softening scales the whole stress:
///   S = eta^(1-w) [zeta S_e + sum a_i H_i[zeta S_e]]   (over a Viscoelastic).
/// w = 0 is the form above; w = 1 softens the long-term stress before the memory (S = eta S_e + sum a_i H_i[eta S_e]).
/// The memory beneath has already advanced from the stored (softened) state with S_e; the effect then stores
/// zeta S_e and drives the memory with (zeta - 1) S_e more (PronyMemory::drive_memory: the stress rises by
/// k_m (zeta - 1) S_e; Viscoelastic: k_m = sum a_i q_i, q_i the recursion weight; strain_dependent_prony:
/// k_m = f(J) sum a_i q_i), so that
///   S_visco = S_inner + (zeta - 1) k S_e,  k = 1 + k_m,
///   dS_visco/dE = dS_inner/dE + k [(zeta - 1) C_e + S_e (x) dzeta/dE] + (zeta - 1) S_e (x) dk_m/dE,
///   dzeta/dE = w eta^(w-1) deta/dE,  dS/dE = eta^(1-w) dS_visco/dE + (1 - w) eta^(-w) S_visco (x) deta/dE.
/// complex_tangent about the shaken-down base: C* = C*_inner + [w f(omega) + 1 - w] S_base (x) deta/dE,
/// f(omega) the memory's complex factor (Viscoelastic: 1 + sum a_i i omega tau_i/(1 + i omega tau_i); the memory
/// sees the softening's part w).
#include <cmath>

#include "material/effect_decorator.hpp"
#include "material/hyperelastic.hpp"
#include "material/viscoelastic.hpp"

namespace cushion::material {

/// Parameters in internal units (MPa).
struct MullinsParameters {
  double r = 2.0;     ///< r [-], > 1: eta >= 1 - 1/r (maximum softening 1/r)
  double m = 1e-3;    ///< m [MPa], > 0: energy scale of the softening
  double beta = 0.1;  ///< beta [-], >= 0: growth of the energy scale with W_max
  double relaxation_share = 0.0;  ///< w [-] in [0, 1]: share of the softening that drives the Prony memory
  double strain_scale = 0.0;      ///< m_e [-], >= 0: 0 drives the softening by the energy; > 0 by the Biot strain norm
  double damage_limit = 0.0;      ///< d_inf [-] in [0, 1): 0, no damage; > 0, the damage factor above
  double damage_strain = 0.3;     ///< e_d [-], > 0: Biot strain norm over which the damage grows
};

class MullinsEffect final : public EffectDecorator {
 public:
  /// energy_base: the elastic model whose energy drives the softening (not null); with relaxation_share > 0 it must be
  /// the long-term base of `inner`, which must be a PronyMemory. Throws std::invalid_argument on parameters outside
  /// the ranges above or a relaxation share > 0 over a model that is not a PronyMemory.
  MullinsEffect(std::shared_ptr<const Material> inner, std::shared_ptr<const Hyperelastic> energy_base,
                MullinsParameters parameters);

  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt, std::span<const double> state_old,
                          std::span<double> state_new) const override;
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override;
  /// eta^(1-w) times the inner viscous stress [MPa] (with w = 0 the softening scales the whole inner stress).
  Vec6 viscous_stress(const Mat3& F, std::span<const double> state) const override;
  std::string describe() const override;

  /// Softening factor eta [-] at driver D with maximum D_max: the base energy W [MPa] or the Biot strain norm [-].
  double eta(double D, double D_max) const;
  /// The driver D at F (e: the energy base at F) and its gradient dD/dE [Voigt, stress-like: dD = dD_dE . dE_voigt].
  struct Driver {
    double D = 0.0;
    Vec6 dD_dE = Vec6::Zero();
  };
  Driver driver(const Mat3& F, const ElasticEval& e) const;
  /// The Biot strain norm N = ||U - I|| [-] at F and dN/dE (0 at F = I).
  static Driver biot_norm(const Mat3& F);
  /// The damage factor 1 - d [-] at the largest Biot strain norm N_max (1 without damage).
  double damage_factor(double N_max) const { return damage_factor(p_.damage_limit, p_.damage_strain, N_max); }
  /// 1 - d_inf (1 - exp(-N_max/e_d)) [-] (d_inf, e_d, N_max [-]): the one formula of the damage, also for diagnose's
  /// damage start (calibration/damage_start.hpp).
  static double damage_factor(double damage_limit, double damage_strain, double N_max) {
    return 1.0 - damage_limit * -std::expm1(-N_max / damage_strain);
  }
  const MullinsParameters& parameters() const { return p_; }

 private:
  /// w > 0: stores zeta S_e in the Viscoelastic's state, adds q_i (zeta - 1) S_e to each H_i, and turns r from
  /// S_inner into S_visco with its tangent (formulas above).
  /// The scale of the erf's argument: m (energy) or m_e (strain) plus beta D_max.
  double scale(double D_max) const;
  /// A softening factor [-] and its gradient [Voigt, stress-like]; first_loading_unchanged: 1 and 0 identically.
  struct Softening {
    double value = 1.0;
    Vec6 d_dE = Vec6::Zero();
    bool first_loading_unchanged = true;
  };
  /// eta and deta/dE at the driver d (W or the Biot strain norm at F_new) below the stored D_max_old (state_new's D_max
  /// updated).
  Softening ogden_roxburgh(const Driver& d, double D_max_old, std::span<double> state_new) const;
  /// f times the damage factor 1 - d, with its gradient; n: the Biot strain norm at F_new (state_new's N_max updated
  /// from N_max_old).
  void damage(Softening& f, const Driver& n, double N_max_old, std::span<double> state_new) const;
  void drive_memory_with_softened_stress(PointResponse& r, const Mat3& F_new, const ElasticEval& e, double eta_value,
                                         const Vec6& deta_dE, double dt, std::span<double> state_new) const;

  std::shared_ptr<const Hyperelastic> energy_base_;
  std::shared_ptr<const PronyMemory> memory_;  ///< the Prony memory beneath when w > 0, else null
  MullinsParameters p_;
};

}  // namespace cushion::material
