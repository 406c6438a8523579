// Spinning shafts ([rotor]) against closed forms written out here, independently of the code:
//   - a pinned-pinned Timoshenko shaft: per mode n (k = n pi / L, w = W sin kx, psi = Psi cos kx)
//     (rho A w^2 - kGA k^2)(J(w) - EI k^2 - kGA) - (kGA k)^2 = 0, J(w) = rho I w^2 - s rho I_p Omega w,
//     s = +1 forward, -1 backward; critical speeds with Omega = w;
//   - a Jeffcott rotor: a disc at the middle of a pinned-pinned shaft of negligible mass: translation
//     sqrt(48 EI / (m L^3)) at every spin, tilt J_t w^2 -+ J_p Omega w - 12 EI / L = 0;
//   - an asymmetric Euler-Bernoulli shaft in its rotating frame, per pinned mode:
//     (lambda^2 + w_1^2 - Omega^2)(lambda^2 + w_2^2 - Omega^2) + 4 Omega^2 lambda^2 = 0, unstable
//     (a real root) for Omega between w_1 and w_2;
//   - a symmetric shaft seen from its rotating frame: the stationary frame's forward whirl at
//     w_F - Omega, the backward at w_B + Omega (a missing factor 2 in the Coriolis terms breaks it).
// exact is held to 1e-9 (its roots are bracketed to 1e-13); dtfm's one-prism line (the shaft's own
// theory, its roots polished to 1e-11 in omega^2) to 1e-8; rfem and difference_eq (the appendix's A3
// chain, Euler-Bernoulli) to their own error estimates.
#define BOOST_TEST_MODULE rotor
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "solver_tests.hpp"
#include "solve_options.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

constexpr double kPi = 3.14159265358979323846;

Result solve(const std::string& backend, const Scene& s) {
  const Solver& b = registry().get(backend);
  Result r = b.solve(s, testing::default_mesh(b, s), Options{});
  BOOST_TEST_INFO(backend << ": " << r.summary.message);
  BOOST_TEST(r.ok());
  BOOST_TEST_REQUIRE(r.campbell.points.size() == s.rotor->spin.size());
  return r;
}

/// The tolerance a back-end's Campbell frequencies are held to: exact 1e-9; dtfm's one prism (no
/// discretization: the count's polish, 1e-11 in omega^2, and the rounding of the segment matrices,
/// whose stiffness grows like 1/h^3 against the mass's h) 1e-8; a mesh its estimate.
double allowed(const std::string& backend, const Result& r) {
  return backend == "exact" ? 1e-9 : backend == "dtfm" ? 1e-8 : r.summary.error_estimate.campbell;
}

// ---- the pinned Timoshenko shaft (scenes/rotor_timoshenko_shaft.toml)

struct Shaft {
  double E = 2.1e11, nu = 0.3, rho = 7850.0, d = 0.1, L = 1.0;
  double G() const { return E / (2 * (1 + nu)); }
  double A() const { return kPi * d * d / 4; }
  double I() const { return kPi * std::pow(d, 4) / 64; }
  double kGA() const { return 6 * (1 + nu) / (7 + 6 * nu) * G() * A(); }  // Cowper's circle
  /// The characteristic function of mode n at whirl w, spin Omega, sense s.
  double f(double w, int n, int s, double spin) const {
    const double k = n * kPi / L, J = rho * I() * w * w - s * rho * 2 * I() * spin * w;
    return (rho * A() * w * w - kGA() * k * k) * (J - E * I() * k * k - kGA()) - std::pow(kGA() * k, 2);
  }
  /// The lowest root of f in w, by bisection from 0 (f(0) > 0 and it changes sign once below the
  /// shear branch).
  double root(int n, int s, double spin, bool synchronous = false) const {
    auto g = [&](double w) { return f(w, n, s, synchronous ? w : spin); };
    double lo = 1.0, hi = 1.0;
    while (g(hi) * g(lo) > 0) hi *= 1.1;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (g(mid) * g(lo) > 0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(a_pinned_timoshenko_shaft_whirls_and_goes_critical_as_its_closed_form) {
  const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/rotor_timoshenko_shaft.toml");
  const Shaft sh;
  for (const std::string backend : {"exact", "dtfm", "rfem"}) {
    const Result r = solve(backend, s);
    const double tol = allowed(backend, r);
    BOOST_TEST_INFO(backend);
    BOOST_TEST(tol <= s.request.tolerance);
    for (const CampbellPoint& p : r.campbell.points) {
      // Modes 1 and 2, each backward then forward (the backward whirl lies lower).
      const std::vector<double> ref = {sh.root(1, -1, p.spin_rad_s), sh.root(1, +1, p.spin_rad_s),
                                       sh.root(2, -1, p.spin_rad_s), sh.root(2, +1, p.spin_rad_s)};
      BOOST_TEST_REQUIRE(p.frequencies_rad_s.size() == 4u);
      for (std::size_t i = 0; i < 4; ++i) {
        BOOST_TEST_INFO(backend << " spin " << p.spin_rad_s << " root " << i);
        BOOST_TEST(rel(p.frequencies_rad_s[i], ref[i]) <= tol);
        BOOST_TEST(p.growth_rates_1_s[i] == 0.0);
        if (p.spin_rad_s > 0) BOOST_TEST((p.whirl[i] == (i % 2 == 0 ? Whirl::Backward : Whirl::Forward)));
      }
    }
    // Every critical speed up to the highest spin (3000 rad/s) and the next above: modes 1 and 2.
    BOOST_TEST_REQUIRE(r.campbell.forward_criticals.size() == 2u);
    BOOST_TEST_REQUIRE(r.campbell.backward_criticals.size() == 2u);
    for (int n = 1; n <= 2; ++n) {
      BOOST_TEST(rel(r.campbell.forward_criticals[n - 1], sh.root(n, +1, 0, true)) <= tol);
      BOOST_TEST(rel(r.campbell.backward_criticals[n - 1], sh.root(n, -1, 0, true)) <= tol);
    }
  }
}

BOOST_AUTO_TEST_CASE(a_symmetric_shaft_seen_from_its_own_frame_whirls_at_the_stationary_frequencies_shifted_by_the_spin) {
  Scene st = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/rotor_timoshenko_shaft.toml");
  st.rotor->spin = {0.0, 700.0, 2500.0};
  Scene ro = st;
  ro.rotor->frame = Rotor::Frame::Rotating;
  for (const std::string backend : {"exact", "dtfm", "rfem", "difference_eq"}) {
    const Solver& b = registry().get(backend);
    const Discretization mesh = backend == "exact"  ? Discretization{}
                                : backend == "dtfm" ? Discretization::parse("1x1")
                                                    : Discretization{{64}};
    Options o;
    o.estimate_error = false;  // one mesh: the identity holds for the discrete model as it stands
    const Result a = b.solve(st, mesh, o), c = b.solve(ro, mesh, o);
    BOOST_TEST_REQUIRE(a.ok());
    BOOST_TEST_REQUIRE(c.ok());
    for (std::size_t p = 0; p < st.rotor->spin.size(); ++p) {
      const double spin = st.rotor->spin[p];
      // The stationary roots, shifted: forward - spin (its sign is the rotating frame's sense).
      std::vector<double> shifted;
      const CampbellPoint& sp = a.campbell.points[p];
      for (std::size_t i = 0; i < sp.frequencies_rad_s.size(); ++i)
        shifted.push_back(std::abs(sp.frequencies_rad_s[i] + (sp.whirl[i] == Whirl::Forward ? -spin : spin)));
      std::sort(shifted.begin(), shifted.end());
      const CampbellPoint& rp = c.campbell.points[p];
      // The rotating frame's lowest roots are the lowest of the shifted ones (here the same set:
      // 2500 rad/s is below every forward frequency).
      for (std::size_t i = 0; i < rp.frequencies_rad_s.size(); ++i) {
        BOOST_TEST_INFO(backend << " spin " << spin << " root " << i);
        BOOST_TEST(std::abs(rp.frequencies_rad_s[i] - shifted[i]) <= 1e-9 * (shifted[i] + spin));
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(a_jeffcott_rotor_whirls_as_its_closed_form) {
  // A 0.5 m shaft of 20 mm diameter whose density is 1e-3 kg/m^3 (mass 1.6e-7 kg: 1.6e-8 of the
  // disc's, so the shaft shifts the frequencies by about that much) and a disc of 10 kg at its middle.
  const double E = 2.1e11, d = 0.02, L = 0.5, m = 10.0, Jp = 0.05, Jt = 0.03;
  const double EI = E * kPi * std::pow(d, 4) / 64;
  const std::string text = R"(
[scene]
name = "jeffcott"
kind = "beam"
physics = "lateral"
theory = "euler-bernoulli"
[geometry]
length = 0.5
section = { shape = "circle", diameter = 0.02 }
[material]
E = 2.1e11
nu = 0.3
rho = 1e-3
[supports]
x0 = "pinned"
xL = "pinned"
[[masses]]
x = 0.25
mass = 10.0
Jx = 0.05
Jy = 0.03
Jz = 0.03
[rotor]
spin = [0.0, 500.0, 2000.0]
[request]
modes = 4
)";
  const Scene s = parse_scene(text, "jeffcott.toml");
  const double wt = std::sqrt(48 * EI / (m * L * L * L)), kr = 12 * EI / L;
  for (const std::string backend : {"exact", "dtfm", "rfem"}) {
    const Result r = solve(backend, s);
    const double tol = std::max(allowed(backend, r), 1e-7);
    for (const CampbellPoint& p : r.campbell.points) {
      const double O = p.spin_rad_s, disc = std::sqrt(Jp * Jp * O * O + 4 * Jt * kr);
      std::vector<double> ref = {wt, wt, (Jp * O + disc) / (2 * Jt), (-Jp * O + disc) / (2 * Jt)};
      std::sort(ref.begin(), ref.end());
      BOOST_TEST_REQUIRE(p.frequencies_rad_s.size() == 4u);
      for (std::size_t i = 0; i < 4; ++i) {
        BOOST_TEST_INFO(backend << " spin " << O << " root " << i);
        BOOST_TEST(rel(p.frequencies_rad_s[i], ref[i]) <= tol);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(an_asymmetric_shaft_in_its_rotating_frame_is_unstable_between_its_two_frequencies) {
  const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/rotor_asymmetric_shaft.toml");
  const double E = 2.1e11, rho = 7850.0, L = 1.2, b = 0.04, h = 0.05, A = b * h;
  const double Iy = b * h * h * h / 12, Iz = h * b * b * b / 12;
  auto plane = [&](int n, double I) { return std::pow(n * kPi / L, 2) * std::sqrt(E * I / (rho * A)); };
  for (const std::string backend : {"exact", "rfem", "difference_eq"}) {
    const Solver& bk = registry().get(backend);
    const Result r = bk.solve(s, testing::default_mesh(bk, s), Options{});
    BOOST_TEST_INFO(backend << ": " << r.summary.message);
    BOOST_TEST(r.ok());
    const double tol = allowed(backend, r);
    for (const CampbellPoint& p : r.campbell.points) {
      const double O2 = p.spin_rad_s * p.spin_rad_s;
      struct Ref { double omega, growth; };
      std::vector<Ref> ref;
      for (int n = 1; n <= 4; ++n) {
        const double a = std::pow(plane(n, Iy), 2) - O2, c = std::pow(plane(n, Iz), 2) - O2, q = a + c + 4 * O2;
        const std::complex<double> disc = std::sqrt(std::complex<double>(q * q - 4 * a * c));
        for (const auto x : {(q + disc) / 2.0, (q - disc) / 2.0}) {
          const std::complex<double> l = std::sqrt(-x);
          ref.push_back({std::abs(l.imag()), std::abs(l.real())});
        }
      }
      std::sort(ref.begin(), ref.end(), [](const Ref& x, const Ref& y) { return x.omega < y.omega; });
      const bool unstable = p.spin_rad_s > plane(1, Iz) && p.spin_rad_s < plane(1, Iy);
      BOOST_TEST((std::find(r.campbell.unstable_spins.begin(), r.campbell.unstable_spins.end(), p.spin_rad_s) !=
                  r.campbell.unstable_spins.end()) == unstable);
      for (std::size_t i = 0; i < p.frequencies_rad_s.size(); ++i) {
        BOOST_TEST_INFO(backend << " spin " << p.spin_rad_s << " root " << i);
        const double scale = ref[i].omega + p.spin_rad_s;
        BOOST_TEST(std::abs(p.frequencies_rad_s[i] - ref[i].omega) <= tol * scale);
        BOOST_TEST(std::abs(p.growth_rates_1_s[i] - ref[i].growth) <= tol * scale);
      }
    }
    // Forward critical speeds: the planes' frequencies (the ends of the unstable ranges).
    BOOST_TEST_REQUIRE(r.campbell.forward_criticals.size() >= 2u);
    BOOST_TEST(rel(r.campbell.forward_criticals[0], plane(1, Iz)) <= tol);
    BOOST_TEST(rel(r.campbell.forward_criticals[1], plane(1, Iy)) <= tol);
  }
}

BOOST_AUTO_TEST_CASE(rotor_scenes_refuse_what_they_cannot_mean) {
  const std::string head = R"(
[scene]
name = "r"
kind = "beam"
physics = "lateral"
theory = "timoshenko"
[geometry]
length = 1.0
width = 0.04
height = 0.05
[material]
E = 2.1e11
nu = 0.3
rho = 7850.0
[supports]
x0 = "pinned"
xL = "pinned"
[request]
modes = 2
)";
  expect_input_error(head + "[rotor]\nspin = [0.0, 100.0]\n", "rotor.frame", "periodic in time");
  expect_input_error(head + "[rotor]\nspin = [100.0, 0.0]\nframe = \"rotating\"\n", "rotor.spin[1]", "ascending");
  expect_input_error(head + "[rotor]\nspin = [-1.0]\nframe = \"rotating\"\n", "rotor.spin[0]", ">= 0");
  expect_input_error(head + "[rotor]\nspin = [1.0]\nframe = \"spinning\"\n", "rotor.frame", "unknown frame");
  expect_input_error(head + "[rotor]\nspin = { from = 0.0, to = 10.0 }\nframe = \"rotating\"\n", "rotor.spin.num", "missing");
  expect_input_error(head + "[rotor]\nframe = \"rotating\"\n", "rotor.spin", "missing");
  std::string bending = head;
  bending.replace(bending.find("lateral"), 7, "bending");
  expect_input_error(bending + "[rotor]\nspin = [1.0]\n", "rotor", "physics 'lateral'");
  expect_input_error(head + "[[loads]]\nx = 0.5\nFx = 1.0\n[rotor]\nspin = [1.0]\nframe = \"rotating\"\n", "loads[0].Fx",
                     "unknown key");
  // Timoshenko theory, asymmetric section, rotating frame: rfem refuses (one diametral inertia per
  // element), naming why; exact refuses an asymmetric Timoshenko shaft too.
  const Scene s = parse_scene(head + "[rotor]\nspin = [0.0, 100.0]\nframe = \"rotating\"\n", "r.toml");
  // What a back-end cannot give is said: refused outright, or the rest computed and a warning
  // naming the Campbell diagram and why. (difference_eq solves its own model, the Euler-Bernoulli
  // chain, and says so; with a lumped mass it refuses the rotating frame, whose A3 matrices are the
  // consistent mass's.)
  for (const std::string backend : {"exact", "rfem", "dtfm"}) {
    const Solver& b = registry().get(backend);
    const Result r = b.solve(s, testing::default_mesh(b, s), Options{});
    BOOST_TEST_INFO(backend << ": " << r.summary.message);
    BOOST_TEST(r.campbell.empty());
    const bool said = std::any_of(r.summary.warnings.begin(), r.summary.warnings.end(), [](const std::string& w) {
      return w.find("not computed: ") != std::string::npos && w.find("Campbell") != std::string::npos;
    });
    BOOST_TEST((r.summary.status == Status::Unsupported || said));
  }
  const Solver& de = registry().get("difference_eq");
  const Result chain = de.solve(s, testing::default_mesh(de, s), Options{});
  BOOST_TEST(!chain.campbell.empty());
  BOOST_TEST(!chain.summary.converges_to_scene_theory);
  Options lumped;
  lumped.mass = MassModel::Lumped;
  const Result l = de.solve(s, testing::default_mesh(de, s), lumped);
  BOOST_TEST(l.campbell.empty());
  BOOST_TEST((l.summary.status == Status::Unsupported), l.summary.message);
}

BOOST_AUTO_TEST_CASE(rfem_dtfm_and_exact_agree_on_friswell_s_two_disc_rotor) {
  // Friswell et al. Example 5.9.1 (scenes/rotor_friswell_two_discs.toml): no closed form; exact
  // (per whirl direction, counted on its transfer matrices) is the second method for rfem (within
  // its estimate) and for dtfm (its prism line's segment dynamic stiffness, the same Timoshenko
  // shaft: within 1e-8), root by root, sense by sense, critical speed by critical speed, across 0
  // to 4000 rev/min.
  const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/rotor_friswell_two_discs.toml");
  const Result e = solve("exact", s);
  for (const std::string backend : {"rfem", "dtfm"}) {
    const Result r = solve(backend, s);
    const double tol = allowed(backend, r);
    BOOST_TEST_INFO(backend);
    BOOST_TEST(tol <= s.request.tolerance);
    for (std::size_t p = 0; p < s.rotor->spin.size(); ++p) {
      const CampbellPoint &a = r.campbell.points[p], &b = e.campbell.points[p];
      BOOST_TEST_REQUIRE(a.frequencies_rad_s.size() == b.frequencies_rad_s.size());
      for (std::size_t i = 0; i < a.frequencies_rad_s.size(); ++i) {
        BOOST_TEST_INFO("spin " << a.spin_rad_s << " root " << i);
        BOOST_TEST(std::abs(a.frequencies_rad_s[i] - b.frequencies_rad_s[i]) <= tol * (b.frequencies_rad_s[i] + a.spin_rad_s));
        if (a.spin_rad_s > 0) BOOST_TEST((a.whirl[i] == b.whirl[i]));
      }
    }
    for (const auto& [x, y] : {std::pair{&r.campbell.forward_criticals, &e.campbell.forward_criticals},
                               std::pair{&r.campbell.backward_criticals, &e.campbell.backward_criticals}}) {
      BOOST_TEST_REQUIRE(x->size() == y->size());
      for (std::size_t i = 0; i < x->size(); ++i) BOOST_TEST(rel((*x)[i], (*y)[i]) <= tol);
    }
  }
}

BOOST_AUTO_TEST_CASE(the_lateral_model_at_rest_bends_in_both_planes_as_the_closed_forms) {
  // The asymmetric shaft without spin, loaded across in both planes: pinned-pinned frequencies
  // (n pi / L)^2 sqrt(EI / rho A) per plane (EI_z for v, EI_y for w), the point load's deflection
  // P b x (L^2 - b^2 - x^2) / (6 L EI) left of it (mirrored right of it), and reactions that balance
  // the loads. exact and dtfm's one prism (the Euler-Bernoulli beam itself) to 1e-8.
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/rotor_asymmetric_shaft.toml");
  s.rotor.reset();
  const double E = 2.1e11, rho = 7850.0, L = 1.2, b = 0.04, h = 0.05, A = b * h;
  const double Iy = b * h * h * h / 12, Iz = h * b * b * b / 12;
  PointLoad fy, fz;
  fy.x = 0.4;
  fy.Fy = 1000.0;
  fz.x = 0.7;
  fz.Fz = -2000.0;
  s.loads = {fy, fz};
  s.request.modes = 6;
  s.request.probes = {{0.3, 0.0}, {0.9, 0.0}};
  auto deflection = [&](double P, double a, double EI, double x) {
    if (x > a) return P * a * (L - x) * (L * L - a * a - (L - x) * (L - x)) / (6 * L * EI);
    const double bb = L - a;
    return P * bb * x * (L * L - bb * bb - x * x) / (6 * L * EI);
  };
  std::vector<double> ref;
  for (int n = 1; n <= 6; ++n)
    for (double I : {Iy, Iz}) ref.push_back(std::pow(n * kPi / L, 2) * std::sqrt(E * I / (rho * A)));
  std::sort(ref.begin(), ref.end());
  for (const std::string backend : {"exact", "dtfm"}) {
    const Solver& bk = registry().get(backend);
    const Result r = bk.solve(s, testing::default_mesh(bk, s), Options{});
    BOOST_TEST_INFO(backend << ": " << r.summary.message);
    BOOST_TEST(r.ok());
    BOOST_TEST_REQUIRE(r.frequencies_rad_s.size() == 6u);
    for (std::size_t i = 0; i < 6; ++i) BOOST_TEST(rel(r.frequencies_rad_s[i], ref[i]) <= 1e-8);
    BOOST_TEST_REQUIRE(r.deflections.size() == 2u);
    const double scale = std::abs(deflection(fz.Fz, fz.x, E * Iy, fz.x));
    for (const Deflection& d : r.deflections) {
      const double x = d.position[0];
      BOOST_TEST_INFO(backend << " x " << x);
      BOOST_TEST(std::abs(d.v - deflection(fy.Fy, fy.x, E * Iz, x)) <= 1e-8 * scale);
      BOOST_TEST(std::abs(d.w - deflection(fz.Fz, fz.x, E * Iy, x)) <= 1e-8 * scale);
      BOOST_TEST(d.u == 0.0);
      BOOST_TEST(d.theta_x == 0.0);
    }
    double Ry = 0, Rz = 0;
    for (const Reaction& re : r.reactions) {
      Ry += re.force[1];
      Rz += re.force[2];
    }
    BOOST_TEST(std::abs(Ry + fy.Fy) <= 1e-9 * 3000.0);
    BOOST_TEST(std::abs(Rz + fz.Fz) <= 1e-9 * 3000.0);
  }
}

BOOST_AUTO_TEST_CASE(dtfm_and_exact_agree_on_a_stepped_rotor_with_a_disc) {
  // scenes/stepped_shaft_disc.toml as a rotor: three Timoshenko pieces (40, 60, 40 mm) on radial
  // springs, a disc at the middle, spun to 3000 rad/s in both frames. exact (transfer matrices,
  // a node at each step) and dtfm (the prism line's segment dynamic stiffness per piece) solve
  // the same shaft by different methods: within 1e-8, root by root, sense by sense.
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/stepped_shaft_disc.toml");
  s.physics = Physics::Lateral;
  for (Support* e : {&s.x0, &s.xL}) e->axial = e->torsional = 0.0;
  s.gravity.reset();
  s.request.probes.clear();
  s.request.modes = 6;
  s.rotor = Rotor{};
  s.rotor->spin = {0.0, 1000.0, 3000.0};
  for (const auto frame : {Rotor::Frame::Stationary, Rotor::Frame::Rotating}) {
    s.rotor->frame = frame;
    const Result e = solve("exact", s), d = solve("dtfm", s);
    for (std::size_t p = 0; p < s.rotor->spin.size(); ++p) {
      const CampbellPoint &a = d.campbell.points[p], &b = e.campbell.points[p];
      BOOST_TEST_REQUIRE(a.frequencies_rad_s.size() == b.frequencies_rad_s.size());
      for (std::size_t i = 0; i < a.frequencies_rad_s.size(); ++i) {
        BOOST_TEST_INFO(to_string(frame) << " spin " << a.spin_rad_s << " root " << i);
        BOOST_TEST(std::abs(a.frequencies_rad_s[i] - b.frequencies_rad_s[i]) <= 1e-8 * (b.frequencies_rad_s[i] + a.spin_rad_s));
        if (a.spin_rad_s > 0) BOOST_TEST((a.whirl[i] == b.whirl[i]));
      }
    }
    for (const auto& [x, y] : {std::pair{&d.campbell.forward_criticals, &e.campbell.forward_criticals},
                               std::pair{&d.campbell.backward_criticals, &e.campbell.backward_criticals}}) {
      BOOST_TEST_REQUIRE(x->size() == y->size());
      for (std::size_t i = 0; i < x->size(); ++i) BOOST_TEST(rel((*x)[i], (*y)[i]) <= 1e-8);
    }
  }
}

BOOST_AUTO_TEST_CASE(whirl_orbits_are_circles_of_the_closed_form_shapes) {
  // The pinned Timoshenko shaft with [request.shapes] at 9 points: root (mode n, sense s) is the
  // circle v = sin(n pi x / L) (normalized: |v|^2 + |w|^2 = 1 at its largest), w = -i v forward, +i v backward
  // (turning from +y towards +z is forward). exact and dtfm to 1e-8; rfem's orbit is its rigid
  // elements' v, w, linear between their centres: within the interpolation's h^2 / 8 |v''| plus
  // ten times its frequency estimate.
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/rotor_timoshenko_shaft.toml");
  s.rotor->spin = {0.0, 1000.0, 3000.0};
  s.request.shapes = ShapeRequest{};
  s.request.shapes->nx = 9;
  const double L = s.geometry.length;
  for (const std::string backend : {"exact", "dtfm", "rfem"}) {
    const Result r = solve(backend, s);
    BOOST_TEST_REQUIRE(r.campbell.orbit_points_m.size() == 9u);
    const double h = backend == "rfem" ? L / std::stod(r.summary.mesh) : 0.0;
    for (const CampbellPoint& p : r.campbell.points) {
      BOOST_TEST_REQUIRE(p.orbits.size() == p.frequencies_rad_s.size());
      for (std::size_t i = 0; i < p.orbits.size(); ++i) {
        const int n = static_cast<int>(i / 2) + 1;
        const double k = n * kPi / L;
        const double tol = backend == "rfem" ? h * h / 8 * k * k + 10 * allowed(backend, r) : 1e-8;
        const std::complex<double> turn(0.0, p.whirl[i] == Whirl::Forward ? -1.0 : 1.0);
        // The largest of |sin| over the points (n = 1: at L / 2; n = 2: at L / 4 and 3 L / 4).
        double top = 0;
        for (double x : r.campbell.orbit_points_m) top = std::max(top, std::abs(std::sin(k * x)));
        // The normalization makes v real and positive where the orbit is largest: of two points
        // alike (n = 2), either; the reference takes the sign v has at the first.
        const Orbit& o = p.orbits[i];
        double sign = 1;
        for (std::size_t j = 0; j < 9; ++j)
          if (std::abs(std::abs(std::sin(k * r.campbell.orbit_points_m[j])) - top) <= 1e-12) {
            sign = o.v[j].real() >= 0 ? 1 : -1;
            break;
          }
        for (std::size_t j = 0; j < 9; ++j) {
          const double ref = sign * std::sin(k * r.campbell.orbit_points_m[j]) / top / std::sqrt(2.0);
          BOOST_TEST_INFO(backend << " spin " << p.spin_rad_s << " root " << i << " point " << j);
          // At spin 0 the pair's basis is any two circles: |v| and |v| = |w| only.
          if (p.spin_rad_s == 0) {
            BOOST_TEST(std::abs(std::abs(o.v[j]) - std::abs(ref)) <= tol);
            BOOST_TEST(std::abs(std::abs(o.w[j]) - std::abs(o.v[j])) <= tol);
            continue;
          }
          BOOST_TEST(std::abs(o.v[j] - ref) <= tol);
          BOOST_TEST(std::abs(o.w[j] - turn * o.v[j]) <= tol);
        }
      }
    }
  }
}
