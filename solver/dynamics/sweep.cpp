#include "solver/dynamics/sweep.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace cushion::solver::dynamics {
namespace {

constexpr double kPa_per_MPa = 1000.0;
constexpr int kRow[6] = {0, 1, 2, 0, 1, 0}, kColumn[6] = {0, 1, 2, 1, 2, 2};  // Voigt XX YY ZZ XY YZ XZ

/// Point arrays of the harmonic displacement u_hat [mm] (first 3 x nodes entries of u).
std::vector<NamedField> displacement_fields(std::size_t nodes, const Eigen::VectorXcd& u, int component) {
  NamedField re{"U_real_mm", 3, {}}, im{"U_imag_mm", 3, {}}, amp{"U_amplitude_mm", 3, {}}, ph{"U_phase_deg", 1, {}};
  for (std::size_t a = 0; a < nodes; ++a) {
    for (int c = 0; c < 3; ++c) {
      const std::complex<double> z = u(static_cast<Eigen::Index>(3 * a + c));
      re.values.push_back(z.real());
      im.values.push_back(z.imag());
      amp.values.push_back(std::abs(z));
    }
    ph.values.push_back(phase_deg(u(static_cast<Eigen::Index>(3 * a + component))));
  }
  return {re, im, amp, ph};
}

/// Cell arrays of the Cauchy stress perturbation sigma_hat [MPa] (written in kPa), tensors in the Voigt
/// stress order XX YY ZZ XY YZ XZ.
std::vector<NamedField> stress_fields(const std::vector<Mat3c>& sigma_hat, int component) {
  NamedField re{"sigma_hat_real_kPa", 6, {}}, im{"sigma_hat_imag_kPa", 6, {}}, amp{"sigma_hat_amplitude_kPa", 6, {}},
      ph{"sigma_hat_phase_deg", 1, {}};
  for (const Mat3c& s : sigma_hat) {
    for (int v = 0; v < 6; ++v) {
      const int i = kRow[v], j = kColumn[v];
      const std::complex<double> z = kPa_per_MPa * 0.5 * (s(i, j) + s(j, i));
      re.values.push_back(z.real());
      im.values.push_back(z.imag());
      amp.values.push_back(std::abs(z));
    }
    ph.values.push_back(phase_deg(s(component, component)));
  }
  return {re, im, amp, ph};
}

}  // namespace

double phase_deg(std::complex<double> z) {
  const double deg = std::arg(z) * 180.0 / M_PI;
  return deg <= -180.0 ? deg + 360.0 : deg;
}

double displacement_amplitude(double acceleration, AccelerationReading reading, double frequency) {
  if (!(frequency > 0.0)) throw std::invalid_argument("displacement_amplitude: frequency must be > 0 Hz");
  const double a_peak = reading == AccelerationReading::peak ? acceleration : 0.5 * acceleration;
  const double w = 2.0 * M_PI * frequency;
  return a_peak / (w * w);
}

SweepRow make_row(const FrequencyResponse& r, Measure measure, const NominalGeometry& geometry) {
  if (r.reaction.size() < 2) throw std::invalid_argument("make_row: the response needs the groups {indenter, base}");
  SweepRow row;
  row.frequency = r.frequency;
  row.amplitude = r.amplitude;
  row.indenter_force = r.reaction[0];
  row.base_force = r.reaction[1];
  row.indenter_motion = r.displacement[0];
  switch (measure) {
    case Measure::indenter_held: row.stiffness = -row.indenter_force / r.amplitude; break;
    case Measure::indenter_driven: row.stiffness = row.indenter_force / r.amplitude; break;
    case Measure::indenter_free: row.stiffness = row.base_force / r.amplitude; break;
  }
  row.modulus = geometry.area > 0.0 ? row.stiffness * geometry.thickness / geometry.area : 0.0;
  return row;
}

void write_sweep_csv(const std::filesystem::path& file, const std::vector<SweepRow>& rows,
                     const std::vector<std::string>& comment) {
  // Written to <file>.tmp, then renamed: the sweep file is complete or absent, never half-written.
  const std::filesystem::path tmp = file.string() + ".tmp";
  std::ofstream out(tmp);
  if (!out) throw std::runtime_error(file.string() + ": cannot open the sweep file for writing");
  for (const auto& c : comment) out << "# " << c << "\n";
  out << "frequency_Hz,U_real_mm,U_imag_mm,"
         "indenter_RF_real_N,indenter_RF_imag_N,indenter_RF_amplitude_N,indenter_RF_phase_deg,"
         "base_RF_real_N,base_RF_imag_N,base_RF_amplitude_N,base_RF_phase_deg,"
         "indenter_U_amplitude_mm,indenter_U_phase_deg,transmissibility,"
         "stiffness_real_N_per_mm,stiffness_imag_N_per_mm,dynamic_stiffness_N_per_mm,"
         "dynamic_modulus_kPa,storage_modulus_kPa,loss_modulus_kPa,phase_deg\n";
  out.precision(10);
  for (const auto& r : rows) {
    const auto T = r.indenter_motion / r.amplitude;
    out << r.frequency << ',' << r.amplitude.real() << ',' << r.amplitude.imag() << ',' << r.indenter_force.real()
        << ',' << r.indenter_force.imag() << ',' << std::abs(r.indenter_force) << ',' << phase_deg(r.indenter_force)
        << ',' << r.base_force.real() << ',' << r.base_force.imag() << ',' << std::abs(r.base_force) << ','
        << phase_deg(r.base_force) << ',' << std::abs(r.indenter_motion) << ',' << phase_deg(r.indenter_motion) << ','
        << std::abs(T) << ',' << r.stiffness.real() << ',' << r.stiffness.imag() << ',' << std::abs(r.stiffness)
        << ',' << 1e3 * std::abs(r.modulus) << ',' << 1e3 * r.modulus.real() << ',' << 1e3 * r.modulus.imag() << ','
        << phase_deg(r.stiffness) << '\n';
  }
  out.close();
  if (!out) throw std::runtime_error(file.string() + ": write failed");
  std::filesystem::rename(tmp, file);
}

void write_frequency_frame(ResultSeries& series, const mesh::Mesh& mesh, const LinearisedSystem& system,
                           const LinearisedSystem::ElementBase& base, const FrequencyResponse& r, int component) {
  if (component < 0 || component > 2) throw std::invalid_argument("write_frequency_frame: component must be 0, 1 or 2");
  const std::size_t n = mesh.num_nodes();
  FrameData frame;
  frame.time = r.frequency;
  const Eigen::VectorXd& u_base = system.base_displacement();
  frame.displacement.resize(n);
  for (std::size_t a = 0; a < n; ++a) frame.displacement[a] = u_base.segment<3>(static_cast<Eigen::Index>(3 * a));
  frame.cauchy_stress = base.cauchy;
  frame.deformation_gradient = base.F;
  frame.point_fields = displacement_fields(n, r.u, component);
  frame.cell_fields = stress_fields(system.cauchy_perturbation(2.0 * M_PI * r.frequency, r.u), component);
  series.write_frame(mesh, frame);
}

void share_responses(std::vector<FrequencyResponse>& responses, std::vector<double>& solve_time,
                     const std::function<int(std::size_t)>& owner, const Distribution& d) {
  for (std::size_t k = 0; k < responses.size(); ++k) {
    FrequencyResponse& r = responses[k];
    const int root = owner(k);
    // Packed: frequency, solve time, amplitude, sizes, then u, reaction, displacement (re, im pairs).
    std::vector<double> packed;
    if (d.rank() == root) {
      packed = {r.frequency, solve_time[k], r.amplitude.real(), r.amplitude.imag(), double(r.u.size()),
                double(r.reaction.size()), double(r.displacement.size())};
      for (Eigen::Index i = 0; i < r.u.size(); ++i) packed.insert(packed.end(), {r.u(i).real(), r.u(i).imag()});
      for (const auto* part : {&r.reaction, &r.displacement})
        for (const std::complex<double>& z : *part) packed.insert(packed.end(), {z.real(), z.imag()});
    }
    double size = static_cast<double>(packed.size());
    d.broadcast(std::span<double>(&size, 1), root);
    packed.resize(static_cast<std::size_t>(size));
    d.broadcast(std::span<double>(packed), root);
    if (d.rank() == root) continue;
    r.frequency = packed[0], solve_time[k] = packed[1], r.amplitude = {packed[2], packed[3]};
    const auto nu = static_cast<Eigen::Index>(packed[4]);
    const auto nr = static_cast<std::size_t>(packed[5]), nd = static_cast<std::size_t>(packed[6]);
    auto z = [&](std::size_t j) { return std::complex<double>(packed[7 + 2 * j], packed[8 + 2 * j]); };
    r.u.resize(nu);
    for (Eigen::Index i = 0; i < nu; ++i) r.u(i) = z(static_cast<std::size_t>(i));
    r.reaction.resize(nr), r.displacement.resize(nd);
    for (std::size_t i = 0; i < nr; ++i) r.reaction[i] = z(static_cast<std::size_t>(nu) + i);
    for (std::size_t i = 0; i < nd; ++i) r.displacement[i] = z(static_cast<std::size_t>(nu) + nr + i);
  }
}

}  // namespace cushion::solver::dynamics
