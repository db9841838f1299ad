#include "solver/dynamics/linearised_system.hpp"

#include <algorithm>
#include <mutex>
#include <stdexcept>

namespace cushion::solver::dynamics {
namespace {

/// Hold time that relaxes any Prony term [s] (exp(-hold / tau) underflows for tau < 1e9 s).
constexpr double relaxing_hold = 1e12;

/// A material frozen at one tangent: its "state" per point is the stress S (6) and the tangent C
/// (36, column-major); integrate() returns them whatever F is. Used to run the real element kernel
/// with a prescribed stress and tangent (the real and the imaginary part of the complex tangent).
class FrozenTangent final : public material::Material {
 public:
  static constexpr std::size_t size = 42;
  std::size_t state_size() const override { return size; }
  material::PointResponse integrate(const Mat3&, const Mat3&, double, std::span<const double> state_old,
                                    std::span<double> state_new) const override {
    material::PointResponse r;
    r.S = Eigen::Map<const Vec6>(state_old.data());
    r.dS_dE = Eigen::Map<const Mat6>(state_old.data() + 6);
    std::copy(state_old.begin(), state_old.end(), state_new.begin());
    return r;
  }
  Mat6c complex_tangent(const Mat3&, double) const override {
    throw std::logic_error("FrozenTangent::complex_tangent is not meaningful");
  }
  std::string describe() const override { return "frozen tangent (linearised system)"; }
};

using cplx = std::complex<double>;

/// Linearised Cauchy stress J^-1 F S F^T at F, S [MPa] in the direction dF (complex amplitude), with
/// dS = C : dE, dE = sym(F^T dF) (C maps engineering-shear strain to stress, material/tensor.hpp).
Mat3c cauchy_increment(const Mat3& F, const Vec6& S_voigt, const Mat6c& C, const Mat3c& dF) {
  const Mat3c Fc = F.cast<cplx>(), S = from_voigt_stress(S_voigt).cast<cplx>();
  const double J = F.determinant();
  const Mat3c dE = 0.5 * (Fc.transpose() * dF + dF.transpose() * Fc);
  Vec6c dE_voigt;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) dE_voigt(voigt_index(i, j)) = (i == j ? 1.0 : 2.0) * dE(i, j);
  const Vec6c dS_voigt = C * dE_voigt;
  Mat3c dS;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) dS(i, j) = dS_voigt(voigt_index(i, j));
  const Mat3c sigma = Fc * S * Fc.transpose() / J;
  const cplx dlogJ = (F.inverse().cast<cplx>() * dF).trace();
  return (dF * S * Fc.transpose() + Fc * S * dF.transpose() + Fc * dS * Fc.transpose()) / J - sigma * dlogJ;
}

}  // namespace

SparseMatrix damping_matrix(const Damping& damping, const SparseMatrix& M, const SparseMatrix& K) {
  SparseMatrix C = damping.rayleigh_alpha * M;
  if (damping.rayleigh_beta != 0.0) C += damping.rayleigh_beta * K;
  return C;
}

std::vector<PointBase> base_point_states(const Assembler& assembler, const StateStore& state,
                                         const Eigen::VectorXd& u_base, BaseStress stress) {
  StateStore scratch = state;
  Eigen::VectorXd f_int;
  std::vector<PointOutput> out;
  const AssemblyStatus status = assembler.assemble(u_base, u_base, 0.0, scratch, f_int, nullptr, &out);
  if (status.failed())
    throw std::runtime_error("base state: material failed in element " + std::to_string(status.element + 1) + ": " +
                             status.message);
  std::vector<PointBase> points(out.size());
  const auto& mesh = assembler.mesh();
  for (std::size_t e = 0; e < mesh.num_elements(); ++e) {
    const int s = assembler.section_of(static_cast<int>(e));
    if (s < 0) continue;
    const auto& mat = *assembler.sections()[s].material;
    const std::size_t ns = mat.state_size();
    const int nq = num_points(mesh.elements[e].type);
    std::vector<double> trial(ns);
    for (int q = 0; q < nq; ++q) {
      const std::size_t k = assembler.point_offset(static_cast<int>(e)) + q;
      points[k].F = out[k].F;
      points[k].S_geo = out[k].S;
      if (stress == BaseStress::relaxed) {
        const auto old = state.old_state(static_cast<int>(e)).subspan(q * ns, ns);
        const auto r = mat.integrate(out[k].F, out[k].F, relaxing_hold, old, trial);
        if (r.status == material::Status::failed)
          throw std::runtime_error("base state: relaxed stress failed in element " + std::to_string(e + 1) + ": " +
                                   r.message);
        points[k].S_geo = r.S;
      }
    }
  }
  return points;
}

struct LinearisedSystem::Impl {
  const mesh::Mesh& mesh;
  std::vector<Section> sections;  ///< as given (materials supply C*)
  std::vector<PointBase> points;
  Eigen::VectorXd u_base;
  std::unique_ptr<Assembler> frozen;  ///< all DOFs free, FrozenTangent materials
  StateStore state;
  std::mutex assembly;  ///< `state` is scratch of stiffness(): one caller at a time
};

LinearisedSystem::LinearisedSystem(const mesh::Mesh& mesh, const std::vector<Section>& sections,
                                   std::vector<PointBase> points, Eigen::VectorXd u_base, AssemblyOptions options)
    : impl_(new Impl{mesh, sections, std::move(points), std::move(u_base), nullptr, {}, {}}) {
  auto frozen_material = std::make_shared<const FrozenTangent>();
  std::vector<Section> frozen_sections = sections;
  for (auto& s : frozen_sections) s.material = frozen_material;
  // Replicated on every process of a distributed run: its matrices are used whole (products, LU).
  options.distribution = nullptr;
  impl_->frozen = std::make_unique<Assembler>(mesh, frozen_sections, DofMap(mesh.num_nodes(), {}), options);
  if (impl_->points.size() != impl_->frozen->num_points_total())
    throw std::invalid_argument("LinearisedSystem: point base states do not match the mesh and sections");
  if (impl_->u_base.size() != static_cast<Eigen::Index>(3 * mesh.num_nodes()))
    throw std::invalid_argument("LinearisedSystem: u_base must hold 3 values per node");
  impl_->state = impl_->frozen->make_state_store();
  K0_ = assemble_part(point_tangents(0.0), false);
  M_ = impl_->frozen->make_matrix();
  impl_->frozen->assemble_mass(M_);
}

LinearisedSystem::~LinearisedSystem() = default;

std::size_t LinearisedSystem::num_dofs() const { return 3 * impl_->mesh.num_nodes(); }

std::vector<std::string> LinearisedSystem::sections_without_density() const {
  std::vector<std::string> names;
  for (const auto& s : impl_->sections)
    if (!(s.density > 0.0)) names.push_back(s.name);
  return names;
}

std::vector<Mat6c> LinearisedSystem::point_tangents(double omega) const {
  const Impl& m = *impl_;
  const Assembler& A = *m.frozen;
  std::vector<Mat6c> C(m.points.size(), Mat6c::Zero());
  for (std::size_t e = 0; e < m.mesh.num_elements(); ++e) {
    const int s = A.section_of(static_cast<int>(e));
    if (s < 0) continue;
    const auto& mat = *m.sections[s].material;
    const int nq = num_points(m.mesh.elements[e].type);
    for (int q = 0; q < nq; ++q) {
      const std::size_t k = A.point_offset(static_cast<int>(e)) + q;
      C[k] = mat.complex_tangent(m.points[k].F, omega);
    }
  }
  return C;
}

SparseMatrix LinearisedSystem::assemble_part(const std::vector<Mat6c>& C, bool imaginary) const {
  Impl& m = *impl_;
  const Assembler& A = *m.frozen;
  for (std::size_t e = 0; e < m.mesh.num_elements(); ++e) {
    const int s = A.section_of(static_cast<int>(e));
    if (s < 0) continue;
    auto st = m.state.new_state(static_cast<int>(e));
    const int nq = num_points(m.mesh.elements[e].type);
    for (int q = 0; q < nq; ++q) {
      const std::size_t k = A.point_offset(static_cast<int>(e)) + q;
      double* d = st.data() + q * FrozenTangent::size;
      Eigen::Map<Vec6> S(d);
      Eigen::Map<Mat6> Ct(d + 6);
      S = imaginary ? Vec6::Zero() : m.points[k].S_geo;
      Ct = imaginary ? Mat6(C[k].imag()) : Mat6(C[k].real());
    }
  }
  m.state.commit();
  SparseMatrix K = A.make_matrix();
  Eigen::VectorXd f_int;
  const AssemblyStatus status = A.assemble(m.u_base, m.u_base, 0.0, m.state, f_int, &K);
  if (status.failed()) throw std::runtime_error("linearised stiffness: " + status.message);
  return K;
}

std::vector<PointOutput> LinearisedSystem::point_outputs(const Eigen::VectorXd& u) const {
  const std::lock_guard<std::mutex> lock(impl_->assembly);
  std::vector<PointOutput> out;
  Eigen::VectorXd f_int;
  const AssemblyStatus status = impl_->frozen->assemble(u, u, 0.0, impl_->state, f_int, nullptr, &out);
  if (status.failed()) throw std::runtime_error("linearised system: " + status.message);
  return out;
}

template <class T, class Value>
std::vector<T> LinearisedSystem::element_average(const std::vector<PointOutput>& points, const Value& value) const {
  const Assembler& A = *impl_->frozen;
  std::vector<T> out(impl_->mesh.num_elements(), T::Zero());
  for (std::size_t e = 0; e < out.size(); ++e) {
    if (A.section_of(static_cast<int>(e)) < 0) continue;
    double V = 0.0;
    for (int q = 0; q < num_points(impl_->mesh.elements[e].type); ++q) {
      const std::size_t k = A.point_offset(static_cast<int>(e)) + q;
      out[e] += points[k].dV0 * value(k);
      V += points[k].dV0;
    }
    out[e] /= V;
  }
  return out;
}

const Eigen::VectorXd& LinearisedSystem::base_displacement() const { return impl_->u_base; }

LinearisedSystem::ElementBase LinearisedSystem::element_base() const {
  const std::vector<PointOutput> p = point_outputs(impl_->u_base);
  const std::vector<PointBase>& base = impl_->points;
  ElementBase out;
  out.cauchy = element_average<Mat3>(p, [&](std::size_t k) {
    return Mat3(cauchy_from_pk2(base[k].F, from_voigt_stress(base[k].S_geo)));
  });
  out.F = element_average<Mat3>(p, [&](std::size_t k) { return base[k].F; });
  // Elements without a section average nothing: F = I there.
  for (std::size_t e = 0; e < out.F.size(); ++e)
    if (impl_->frozen->section_of(static_cast<int>(e)) < 0) out.F[e] = Mat3::Identity();
  return out;
}

std::vector<Mat3c> LinearisedSystem::cauchy_perturbation(double omega, const Eigen::VectorXcd& u_hat) const {
  const Eigen::Index n = static_cast<Eigen::Index>(num_dofs());
  if (u_hat.size() < n) throw std::invalid_argument("cauchy_perturbation: u_hat must hold 3 values per node");
  const Eigen::VectorXcd v = u_hat.head(n);
  const double scale = v.cwiseAbs().maxCoeff();
  std::vector<Mat3c> dF(impl_->points.size(), Mat3c::Zero());
  const std::vector<PointOutput> base = point_outputs(impl_->u_base);
  if (scale > 0.0) {
    // dF = (F(u + h w) - F(u - h w)) / 2h for w = Re, Im u_hat; h moves no node by more than 1e-4 mm.
    const double h = 1e-4 / scale;
    for (int part = 0; part < 2; ++part) {
      const Eigen::VectorXd w = part == 0 ? Eigen::VectorXd(v.real()) : Eigen::VectorXd(v.imag());
      const std::vector<PointOutput> plus = point_outputs(impl_->u_base + h * w);
      const std::vector<PointOutput> minus = point_outputs(impl_->u_base - h * w);
      const cplx unit = part == 0 ? cplx(1.0, 0.0) : cplx(0.0, 1.0);
      for (std::size_t k = 0; k < dF.size(); ++k) dF[k] += unit * ((plus[k].F - minus[k].F) / (2.0 * h)).cast<cplx>();
    }
  }
  const std::vector<Mat6c> C = point_tangents(omega);
  const std::vector<PointBase>& pb = impl_->points;
  return element_average<Mat3c>(base, [&](std::size_t k) { return cauchy_increment(pb[k].F, pb[k].S_geo, C[k], dF[k]); });
}

ComplexMatrix LinearisedSystem::stiffness(double omega) const {
  const std::vector<Mat6c> C = point_tangents(omega);
  const std::lock_guard<std::mutex> lock(impl_->assembly);
  const SparseMatrix Kr = assemble_part(C, false);
  const SparseMatrix Ki = assemble_part(C, true);
  ComplexMatrix K = Kr.cast<std::complex<double>>();
  for (Eigen::Index k = 0; k < K.nonZeros(); ++k) K.valuePtr()[k] += std::complex<double>(0.0, Ki.valuePtr()[k]);
  return K;
}

}  // namespace cushion::solver::dynamics
