// One whirl direction of an axisymmetric spinning shaft as a planar line (whirl_line.hpp).
#include "whirl_line.hpp"

#include <cmath>
#include <limits>

#include "beam_attachments.hpp"
#include "modalbench/numerics/line_mode.hpp"

namespace modalbench::exact::detail {

namespace {

/// The state matrix and wavenumber bound of one piece `own` (polar rotary inertia rhoIp per
/// length) in the units of the first piece `ref`, as BendingLine::set_piece with the rotary term
/// rho I lambda replaced per `w`.
void set_whirl_piece(const BeamBending& ref, const BeamBending& own, double rhoIp, const Whirling& w,
                     std::function<Eigen::MatrixXd(double)>& state_matrix, std::function<double(double)>& wavenumber) {
  const double L2 = ref.L * ref.L, c = ref.rhoA * L2 * L2 / ref.EI;
  const double ss = std::isinf(own.kGA) ? 0.0 : ref.EI / (own.kGA * L2), inv_e = ref.EI / own.EI;
  const double a = own.rhoA / ref.rhoA, rr = own.rhoI / (ref.rhoA * L2), rp = rhoIp / (ref.rhoA * L2);
  const double sg = w.sense, spin = w.spin;
  const bool sync = w.synchronous;
  // rho I lambda - s rho I_p Omega sqrt(lambda) (or (rho I - s rho I_p) lambda), per rho A0 L^2.
  auto rotary = [=](double lambda, double rI, double rIp) {
    const double lam = std::max(lambda, 0.0);
    return sync ? (rI - sg * rIp) * lam : rI * lam - sg * rIp * spin * std::sqrt(lam);
  };
  state_matrix = [=](double lambda) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
    // y = [w, phi, Q, M]
    A(0, 1) = 1.0; A(0, 2) = ss;
    A(1, 3) = inv_e;
    A(2, 0) = -a * lambda * c;
    A(3, 1) = -rotary(lambda, rr, rp) * c; A(3, 2) = -1.0;
    return A;
  };
  // The piece's own scaling: O2 = |lambda| rhoA L^4 / EI, shear s = EI / (kGA L^2), rotary
  // R = |rotary| L^2 / EI; the wavenumbers' squares are bounded by O2 s + R + sqrt(O2) + sqrt(O2 s R).
  const double s_own = std::isinf(own.kGA) ? 0.0 : own.EI / (own.kGA * L2), k_o2 = own.rhoA * L2 * L2 / own.EI,
               k_r = L2 / own.EI, rI = own.rhoI;
  wavenumber = [=](double lambda) {
    const double O2 = std::abs(lambda) * k_o2, R = std::abs(rotary(std::abs(lambda), rI, rhoIp)) * k_r;
    return 1.25 * std::sqrt(O2 * s_own + R + std::sqrt(O2) + std::sqrt(O2 * s_own * R));
  };
}

/// A tapered piece's whirl line variation: set_whirl_piece's state matrix with the properties at
/// each xi, and the wavenumber bound of a comparison over [xi0, xi1] (EI and kGA lowest, rhoA highest,
/// the rotary term at its largest size: rhoI lambda + rhoIp spin sqrt(lambda) with both highest).
LineVariation whirl_variation(const BeamBending& beam, const Segment& piece, bool eb, const Whirling& w) {
  const double L = beam.L;
  const BeamBending r{beam.EI, beam.kGA, beam.rhoA, beam.rhoI, L};  // the units (the first piece's)
  const auto rho_ip = [eb, rho = piece.material.rho](const Section& sec) { return eb ? 0.0 : rho * sec.Ip; };
  return {[r, piece, beam, rho_ip, w, L](double lambda, double xi) {
            std::function<Eigen::MatrixXd(double)> A;
            std::function<double(double)> p;
            set_whirl_piece(r, beam.at(xi * L), rho_ip(piece.properties_at(xi * L)), w, A, p);
            return A(lambda);
          },
          [piece, rho_ip, w, L, eb](double lambda, double xi0, double xi1) {
            const Segment::Bounds b = piece.bounds_on(xi0 * L, xi1 * L);
            if (!b.weakest_exists) return std::numeric_limits<double>::quiet_NaN();
            const Material& m = piece.material;
            const double EI = m.E * b.weakest.Iy, kGA = eb ? kInf : b.kappa_lo * m.G * b.weakest.A;
            const double rhoA = m.rho * b.heaviest.A, rhoI = eb ? 0.0 : m.rho * b.heaviest.Iy, rhoIp = rho_ip(b.heaviest);
            const double L2 = L * L, lam = std::abs(lambda);
            const double O2 = lam * rhoA * L2 * L2 / EI, s_own = std::isinf(kGA) ? 0.0 : EI / (kGA * L2);
            const double rotary = w.synchronous ? (rhoI + rhoIp) * lam : rhoI * lam + rhoIp * std::abs(w.spin) * std::sqrt(lam);
            const double R = rotary * L2 / EI;
            return 1.25 * std::sqrt(O2 * s_own + R + std::sqrt(O2) + std::sqrt(O2 * s_own * R));
          }};
}

}  // namespace

BendingLine whirl_line(const Scene& s, const Whirling& w) {
  const BeamBending b = bending_xz(s);
  BendingLine line(b, {s.x0.translational, s.x0.rotational}, {s.xL.translational, s.xL.rotational},
                   line_points(s, ModeFamily::BendingXZ));
  line.sys.polynomial_in_lambda = w.synchronous;
  const bool eb = s.theory == Theory::EulerBernoulli;
  const std::vector<Segment> pieces = s.beam_pieces();
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const double rhoIp = eb ? 0.0 : pieces[i].material.rho * pieces[i].properties_at(pieces[i].x_from).Ip;
    const BeamBending own = b.at(pieces[i].x_from);
    if (i == 0) set_whirl_piece(b, own, rhoIp, w, line.sys.state_matrix, line.sys.max_wavenumber);
    else set_whirl_piece(b, own, rhoIp, w, line.sys.steps[i - 1].state_matrix, line.sys.steps[i - 1].max_wavenumber);
    if (pieces[i].tapered()) (i == 0 ? line.sys.variation : line.sys.steps[i - 1].variation) = whirl_variation(b, pieces[i], eb, w);
  }
  // line_points puts the point supports first, then the masses in order (beam_attachments.cpp).
  const double kr = b.L / b.EI;
  for (std::size_t j = 0; j < s.masses.size(); ++j) {
    LineAttachment& at = line.sys.attachments[s.point_supports.size() + j];
    const PointMass& m = s.masses[j];
    if (w.synchronous) at.mass[1] = (m.Jy - w.sense * m.Jx) * kr;
    else at.gyro = {0.0, w.sense * m.Jx * w.spin * kr};
  }
  return line;
}

std::vector<double> whirl_shape(const Scene& s, const Whirling& w, double omega, const std::vector<double>& xs) {
  BendingLine line = whirl_line(s, w);
  const double L = s.geometry.length;
  for (double x : xs) line.sys.nodes_at.push_back(x / L);
  const LineMode mode(line.sys, omega * omega);
  std::vector<double> disp;
  for (double x : xs) disp.push_back(mode.state(x / L)[0] * L);  // the state [w_bar, phi, Q, M], w_bar = w / L
  return disp;
}

}  // namespace modalbench::exact::detail
