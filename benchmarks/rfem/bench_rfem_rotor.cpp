// A Campbell sweep on rfem (issue "spinning shafts": 61 speeds of a 2000-DOF rotor in about one
// factorization's cost): Friswell's two-disc rotor (scenes/rotor_friswell_two_discs.toml) on meshes
// of about 500 to 4000 lateral coordinates, 6 whirl frequencies at 61 spins from 0 to 4000 rev/min.
// Stationary frame: the default (campbell_method = projected: K factored once, the projected
// gyroscopic problem per spin, each root's frequency bounded to 1e-9 by its residual, the count at
// the top spin) and, in the same run, shift-invert Arnoldi at every spin (campbell_method =
// arnoldi); rotating frame (K - Omega^2 K_c factored per spin, Arnoldi). Beside them the time of
// one sparse LU of K alone and of the shaft's 6 modes at rest; "solves": the projection's K^-1
// solves, in whole solves (a residual's norm takes the forward half of one, its enrichment the back
// half), "basis" its largest basis, "arnoldi" the spins it left to Arnoldi. Last, per mesh, the
// floor of any sweep that checks every root: 61 spins x 6 roots x (the residual's products with K
// and M, G's left out, and 2 forward half solves for its K^-1 norm).
//
// Sample run:
//   build/benchmarks/rfem/bench_rfem_rotor
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <fmt/format.h>

#include <chrono>
#include <string>
#include <vector>

#include "modalbench/rfem/builders.hpp"
#include "modalbench/rfem/rfem.hpp"
#include "modalbench/rfem/system.hpp"

using namespace modalbench;

namespace {

double seconds(const std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main() {
  const rfem::RfemSolver solver;
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/rotor_friswell_two_discs.toml");
  s.rotor->spin.clear();
  for (int i = 0; i <= 60; ++i) s.rotor->spin.push_back(4000.0 * 3.141592653589793 / 30.0 * i / 60.0);
  fmt::print("{:>9} {:>12} {:>12} {:>12} {:>14} {:>14} {:>12} {:>8} {:>7} {:>8} {:>8}\n", "segments", "coordinates",
             "LU of K [s]", "modes [s]", "61 spins [s]", "per spin [s]", "Arnoldi [s]", "solves", "basis", "arnoldi",
             "status");
  std::vector<double> floors;
  for (const int n : {120, 240, 498, 996}) {
    rfem::BeamOptions bo;
    bo.rigid_shear = rfem::RigidShear::JointCoordinates;
    const rfem::System sys = rfem::assemble(rfem::build_beam(s, n, bo));
    auto t0 = std::chrono::steady_clock::now();
    Eigen::SparseLU<rfem::SpMat> lu(sys.K);
    const double t_lu = seconds(t0);
    // The floor of a verified root: its residual (sparse products with K and M on its real and
    // imaginary parts; G's two are left out) and the residual's K^-1 norm (the forward half of a
    // Cholesky solve, twice).
    const Eigen::SimplicialLLT<rfem::SpMat> llt(sys.K);
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(sys.n());
    Eigen::VectorXd y;
    t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < 200; ++i) y = sys.K * ones;
    const double t_k = seconds(t0) / 200;
    t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < 200; ++i) y = sys.M * ones;
    const double t_m = seconds(t0) / 200;
    t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < 200; ++i) y = llt.matrixL().solve(llt.permutationP() * ones);
    const double t_half = seconds(t0) / 200;
    floors.push_back(61.0 * 6 * (2 * t_k + 2 * t_m + 2 * t_half));
    Options o;
    o.estimate_error = false;
    Scene rest = s;
    rest.rotor.reset();
    const Result m = solver.solve(rest, Discretization{{n}}, o);
    const Result r = solver.solve(s, Discretization{{n}}, o);
    Options oa = o;
    oa.backend = {{"campbell_method", "arnoldi"}};
    const Result ra = solver.solve(s, Discretization{{n}}, oa);
    fmt::print("{:>9} {:>12} {:>12.3g} {:>12.3g} {:>14.3g} {:>14.3g} {:>12.3g} {:>8} {:>7} {:>8} {:>8}\n", n, sys.n(), t_lu,
               m.summary.timings_s.modes, r.summary.timings_s.campbell, r.summary.timings_s.campbell / 61,
               ra.summary.timings_s.campbell, r.summary.diagnostic("campbell_projected_solves"),
               r.summary.diagnostic("campbell_projected_basis"), r.summary.diagnostic("campbell_arnoldi_spins"),
               to_string(r.summary.status));
  }
  fmt::print("floor of a checked sweep (61 spins x 6 roots x (K and M products, 2 half solves each)): {:.3g} s, {:.3g} "
             "s, {:.3g} s, {:.3g} s\n",
             floors[0], floors[1], floors[2], floors[3]);
  s.rotor->frame = Rotor::Frame::Rotating;
  Options o;
  o.estimate_error = false;
  const Result r = solver.solve(s, Discretization{{498}}, o);
  fmt::print("rotating frame, 498 segments: 61 spins {:.3g} s, {} restarts ({})\n", r.summary.timings_s.campbell,
             r.summary.diagnostic("campbell_arnoldi_restarts"), to_string(r.summary.status));
}
