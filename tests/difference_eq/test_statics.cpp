// Static closed forms of the regular discrete beam against (a) the assembled banded FE system
// solved directly in binary128 and (b) the exact continuous Euler-Bernoulli beam.
#define BOOST_TEST_MODULE difference_eq_statics
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "helpers.hpp"
#include "modalbench/difference_eq/assembled.hpp"
#include "modalbench/difference_eq/statics.hpp"
#include "modalbench/exact/exact.hpp"

using namespace modalbench::difference_eq;
using deq_test::quad;

namespace {

constexpr double EI = 2.0e6, L = 3.0;

RegularBeam beam(long R, double K0, double Kr0, double KL, double KrL) {
  // Springs given dimensionless: K = kappa L^3 / EI, Kr = chi L / EI.
  auto t = [](double K) { return std::isinf(K) ? kInf : K * EI / (L * L * L); };
  auto r = [](double K) { return std::isinf(K) ? kInf : K * EI / L; };
  return RegularBeam{EI, 0.0, L, R, t(K0), r(Kr0), t(KL), r(KrL)};
}

// Load patterns: interior force, end actions, moments, every node loaded.
std::vector<std::vector<NodalLoad>> patterns(long R) {
  std::vector<std::vector<NodalLoad>> p;
  p.push_back({{R / 2, -1000.0, 0.0}});
  p.push_back({{0, 10.0, -20.0}, {R, 300.0, 50.0}, {(2 * R) / 3, 0.0, 700.0}, {R / 3, -250.0, 0.0}});
  std::vector<NodalLoad> all;
  for (long r = 0; r <= R; ++r) all.push_back({r, -1.0 + 0.3 * std::sin(0.7 * static_cast<double>(r)), 0.0});
  p.push_back(all);
  return p;
}

const double kSweep[] = {0.0, 1e-6, 1e-2, 1.0, 1e3, 1e12, kInf};

// Error of w and slope against the binary128 assembled solve, relative to the natural size of
// the deflection field, max(max |w|, L max |slope|) (either may vanish on its own: w under a
// pure end moment of a clamped beam, the slope under a pure translation).
double error_vs_assembled(const RegularBeam& b, const std::vector<NodalLoad>& loads, StaticMethod m) {
  std::vector<quad> wq, sq;
  assembled::static_solve<quad>(b, loads, wq, sq);
  const StaticSolution s = solve_static(b, loads, m);
  double scale = 0, err = 0;
  for (std::size_t r = 0; r < wq.size(); ++r) {
    scale = std::max({scale, std::abs(static_cast<double>(wq[r])), L * std::abs(static_cast<double>(sq[r]))});
    const double e = std::max(std::abs(s.w[r] - static_cast<double>(wq[r])), L * std::abs(s.slope[r] - static_cast<double>(sq[r])));
    err = (std::isnan(e) || e > err) ? e : err;
  }
  return scale > 0 ? err / scale : err;  // all loads on held DOFs: the answer is exactly 0
}

}  // namespace

BOOST_AUTO_TEST_SUITE(closed_form_vs_assembled)

// Every spring combination of the sweep (dimensionless 0, 1e-6 ... 1e12, inf at each of the four
// DOFs) and every load pattern, R from 1 to 1000: the piecewise-cubic closed form equals the
// direct solve of the assembled system (binary128) to 1e-10 relative (max norm, w and slope).
BOOST_AUTO_TEST_CASE(piecewise_cubic_spring_sweep) {
  double worst = 0;
  int cases = 0;
  for (long R : {1L, 2L, 3L, 8L, 41L, 1000L})
    for (double a : kSweep)
      for (double b : kSweep)
        for (double c : kSweep)
          for (double d : kSweep) {
            if (R == 1000 && !(a == c || b == d)) continue;  // keep the run short at the largest R
            const RegularBeam bm = beam(R, a, b, c, d);
            if (rigid_body_modes(bm) > 0) continue;
            for (const auto& loads : patterns(R)) {
              const double e = error_vs_assembled(bm, loads, StaticMethod::PiecewiseCubic);
              ++cases;
              if (!(e <= worst)) worst = e;
              BOOST_TEST(e <= 1e-10, "R=" << R << " springs " << a << " " << b << " " << c << " " << d << ": " << e);
            }
          }
  BOOST_TEST_MESSAGE(cases << " cases, worst relative error " << worst);
}

// The paper's path (clamped-pinned eigenfunction expansion + settlements), generalised to four
// springs and nodal moments: the same check for R up to 1000 (it costs O(R^2), so fewer cases
// at the larger R).
BOOST_AUTO_TEST_CASE(eigenfunction_expansion_spring_sweep) {
  double worst = 0;
  for (long R : {1L, 2L, 5L, 16L, 120L, 1000L})
    for (double a : kSweep)
      for (double b : kSweep)
        for (double c : kSweep)
          for (double d : kSweep) {
            if (R == 120 && !(a == c && b == d)) continue;
            if (R == 1000 && !(a == c && b == d && (a == 1e-6 || a == 1.0 || a == kInf) && (b == 0 || b == 1e12))) continue;
            const RegularBeam bm = beam(R, a, b, c, d);
            if (rigid_body_modes(bm) > 0) continue;
            for (const auto& loads : patterns(R)) {
              const double e = error_vs_assembled(bm, loads, StaticMethod::EigenfunctionExpansion);
              if (!(e <= worst)) worst = e;
              BOOST_TEST(e <= 1e-10, "R=" << R << " springs " << a << " " << b << " " << c << " " << d << ": " << e);
            }
          }
  BOOST_TEST_MESSAGE("worst relative error " << worst);
}

// The two closed forms against each other (same model, different routes).
BOOST_AUTO_TEST_CASE(two_routes_agree) {
  for (long R : {3L, 10L, 64L}) {
    const RegularBeam bm = beam(R, 40.0, 5.0, 10.0, 0.0);
    for (const auto& loads : patterns(R)) {
      const StaticSolution a = solve_static(bm, loads, StaticMethod::PiecewiseCubic);
      const StaticSolution b = solve_static(bm, loads, StaticMethod::EigenfunctionExpansion);
      double e = 0, s = 0;
      for (long r = 0; r <= R; ++r) {
        e = std::max(e, std::abs(a.w[r] - b.w[r]));
        s = std::max(s, std::abs(a.w[r]));
      }
      BOOST_TEST(e <= 1e-11 * s);
      for (int i = 0; i < 4; ++i)
        BOOST_TEST(std::abs(a.reactions[i] - b.reactions[i]) <= 1e-10 * (1.0 + std::abs(a.reactions[i])));
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(exact_continuous)

// For nodal loads the nodal values of the Hermite model are those of the continuous beam:
// exact::beam_static (Euler-Bernoulli: kGA = inf, rhoI = 0) at every loaded node and a few
// others, supports from clamped to soft springs. Moments enter exact with moment_sign = +1
// (our moment is conjugate to dw/dx, exact's theta = +phi). The probes are kept >= L/8 apart:
// exact::beam_static itself loses accuracy next to very short segments (a probe at L/1000 next
// to a load costs it ~1e-9 relative; see the report), which is not what is tested here.
BOOST_AUTO_TEST_CASE(nodal_values_equal_exact) {
  namespace ex = modalbench::exact;
  const ex::BeamBending bb{EI, kInf, 1.0, 0.0, L};
  struct Sup { double K0, Kr0, KL, KrL; };
  const Sup sups[] = {{kInf, kInf, 0, 0}, {kInf, 0, kInf, 0}, {kInf, kInf, kInf, kInf}, {40, 5, 10, 0},
                      {1e3, 0.5, 2.0, 7.0}, {kInf, 0, 3.0, 0}};
  for (long R : {4L, 12L, 96L, 1000L})
    for (const auto& s : sups) {
      const RegularBeam bm = beam(R, s.K0, s.Kr0, s.KL, s.KrL);
      const std::vector<NodalLoad> loads = {{R / 4, -1e3, 0.0}, {R / 2, -2e3, 300.0}, {3 * R / 4, 5e2, 0.0}};
      std::vector<ex::LineLoad> ll;
      for (const auto& l : loads) ll.push_back({static_cast<double>(l.node) * L / static_cast<double>(R), l.force, l.moment});
      std::vector<double> xs;
      std::vector<long> nodes = {0, R / 4, R / 2, 3 * R / 4, R};
      if (R % 8 == 0) nodes.insert(nodes.begin() + 1, {R / 8, 5 * R / 8});
      for (long n : nodes) xs.push_back(static_cast<double>(n) * L / static_cast<double>(R));
      const auto ref = ex::beam_static(bb, {bm.k0, bm.r0}, {bm.kL, bm.rL}, ll, xs, 1.0);
      const StaticSolution st = solve_static(bm, loads);
      double wmax = 0, tmax = 0;
      for (const auto& r : ref) {
        wmax = std::max(wmax, std::abs(r.w));
        tmax = std::max(tmax, std::abs(r.theta));
      }
      for (std::size_t i = 0; i < nodes.size(); ++i) {
        BOOST_TEST(std::abs(st.w[nodes[i]] - ref[i].w) <= 1e-10 * wmax, "R=" << R << " node " << nodes[i]);
        BOOST_TEST(std::abs(st.slope[nodes[i]] - ref[i].theta) <= 1e-10 * tmax, "R=" << R << " node " << nodes[i]);
      }
    }
}

// Between nodes the element is unloaded, so the Hermite interpolant of the nodal values is the
// exact continuous solution there too.
BOOST_AUTO_TEST_CASE(hermite_interpolation_between_nodes_is_exact) {
  namespace ex = modalbench::exact;
  const ex::BeamBending bb{EI, kInf, 1.0, 0.0, L};
  const long R = 6;
  const RegularBeam bm = beam(R, kInf, 0.0, 20.0, 0.0);
  const std::vector<NodalLoad> loads = {{2, -1e3, 0.0}, {5, 0.0, 400.0}};
  const std::vector<ex::LineLoad> ll = {{1.0, -1e3, 0.0}, {2.5, 0.0, 400.0}};
  const std::vector<double> xs = {0.1234, 0.77, 1.3, 2.2, 2.93};
  const auto ref = ex::beam_static(bb, {kInf, 0}, {bm.kL, 0}, ll, xs, 1.0);
  const StaticSolution st = solve_static(bm, loads);
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const auto v = interpolate(bm, st, xs[i]);
    BOOST_TEST(std::abs(v[0] - ref[i].w) <= 1e-10 * std::abs(ref[i].w) + 1e-18);
    BOOST_TEST(std::abs(v[1] - ref[i].theta) <= 1e-10 * std::abs(ref[i].theta) + 1e-18);
  }
}

// R = 1e6: the closed form keeps its accuracy (the assembled system has condition ~R^4 = 1e24,
// so a double-precision factorisation would not), checked against the continuous beam.
BOOST_AUTO_TEST_CASE(million_elements_against_exact) {
  namespace ex = modalbench::exact;
  const ex::BeamBending bb{EI, kInf, 1.0, 0.0, L};
  const long R = 1'000'000;
  const RegularBeam bm = beam(R, kInf, 0.0, 10.0, 3.0);
  const std::vector<NodalLoad> loads = {{R / 4, -1e3, 0.0}, {R / 2, -2e3, 0.0}, {3 * R / 4, 5e2, 0.0}};
  const std::vector<ex::LineLoad> ll = {{0.75, -1e3, 0.0}, {1.5, -2e3, 0.0}, {2.25, 5e2, 0.0}};
  const std::vector<double> xs = {0.375, 1.5, 2.1, 3.0};
  const auto ref = ex::beam_static(bb, {kInf, 0}, {bm.kL, bm.rL}, ll, xs, 1.0);
  const StaticSolution st = solve_static(bm, loads);
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const long r = std::lround(xs[i] / L * R);
    BOOST_TEST(std::abs(st.w[r] - ref[i].w) <= 1e-10 * std::abs(ref[i].w));
  }
  BOOST_TEST(static_residual(bm, loads, st) < 1e-14);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(reactions_and_extremes)

// Support actions: force and moment equilibrium of the whole beam, and the spring or held-DOF
// reactions of the binary128 assembled solve (K u - f at held DOFs, -k u at springs).
BOOST_AUTO_TEST_CASE(reactions_equilibrium_and_assembled) {
  for (long R : {2L, 9L, 50L})
    for (double a : kSweep)
      for (double d : kSweep) {
        const RegularBeam bm = beam(R, a, 3.0, kInf, d);
        const auto loads = patterns(R)[1];
        const StaticSolution st = solve_static(bm, loads);
        double F = st.reactions[0] + st.reactions[2], M = st.reactions[1] + st.reactions[3] + st.reactions[2] * L;
        double scale = 0;
        for (const auto& l : loads) {
          const double x = static_cast<double>(l.node) * L / static_cast<double>(R);
          F += l.force;
          M += l.moment + l.force * x;  // moments about x = 0, conjugate to the slope (w up, x right)
          scale += std::abs(l.force) * L + std::abs(l.moment);
        }
        BOOST_TEST(std::abs(F) * L <= 1e-12 * scale);
        BOOST_TEST(std::abs(M) <= 1e-12 * scale);
        // Held DOF at x = L (translation): reaction of the assembled system.
        std::vector<quad> wq, sq;
        assembled::static_solve<quad>(bm, loads, wq, sq);
        const double ad = L / static_cast<double>(R);
        const quad a3 = quad(ad) * quad(ad) * quad(ad);
        const quad ke = quad(EI) / a3, aq = quad(ad);
        quad ku = ke * (quad(-12) * wq[R - 1] - quad(6) * aq * sq[R - 1] + quad(12) * wq[R] - quad(6) * aq * sq[R]);
        for (const auto& l : loads)
          if (l.node == R) ku -= quad(l.force);
        BOOST_TEST(std::abs(st.reactions[2] - static_cast<double>(ku)) <= 1e-10 * scale / L);
      }
}

// Near-mechanism: large but correct deflections, said as such (information: no warning, the
// closed form keeps its digits).
BOOST_AUTO_TEST_CASE(near_mechanism_warns_and_is_accurate) {
  const RegularBeam bm = beam(20, 1e-6, 1e-6, 1e-6, 1e-6);
  const auto loads = patterns(20)[1];
  const StaticSolution st = solve_static(bm, loads);
  BOOST_TEST(st.support_flexibility > kNearMechanismFlexibility);
  BOOST_TEST(st.near_mechanism);
  BOOST_TEST(st.warnings.empty());
  BOOST_TEST(error_vs_assembled(bm, loads, StaticMethod::PiecewiseCubic) <= 1e-10);
  // A well supported beam is not one.
  const StaticSolution held = solve_static(beam(20, kInf, 0, kInf, 0), loads);
  BOOST_TEST(!held.near_mechanism);
  BOOST_TEST(held.warnings.empty());
}

// A true mechanism has no static solution: refused with a message naming the free motion.
BOOST_AUTO_TEST_CASE(mechanism_is_refused) {
  const auto loads = patterns(10)[0];
  for (const auto& bm : {beam(10, 0, 0, 0, 0), beam(10, kInf, 0, 0, 0), beam(10, 0, 5.0, 0, kInf), beam(10, 1.0, 0, 0, 0)}) {
    BOOST_CHECK_EXCEPTION(solve_static(bm, loads), Mechanism, [](const Mechanism& e) {
      return std::string(e.what()).find("mechanism") != std::string::npos;
    });
  }
  BOOST_CHECK_THROW(solve_static(beam(10, kInf, kInf, 0, 0), {{11, 1.0, 0.0}}), std::invalid_argument);
}

// The relative residual of the assembled equations is at rounding level.
BOOST_AUTO_TEST_CASE(assembled_residual_is_rounding) {
  for (long R : {1L, 7L, 333L, 20000L}) {
    const RegularBeam bm = beam(R, 40.0, 5.0, 10.0, 0.0);
    const auto loads = patterns(R)[1];
    BOOST_TEST(static_residual(bm, loads, solve_static(bm, loads)) < 1e-14);
  }
}

BOOST_AUTO_TEST_SUITE_END()
