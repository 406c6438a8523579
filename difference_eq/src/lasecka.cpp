#include "modalbench/numerics/root_finding.hpp"
#include "modalbench/difference_eq/lasecka.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "chain.hpp"
#include "modalbench/difference_eq/vibration.hpp"

namespace modalbench::difference_eq::lasecka {

namespace {

// cosh mu - 1 = a2 + sqrt(a2^2 + 6 a2), cos nu - 1 = a2 - sqrt(a2^2 + 6 a2), without cancellation.
struct Roots {
  double mu, nu, ch, cn;
  explicit Roots(double a2) {
    const double d = std::sqrt(a2 * a2 + 6.0 * a2);
    const double x1 = a2 + d, x2 = -6.0 * a2 / (a2 + d);
    mu = 2.0 * std::asinh(std::sqrt(0.5 * x1));
    nu = 2.0 * std::asin(std::min(1.0, std::sqrt(-0.5 * x2)));
    ch = 1.0 + x1;
    cn = 1.0 + x2;
  }
};

// sinh(mu y) / cosh(mu R) and cosh(mu y) / cosh(mu R) for y <= R + 1, without overflow.
void ratio(double mu, double y, double R, double& s, double& c) {
  if (mu * R <= 30.0) {
    const double chR = std::cosh(mu * R);
    s = std::sinh(mu * y) / chR;
    c = std::cosh(mu * y) / chR;
  } else {
    const double den = 1.0 + std::exp(-2.0 * mu * R);
    const double p = std::exp(mu * (y - R)), m = std::exp(-mu * (y + R));
    s = (p - m) / den;
    c = (p + m) / den;
  }
}

}  // namespace

double characteristic(long R, double a2) {
  const Roots r(a2);
  const double Rd = static_cast<double>(R);
  const double q = std::sinh(r.mu) / (r.ch + 2.0);
  return (r.cn + 2.0) * q * std::sin(r.nu * Rd) - std::sin(r.nu) * std::tanh(r.mu * Rd) * std::cos(r.nu * Rd);
}

double characteristic_printed(long R, double a2) {
  const Roots r(a2);
  const double Rd = static_cast<double>(R);
  const double q = std::sinh(r.mu) / (r.ch + 2.0);
  return (r.ch - r.cn) * (r.cn + 2.0) * q * std::sin(r.nu * Rd) -
         std::sin(r.nu) * std::tanh(r.mu * Rd) * std::cos(r.nu * Rd);
}

std::vector<double> eigenvalues(long R) {
  std::vector<double> out;
  if (R < 2) return out;
  // The clamped-pinned eigenproblem (8) is the lumped-mass clamped-pinned vibration problem
  // with Omega = 12 alpha^2: its exact count brackets every root; then the paper's
  // (corrected) characteristic equation is solved inside the bracket.
  RegularBeam b;
  b.EI = 1.0;
  b.rhoA = 1.0;
  b.R = R;
  b.L = static_cast<double>(R);  // a = 1: lambda = omega^2 = 24 alpha^2
  b.k0 = b.r0 = b.kL = kInf;
  b.rL = 0.0;
  const Spectrum sp = natural_frequencies(b, MassModel::Lumped, static_cast<int>(std::min<long>(R - 1, 2'000'000'000L)));
  if (static_cast<long>(sp.omega_rad_s.size()) != R - 1)
    throw std::runtime_error("lasecka: expected " + std::to_string(R - 1) + " eigenvalues");
  for (double w : sp.omega_rad_s) {
    const double a0 = w * w / 24.0;
    double root = a0;
    auto f = [&](double x) { return characteristic(R, x); };
    for (double d = 1e-12; d <= 1e-4; d *= 10.0) {
      const double lo = a0 * (1.0 - d), hi = std::min(2.0, a0 * (1.0 + d));
      const double flo = f(lo), fhi = f(hi);
      if (flo == 0.0 || fhi == 0.0 || (flo > 0) != (fhi > 0)) {
        root = (flo == 0.0) ? lo : (fhi == 0.0 ? hi : bracketed_root(f, lo, hi, flo, fhi, 2e-300, detail::kRootRelTol).root);
        break;
      }
    }
    out.push_back(root);
  }
  return out;
}

Eigenfunction eigenfunction(long R, double a2) {
  const Roots rt(a2);
  const double Rd = static_cast<double>(R);
  const double p = std::sin(rt.nu) / (rt.cn + 2.0), q = std::sinh(rt.mu) / (rt.ch + 2.0);
  const double snR = std::sin(rt.nu * Rd), cnR = std::cos(rt.nu * Rd);
  double sRR, cRR;
  ratio(rt.mu, Rd, Rd, sRR, cRR);  // tanh(mu R), 1
  double zero_s, inv_ch;
  ratio(rt.mu, 0.0, Rd, zero_s, inv_ch);  // 0, 1 / cosh(mu R)
  // D^-1 / cosh(mu R) and C_R / cosh(mu R) with C_R = cosh(mu R) - cos(nu R).
  const double Dinv = q * snR * inv_ch - p * sRR;
  const double CR = 1.0 - cnR * inv_ch;
  Eigenfunction ef;
  ef.W.resize(R + 3);
  ef.Phi.resize(R + 3);
  ef.D2.resize(R + 1);
  ef.D3.resize(R);
  const double x1 = rt.ch - 1.0, x2 = rt.cn - 1.0;  // Delta^2 multiplies the cosh/sinh part by 2 x1, the cos/sin part by 2 x2
  const double sh2 = std::sinh(0.5 * rt.mu), sn2 = std::sin(0.5 * rt.nu);
  for (long r = -1; r <= R + 1; ++r) {
    const double y = static_cast<double>(r);
    double e, c, eR, cR;
    ratio(rt.mu, y, Rd, e, c);
    ratio(rt.mu, Rd - y, Rd, eR, cR);
    // W = D C_R (p sinh mu r - q sin nu r) + cosh mu r - cos nu r, regrouped:
    // hyperbolic part D [-p sinh mu(R - r) - p cos(nu R) sinh mu r + q sin(nu R) cosh mu r].
    const double H = (-p * eR - p * cnR * e + q * snR * c) / Dinv;
    const double T = -CR * q * std::sin(rt.nu * y) / Dinv - std::cos(rt.nu * y);
    // Phi = 3 D q p C_R (cosh mu r - cos nu r) + 3 q sinh mu r + 3 p sin nu r, regrouped:
    // hyperbolic part 3 q D [p cosh mu(R - r) - p cos(nu R) cosh mu r + q sin(nu R) sinh mu r].
    const double Phi = 3.0 * q * (p * cR - p * cnR * c + q * snR * e) / Dinv -
                       3.0 * q * p * CR * std::cos(rt.nu * y) / Dinv + 3.0 * p * std::sin(rt.nu * y);
    ef.W[r + 1] = H + T;
    ef.Phi[r + 1] = Phi;
    if (r >= 0 && r <= R) ef.D2[r] = 2.0 * x1 * H + 2.0 * x2 * T;
    if (r >= 0 && r < R) {
      // (E - 1) on each term: sinh mu(r+1) - sinh mu r = 2 sinh(mu/2) cosh mu(r + 1/2), etc.
      double eh, ch, eRh, cRh;
      ratio(rt.mu, y + 0.5, Rd, eh, ch);
      ratio(rt.mu, Rd - y - 0.5, Rd, eRh, cRh);
      const double dH = 2.0 * sh2 * (p * cRh - p * cnR * ch + q * snR * eh) / Dinv;
      const double dT = -CR * q * 2.0 * sn2 * std::cos(rt.nu * (y + 0.5)) / Dinv + 2.0 * sn2 * std::sin(rt.nu * (y + 0.5));
      ef.D3[r] = 2.0 * x1 * dH + 2.0 * x2 * dT;
    }
  }
  return ef;
}

Output solve(const Input& in) {
  const long R = in.R;
  if (R < 2) throw std::invalid_argument("lasecka: R must be >= 2");
  if (static_cast<long>(in.P.size()) != R + 1) throw std::invalid_argument("lasecka: P must have R + 1 entries");
  if (!(in.EI > 0 && in.L > 0)) throw std::invalid_argument("lasecka: EI and L must be > 0");
  for (double k : {in.kappa0, in.chi0, in.kappaR})
    if (!(k >= 0 && std::isfinite(k))) throw std::invalid_argument("lasecka: springs must be finite and >= 0");
  const double Rd = static_cast<double>(R);
  const double a = in.L / Rd, B = a * a * a / (24.0 * in.EI);
  const auto& P = in.P;
  Output out;
  out.alpha2 = eigenvalues(R);
  std::vector<double> wsum(R + 1, 0.0), phisum(R + 1, 0.0);
  double sV0 = 0, sVR = 0, sf0 = 0, X1 = 0, X2 = 0, X3 = 0;
  for (double a2 : out.alpha2) {
    const Eigenfunction ef = eigenfunction(R, a2);
    out.char_residual.push_back(std::abs(characteristic(R, a2)));
    out.printed_char.push_back(std::abs(characteristic_printed(R, a2)));
    double nrm = 0;
    for (long r = 0; r <= R; ++r) nrm += ef.W[r + 1] * ef.W[r + 1];
    nrm = std::sqrt(nrm);
    auto W = [&](long r) { return ef.W[r + 1] / nrm; };
    auto Phi = [&](long r) { return ef.Phi[r + 1] / nrm; };
    auto d2 = [&](long r) { return ef.D2[r] / nrm; };            // Delta^2 W_r
    auto d3 = [&](long r) { return ef.D3[r] / nrm; };            // (E - 1) Delta^2 W_r
    double Pk = 0;
    for (long r = 0; r <= R; ++r) Pk += P[r] * W(r);
    const double c = Pk / a2;  // P_k / alpha_k^2
    for (long r = 0; r <= R; ++r) {
      wsum[r] += c * W(r);
      phisum[r] += c * Phi(r);
    }
    sV0 += c * d3(0);        // (E - 1) Delta^2 W_0
    sVR += -c * d3(R - 1);   // (E^-1 - 1) Delta^2 W_R
    sf0 += c * d2(0);        // Delta^2 W_0
    X1 += -c * d3(0);        // (1 - E) Delta^2 W_0
    X2 += c * d3(R - 1);     // (1 - E^-1) Delta^2 W_R
    X3 += c * d2(0);
  }
  // (19)
  out.V0 = -sV0 / 24.0 + (P[1] + 6.0 * P[0]) / 6.0;
  out.VR = -sVR / 24.0 + (P[R - 1] + 6.0 * P[R]) / 6.0;
  out.f0 = sf0 / 24.0;
  // (21)
  const double EI = in.EI, L = in.L;
  const double K0 = in.kappa0 * L * L * L / EI, KR = in.kappaR * L * L * L / EI, Kf = in.chi0 * L / EI;
  const double Kp = K0 * KR * Kf;
  const double Kden = Kp + 3.0 * (K0 * KR + KR * Kf + Kf * K0);
  if (!(Kden > 0)) throw std::invalid_argument("lasecka: the elastic supports form a mechanism");
  const double K = 1.0 / Kden;
  const double V0 = out.V0, VR = out.VR, f0 = out.f0;
  out.V0s = K * (Kp * V0 + 3.0 * K0 * KR * (V0 - f0 / Rd) + 3.0 * K0 * Kf * (V0 + VR));
  out.VRs = K * (Kp * VR + 3.0 * K0 * KR * (VR + f0 / Rd) + 3.0 * KR * Kf * (V0 + VR));
  out.f0s = K * (Kp * f0 + 3.0 * KR * Kf * (f0 - Rd * V0) + 3.0 * K0 * Kf * (f0 + Rd * VR));
  // (22), corrected (see lasecka.hpp), and as printed.
  const double R3 = Rd * Rd * Rd;
  out.v0 = 24.0 * B * R3 * K * (KR * Kf * V0 + 3.0 * KR * (V0 - f0 / Rd) + 3.0 * Kf * (V0 + VR));
  out.vR = 24.0 * B * R3 * K * (K0 * Kf * VR + 3.0 * K0 * (VR + f0 / Rd) + 3.0 * Kf * (V0 + VR));
  out.Theta0 = 24.0 * B * Rd * K * (K0 * KR * f0 + 3.0 * K0 * (f0 + Rd * VR) + 3.0 * KR * (f0 - Rd * V0));
  out.v0_printed = 24.0 * B * R3 * K * (KR * Kf * V0 + 3.0 * KR * (VR - f0 / Rd) + 3.0 * Kf * (V0 + VR));
  out.vR_printed = 24.0 * B * R3 * K * (K0 * Kf * VR + 3.0 * K0 * (V0 + f0 / Rd) + 3.0 * Kf * (V0 + VR));
  // (7) + (15)
  const double v0 = out.v0, vR = out.vR, T0 = out.Theta0, ch = (vR - v0) / Rd;
  out.w.resize(R + 1);
  out.phi.resize(R + 1);
  out.w_rigid.resize(R + 1);
  out.w23.resize(R + 1);
  for (long r = 0; r <= R; ++r) {
    const double x = static_cast<double>(r);
    const double wbar = v0 + T0 * x + 1.5 / Rd * (ch - T0) * x * x + 0.5 / (Rd * Rd) * (T0 - ch) * x * x * x;
    const double pbar = T0 + 3.0 / Rd * (ch - T0) * x + 1.5 / (Rd * Rd) * (T0 - ch) * x * x;
    out.w_rigid[r] = B * wsum[r];
    out.w[r] = B * wsum[r] + wbar;
    out.phi[r] = B * phisum[r] + pbar;
    // (23), literally (sum to R - 1).
    const double om1 = x - Rd, om2 = x * x - 2.0 * Rd * x - 2.0 * Rd * Rd;
    const double O1 = K / 2.0 * (KR * Kf * om1 * om2 - 6.0 * KR * Rd * Rd * om1 + 6.0 * Kf * R3);
    const double O2 = K / 2.0 * (K0 * Kf * (2.0 * R3 - om1 * om2) + 6.0 * K0 * x * Rd * Rd + 6.0 * Kf * R3);
    const double O3 = K / 2.0 * (K0 * KR * om1 * (om2 + 2.0 * Rd * Rd) + 6.0 * K0 * x * Rd * Rd + 6.0 * KR * Rd * Rd * om1);
    out.w23[r] = B * (wsum[r] + O1 * X1 + O2 * X2 + O3 * X3 / Rd) +
                 4.0 * B * (O1 * (P[1] + 6.0 * P[0]) + O2 * (P[R - 1] + 6.0 * P[R]));
  }
  return out;
}

}  // namespace modalbench::difference_eq::lasecka
