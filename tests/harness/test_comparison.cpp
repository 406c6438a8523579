// Time per quantity, the two errors (discretization against a run's own limit, model error of
// that limit) and the grid convergence index, on manufactured back-ends whose answers are known
// in closed form.
#define BOOST_TEST_MODULE comparison
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <map>

#include "modalbench/exact/exact.hpp"
#include "modalbench/harness/comparison.hpp"
#include "fake_kernels.hpp"

using namespace modalbench;
namespace tt = boost::test_tools;

namespace {

Scene beam_scene() { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml"); }

/// A clock that only the fake back-end below advances: timings become exact numbers.
double fake_now = 0;

/// Known phase costs: build 10 ms on every solve; modes 20 ms, statics 5 ms, FRF 40 ms when asked.
class Phased final : public Solver {
 public:
  std::string name() const override { return "phased"; }
  std::string description() const override { return "known phase costs"; }
  Capability supports(const Scene&) const override { return {true, true, true, ""}; }
  MeshFamily meshes(const Scene&, const Options&) const override { return MeshFamily::single(Discretization::parse("4")); }

 protected:
  std::unique_ptr<Kernels> build(const Scene& s, const Discretization&, const Options&, Result&) const override {
    fake_now += 0.010;
    return std::make_unique<testing::FakeKernels>(
        [&s](Result& r) {
          fake_now += 0.020;
          r.frequencies_rad_s.assign(static_cast<std::size_t>(s.request.modes), 1.0);
          r.mode_families.assign(static_cast<std::size_t>(s.request.modes), ModeFamily::BendingXZ);
        },
        [&s](Result& r) {
          fake_now += 0.005;
          r.deflections.resize(s.request.probes.size());
        },
        [](Result& r) {
          fake_now += 0.040;
          r.frf.push_back({1.0, {1.0, 0.0}});
        });
  }
};

/// Exact frequencies times `scale` (1 + 0.5 i / n^2 + d i / n^4) on meshes 4, 8, 16, 32: a
/// second-order method whose model is the scene's theory (scale 1) or another model (scale != 1).
/// With a stated next order (`next`), it offers the coarser meshes and the error expansion a
/// back-end states for its extrapolation; `ms_per_n`: what a rung costs on the fake clock.
class Scaled final : public Solver {
 public:
  Scaled(std::string name, double scale, bool theory, double d = 0, double next = kNaN, double ms_per_n = 0)
      : name_(std::move(name)), scale_(scale), theory_(theory), d_(d), next_(next), ms_per_n_(ms_per_n) {}
  std::string name() const override { return name_; }
  std::string description() const override { return "exact * scale * (1 + c/n^2 + d/n^4)"; }
  Capability supports(const Scene&) const override { return {true, false, false, ""}; }
  MeshFamily meshes(const Scene&, const Options&) const override {
    MeshFamily f = MeshFamily::single(Discretization::parse("4"));
    f.ladder = {Discretization::parse("4"), Discretization::parse("8"), Discretization::parse("16"), Discretization::parse("32")};
    f.stress = {f.ladder.back()};
    const double next = next_;
    f.coarser = [next](const Discretization& mesh) -> std::optional<CoarserMesh> {
      if (std::isnan(next) || mesh.counts.at(0) < 2) return std::nullopt;
      return CoarserMesh{{{mesh.counts[0] / 2}}, 2.0, 2.0, next};
    };
    return f;
  }

 protected:
  std::unique_ptr<Kernels> build(const Scene& s, const Discretization& mesh, const Options& o, Result&) const override {
    return testing::modes_kernel([this, &s, mesh, &o](Result& r) { fill(s, mesh, o, r); });
  }

 private:
  void fill(const Scene& s, const Discretization& mesh, const Options& o, Result& r) const {
    Scene modes_only = s;
    modes_only.request.probes.clear();
    modes_only.request.frf.reset();
    const Result x = exact::ExactSolver().solve(modes_only, {}, o);
    const double n = mesh.counts.at(0);
    for (std::size_t i = 0; i < x.frequencies_rad_s.size(); ++i) {
      const double c = static_cast<double>(i + 1);
      r.frequencies_rad_s.push_back(x.frequencies_rad_s[i] * scale_ * (1 + 0.5 * c / (n * n) + d_ * c / std::pow(n, 4)));
      r.mode_families.push_back(x.mode_families[i]);
    }
    r.summary.unknowns = static_cast<long>(2 * n);
    r.summary.converges_to_scene_theory = theory_;
    fake_now += 0.001 * ms_per_n_ * n;
  }

  std::string name_;
  double scale_;
  bool theory_;
  double d_, next_, ms_per_n_;
};

const ModelLimit& limit_of(const SceneComparison& c, const std::string& label) {
  for (const auto& l : c.limits)
    if (l.label == label) return l;
  throw std::runtime_error("no limit " + label);
}

}  // namespace

// Each quantity is timed alone, charged with the build it needs: modes 10 + 20 ms, statics
// 10 + 5 ms, FRF 10 + 40 ms -- not the 85 ms of the whole solve.
BOOST_AUTO_TEST_CASE(time_per_quantity_charges_shared_setup_to_each) {
  Registry reg;
  reg.add(std::make_unique<Phased>());
  CompareOptions opt;
  opt.clock = [] { return fake_now; };
  opt.shapes = false;
  const auto all = run_comparison({beam_scene()}, reg, opt);
  BOOST_REQUIRE(all.size() == 1u);
  BOOST_REQUIRE(all[0].runs.size() == 1u);
  const RunRecord& r = all[0].runs[0];
  BOOST_TEST(r.time_s.modes == 0.030, tt::tolerance(1e-9));
  BOOST_TEST(r.time_s.statics == 0.015, tt::tolerance(1e-9));
  BOOST_TEST(r.time_s.frf == 0.050, tt::tolerance(1e-9));
  BOOST_TEST(r.median_s == 0.095, tt::tolerance(1e-9));
  BOOST_TEST(r.repeats >= 3);
  // What the harness spent: the untimed warm-up (85 ms) and every timed repeat.
  BOOST_TEST(r.spent_s >= 0.085 + 3 * 0.095 - 1e-9);
}

// f = f0 + C h^p on four meshes: the order and the limit come back, the fourth mesh confirms
// the order (safety factor 1.25) and the GCI is 1.25 |f_fine - f0| / |f_fine|.
BOOST_AUTO_TEST_CASE(gci_recovers_orders_2_and_4) {
  for (double p : {2.0, 4.0}) {
    std::vector<double> h = {1.0 / 4, 1.0 / 8, 1.0 / 16, 1.0 / 32}, f;
    for (double x : h) f.push_back(10.0 + 3.0 * std::pow(x, p));
    const GridConvergence g = grid_convergence(h, f);
    BOOST_TEST(g.ok);
    BOOST_TEST(g.order == p, tt::tolerance(1e-6));
    BOOST_TEST(g.value == 10.0, tt::tolerance(1e-10));
    BOOST_TEST(g.asymptotic);
    BOOST_TEST(g.safety_factor == 1.25);
    BOOST_TEST(g.gci == 1.25 * std::abs(f.back() - 10.0) / f.back(), tt::tolerance(1e-6));
  }
}

// Outside the asymptotic range (a first-order term that takes over from the fourth-order one
// as the mesh is refined) the orders of the two triples disagree (3.76 and 2.84): safety factor 3, and the note says so. Three meshes alone cannot confirm an
// order: 3 as well.
BOOST_AUTO_TEST_CASE(gci_outside_the_asymptotic_range_takes_the_larger_safety_factor) {
  std::vector<double> h = {1.0, 0.5, 0.25, 0.125}, f;
  for (double x : h) f.push_back(1.0 + 0.05 * x + std::pow(x, 4));
  GridConvergence g = grid_convergence(h, f);
  BOOST_TEST(g.ok);
  BOOST_TEST(!g.asymptotic);
  BOOST_TEST(g.safety_factor == 3.0);
  BOOST_TEST(g.note.find("not in the asymptotic range") != std::string::npos, g.note);
  const double ratio = h[2] / h[3];
  BOOST_TEST(g.gci == 3.0 * std::abs((f[3] - f[2]) / f[3]) / (std::pow(ratio, g.order) - 1), tt::tolerance(1e-12));
  g = grid_convergence({1.0, 0.5, 0.25}, {2.0, 1.25, 1.0625});
  BOOST_TEST(g.ok);
  BOOST_TEST(g.safety_factor == 3.0);
  BOOST_TEST(g.note.find("not confirmed") != std::string::npos, g.note);
  // An oscillating sequence has no GCI.
  g = grid_convergence({1.0, 0.5, 0.25}, {2.0, 1.0, 1.5});
  BOOST_TEST(!g.ok);
  BOOST_TEST(std::isnan(g.gci));
}

// A method of the scene's theory is measured against exact; a method of another model (5 %
// stiffer) against its own Richardson limit, so its discretization error is the same 0.5 i / n^2
// and its model error the 5 % -- the two are never mixed.
BOOST_AUTO_TEST_CASE(discretization_and_model_errors_are_kept_apart) {
  Registry reg;
  reg.add(std::make_unique<exact::ExactSolver>());
  reg.add(std::make_unique<Scaled>("same", 1.0, true));
  reg.add(std::make_unique<Scaled>("other", 1.05, false));
  CompareOptions opt;  // the whole ladder (quick would cut it to three rungs)
  opt.shapes = false;
  opt.min_timing_s = 0;
  const auto all = run_comparison({beam_scene()}, reg, opt);
  const SceneComparison& c = all[0];
  BOOST_TEST(c.reference.source == "exact");
  int same = 0, other = 0;
  for (const auto& r : c.runs) {
    if (r.backend == "exact") continue;
    const double n = r.mesh.counts.at(0);
    // Mode 6 is the worst of the first six: 3 / n^2 relative, in both models.
    BOOST_TEST(r.disc_frequency_error == 3.0 / (n * n), tt::tolerance(1e-6));
    if (r.backend == "same") {
      ++same;
      BOOST_TEST(r.limit == "same");
      BOOST_TEST(r.max_frequency_error == r.disc_frequency_error, tt::tolerance(1e-12));
    } else {
      ++other;
      // Against the scene's reference the 5 % model error is mixed in.
      BOOST_TEST(r.max_frequency_error > 0.05);
    }
  }
  BOOST_TEST(same == 4);
  BOOST_TEST(other == 4);
  const ModelLimit& ls = limit_of(c, "same");
  BOOST_TEST(ls.source == "exact");
  BOOST_TEST(ls.model_error == 0.0, tt::tolerance(1e-12));
  BOOST_TEST(ls.order[0] == 2.0, tt::tolerance(0.02));
  const ModelLimit& lo = limit_of(c, "other");
  BOOST_TEST(lo.source.find("richardson(other") == 0u, lo.source);
  BOOST_TEST(lo.model_error == 0.05, tt::tolerance(1e-6));
  BOOST_TEST(lo.order[0] == 2.0, tt::tolerance(1e-6));
  BOOST_TEST(lo.safety_factor == 1.25);
  // GCI of mode 6 on the finest mesh: 1.25 |f_32 - f_lim| / f_32.
  BOOST_TEST(lo.gci == 1.25 * (3.0 / 1024) / (1 + 3.0 / 1024), tt::tolerance(1e-6));
  // Time to 1 % discretization error: 3 / n^2 <= 0.01 first at n = 32, for both.
  for (const char* m : {"same", "other"}) {
    double t32 = 0;
    for (const auto& r : c.runs)
      if (r.backend == m && r.mesh.counts[0] == 32) t32 = r.time_s.modes;
    BOOST_TEST(time_to_accuracy(c, m, 1e-2) == t32);
    BOOST_TEST(std::isnan(time_to_accuracy(c, m, 1e-3)));
  }
}

// The NAFEMS FV5 scene encodes its benchmark: simply supported Timoshenko bending (both planes),
// a fixed-free shaft in torsion and a fixed-free bar -- each against its closed form.
BOOST_AUTO_TEST_CASE(nafems_fv5_scene_against_closed_forms) {
  const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/nafems_fv5_deep_beam.toml");
  const Result r = exact::ExactSolver().solve(s, {}, Options{});
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const auto& m = s.material;
  const Section sec = s.section();
  const double L = s.geometry.length, pi = 3.14159265358979323846;
  // SS Timoshenko, wavenumber k = n pi / L: E I k^4 - w^2 (rho A + rho I k^2 (1 + E / (kappa G)))
  // + w^4 rho^2 I / (kappa G) = 0, the lower root.
  auto bending = [&](int n) {
    const double k = n * pi / L, I = sec.Iy;
    const double a = m.rho * m.rho * I / (m.kappa * m.G), b = m.rho * sec.A + m.rho * I * k * k * (1 + m.E / (m.kappa * m.G));
    const double c = m.E * I * k * k * k * k;
    return std::sqrt((b - std::sqrt(b * b - 4 * a * c)) / (2 * a));
  };
  const double torsion = pi / (2 * L) * std::sqrt(m.G * sec.J / (m.rho * sec.Ip));
  const double axial = pi / (2 * L) * std::sqrt(m.E / m.rho);
  const std::vector<double> expected = {bending(1), bending(1), torsion, axial, bending(2), bending(2), 3 * torsion,
                                        bending(3), bending(3)};
  BOOST_REQUIRE(r.frequencies_rad_s.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i)
    BOOST_TEST(r.frequencies_rad_s[i] == expected[i], tt::tolerance(1e-8));
  BOOST_TEST(axial / (2 * pi) == 125.0, tt::tolerance(1e-12));  // NAFEMS: 125.00 Hz
  BOOST_TEST(bending(1) / (2 * pi) == 42.649, tt::tolerance(2e-4));  // NAFEMS: 42.649 Hz
}

// A back-end that states its expansion gets a "+richardson" peer: one run per rung with two coarser
// rungs below it, its frequencies the extrapolated ones (their error the h^4 remainder, -4 d / n^4
// relative), timed as the rungs it uses together.
BOOST_AUTO_TEST_CASE(extrapolated_peers_are_compared_and_timed_as_their_meshes) {
  Registry reg;
  reg.add(std::make_unique<exact::ExactSolver>());
  reg.add(std::make_unique<Scaled>("quartic", 1.0, true, 2.0, 4.0, 1.0));  // d = 2, next order 4, n ms a rung
  CompareOptions opt;
  opt.shapes = false;
  opt.clock = [] { return fake_now; };
  const auto all = run_comparison({beam_scene()}, reg, opt);
  const SceneComparison& c = all[0];
  std::map<int, const RunRecord*> own, peer;
  for (const auto& r : c.runs) {
    if (r.backend == "quartic") own[r.mesh.counts.at(0)] = &r;
    if (r.backend == "quartic+richardson") peer[r.mesh.counts.at(0)] = &r;
  }
  BOOST_REQUIRE(own.size() == 4u);
  BOOST_REQUIRE(peer.size() == 2u);  // 16 (from 8 and 4) and 32 (from 16, 8 and 4)
  for (const auto& [n, r] : peer) {
    // Mode 6 is the worst: 4 * 2 * 6 / n^4 left by the step (c(2) = -4 for a remainder of order 4).
    BOOST_TEST(r->disc_frequency_error == 48.0 / std::pow(n, 4), tt::tolerance(1e-3));
    BOOST_TEST(r->disc_frequency_error < 0.1 * own[n]->disc_frequency_error);
    double t = own[n]->time_s.modes + own[n / 2]->time_s.modes + own[n / 4]->time_s.modes;
    if (n == 32) t += own[4]->time_s.modes;  // the fourth mesh checks the extrapolation's order
    BOOST_TEST(r->time_s.modes == t, tt::tolerance(1e-9));
    BOOST_TEST(r->result.summary.method.find("Richardson") != std::string::npos);
  }
  BOOST_TEST(std::log2(peer[16]->disc_frequency_error / peer[32]->disc_frequency_error) == 4.0, tt::tolerance(0.01));
  BOOST_TEST(time_to_accuracy(c, "quartic+richardson", 1e-3) == peer[16]->time_s.modes);
}
