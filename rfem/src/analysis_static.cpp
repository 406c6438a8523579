// rfem statics: K z = f by the saddle-point LDL', or the mechanism that makes it undefined.
#include "modalbench/rfem/analysis.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <string>
#include <vector>

#include "modalbench/rfem/factor.hpp"
#include "analysis_detail.hpp"

namespace modalbench::rfem {

namespace {
using detail::Clock;
using detail::ConstraintProjector;
using detail::seconds_since;
}  // namespace

StaticSolution solve_static(const Model& model, const System& sys, const Eigen::VectorXd& f) {
  StaticSolution s;
  const auto t0 = Clock::now();
  const RigidModes rigid = free_rigid_modes(model, sys);
  if (rigid.Z.cols() > 0) {
    s.mechanism = true;
    // Name the coordinates each free motion moves most.
    std::vector<std::string> moved;
    for (long c = 0; c < rigid.Z.cols(); ++c) {
      const Eigen::VectorXd z = rigid.Z.col(c);
      const double zmax = z.cwiseAbs().maxCoeff();
      long listed = 0, more = 0;
      for (long i = 0; i < z.size(); ++i)
        if (std::abs(z[i]) >= 0.5 * zmax) {
          if (listed < 4) moved.push_back(coordinate_name(model, sys, i)), ++listed;
          else ++more;
        }
      if (more > 0) moved.push_back(fmt::format("... {} more", more));
    }
    s.message = fmt::format(
        "mechanism: the supports leave {} rigid-body motion(s) free ({}); free coordinates include {}. Static "
        "deflection is undefined: add supports or springs",
        rigid.Z.cols(), fmt::join(rigid.motions, "; "), fmt::join(moved, ", "));
    s.factor_seconds = seconds_since(t0);
    return s;
  }
  KktLdlt ldlt;
  ldlt.analyze(sys.K, sys.G, sys.groups);
  const bool fact = ldlt.factorize(sys.K);
  long where = -1;
  const double ratio = ldlt.smallest_primal_pivot_ratio(&where);
  s.factor_seconds = seconds_since(t0);
  if (!fact || ldlt.negative_count() != 0 || ratio < 1e-14) {
    s.message = fmt::format(
        "stiffness matrix singular or indefinite: {} negative pivot(s), smallest pivot ratio {:.3g} at {}",
        fact ? ldlt.negative_count() : -1, ratio,
        where >= 0 ? coordinate_name(model, sys, where) : std::string("?"));
    return s;
  }
  const auto t1 = Clock::now();
  s.z = ldlt.solve(f);
  const ConstraintProjector P(sys.G);
  const double fn = f.norm();
  s.residual = fn > 0 ? P(sys.K * s.z - f).norm() / fn : 0.0;
  s.solve_seconds = seconds_since(t1);
  s.ok = true;
  return s;
}

}  // namespace modalbench::rfem
