// LineAnalysis set-up: each symmetry class of the prism model as a scaled line problem; class selection.
#include "modalbench/dtfm/analysis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <memory>

#include "analysis_detail.hpp"

namespace modalbench::dtfm {

LineAnalysis::~LineAnalysis() = default;

namespace {

using End = LineAnalysis::ClassLine::End;

/// The scaled class operator (St, C, Qt, M) of energy-form matrices.
struct Projected {
  Eigen::MatrixXd St, C, Qt, M;
};

/// W^T A W / sigma, symmetrized (mass-like matrices over the fields); empty stays empty.
Eigen::MatrixXd scaled(const LineAnalysis::ClassLine& l, const Eigen::MatrixXd& A) {
  if (A.size() == 0) return A;
  const Eigen::MatrixXd P = l.W.transpose() * A * l.W / l.sigma;
  return 0.5 * (P + P.transpose());
}
Projected project(const LineAnalysis::ClassLine& l, const Eigen::MatrixXd& Vs, const Eigen::MatrixXd& M,
                  const Eigen::MatrixXd& C, const Eigen::MatrixXd& S, const Eigen::MatrixXd& X,
                  const Eigen::MatrixXd& Q1) {
  const Eigen::MatrixXd& W = l.W;
  const double sigma = l.sigma;
  Projected p;
  const Eigen::MatrixXd Cc = sigma * (Vs.transpose() * C * Vs);
  const Eigen::MatrixXd Sc = l.Winv * S * W;
  const Eigen::MatrixXd Xc = W.transpose() * X * W / sigma;
  const Eigen::MatrixXd Qc = W.transpose() * Q1 * W / sigma;
  p.C = 0.5 * (Cc + Cc.transpose());
  p.M = W.transpose() * M * W / sigma;
  p.M = 0.5 * (p.M + p.M.transpose());
  p.St = Sc + p.C * Xc;
  p.Qt = Qc - Xc.transpose() * p.C * Xc;
  p.Qt = 0.5 * (p.Qt + p.Qt.transpose());
  return p;
}

/// A node condition of the model in the class's coordinates; `si` divides the fields into the
/// line solves' scaled units (translations by the model's translation scale).
End class_end(const LineAnalysis::ClassLine& l, const EndCondition& end, double x, const Eigen::VectorXd& si) {
  const int mc = l.mc;
  const Eigen::MatrixXd& W = l.W;
  End ce;
  ce.x = x;
  Eigen::MatrixXd Nc(mc, 0);
  if (end.N.cols() > 0) {
    // Each admissible motion in scaled units, of unit length, then its part in this class: 1
    // for a motion of the class, rounding (1e-17) for one outside it. Relative to the motion,
    // not to the largest singular value: an end whose admissible motions all lie outside this
    // class projects to rounding noise, whose largest value must not pass as an admissible
    // direction (a pinned end of a 2 x 2 section let the axial class move freely: rigid 0 and
    // the free-free axial mode). Nor to the size of the map, which mixes translations (divided
    // by the section depth) with rotations: a section 5e10 m deep had its free end's w taken
    // for rounding and held (a cantilever solved as clamped-pinned; fuzz seed 7, case 660).
    Eigen::MatrixXd raw = l.Winv * end.N;
    for (Eigen::Index c = 0; c < raw.cols(); ++c) {
      const double len = (si.asDiagonal() * end.N.col(c)).norm();
      if (len > 0) raw.col(c) /= len;
    }
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(raw, Eigen::ComputeThinU);
    if (svd.info() != Eigen::Success) throw std::runtime_error("dtfm: SVD of the end conditions failed");
    const auto& sv = svd.singularValues();
    int r = 0;
    for (Eigen::Index i = 0; i < sv.size(); ++i)
      if (sv[i] > 1e-10) ++r;
    // Every motion of the class admissible (a free end): any basis of the class's coordinates
    // will do, and the identity spares each assembly the transformation of the end blocks.
    Nc = r == mc ? Eigen::MatrixXd::Identity(mc, mc) : Eigen::MatrixXd(svd.matrixU().leftCols(r));
  }
  ce.n_free = static_cast<int>(Nc.cols());
  ce.B = Eigen::MatrixXd::Identity(mc, mc);
  ce.identity = ce.n_free == 0 || ce.n_free == mc;  // held throughout, or Nc = I
  if (ce.n_free > 0) {
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(Nc);
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(mc, mc);
    ce.B.leftCols(ce.n_free) = Nc;
    ce.B.rightCols(mc - ce.n_free) = Q.rightCols(mc - ce.n_free);
    // Springs 1/2 a^T K a with q = N a, a = N^T q = N^T W Nc b. An end motion outside this
    // class projects to rounding (1e-17 of the map): zero it, or its spring would leak into
    // the class squared and pass for a support of a motion the scene leaves free (a statics
    // mechanism taken for a near-mechanism on a 1e-45 spring).
    Eigen::MatrixXd G = end.N.transpose() * W * Nc;
    const double g_floor = 64.0 * std::numeric_limits<double>::epsilon() * G.cwiseAbs().maxCoeff();
    G = G.unaryExpr([g_floor](double g) { return std::abs(g) <= g_floor ? 0.0 : g; });
    ce.K = G.transpose() * end.K * G / l.sigma;
    ce.K = 0.5 * (ce.K + ce.K.transpose());
  } else {
    ce.K = Eigen::MatrixXd(0, 0);
  }
  if (end.mass.size() > 0) {
    Eigen::MatrixXd Mc = W.transpose() * end.mass * W;
    const double floor = 64.0 * std::numeric_limits<double>::epsilon() * Mc.cwiseAbs().maxCoeff();
    Mc = Mc.unaryExpr([floor](double v) { return std::abs(v) <= floor ? 0.0 : v; });
    if (Mc.cwiseAbs().maxCoeff() > 0) {
      ce.Mc = 0.5 * (Mc + Mc.transpose());
      ce.Mfields = end.mass;
      const Eigen::MatrixXd Bf = ce.B.leftCols(ce.n_free);
      ce.mass_scaled = Bf.transpose() * ce.Mc * Bf / l.sigma;
      ce.mass_scaled = 0.5 * (ce.mass_scaled + ce.mass_scaled.transpose()).eval();
    }
  }
  if (end.gyro.size() > 0 && end.gyro.cwiseAbs().maxCoeff() > 0) {
    const Eigen::MatrixXd Bf = ce.B.leftCols(ce.n_free);
    ce.gyro_scaled = Bf.transpose() * scaled(l, end.gyro) * Bf;
  }
  return ce;
}

}  // namespace

LineAnalysis::LineAnalysis(const PrismModel& model, SolveControls controls) : model_(model), ctl_(controls) {
  const int m = model.m;
  Eigen::VectorXd s(m);
  for (int k = 0; k < m; ++k) s[k] = model.field_dof[k] < 3 ? model.translation_scale : 1.0;
  const Eigen::VectorXd si = s.cwiseInverse();
  int ci = 0;
  for (const auto& fc : model.classes) {
    auto line = std::make_unique<ClassLine>();
    line->index = ci++;
    line->mc = static_cast<int>(fc.V.cols());
    line->family = fc.family;
    line->family_motions = fc.family_motions;
    line->length = model.length;
    line->W = s.asDiagonal() * fc.V;
    line->Winv = fc.V.transpose() * si.asDiagonal();
    const Eigen::MatrixXd Vs = si.asDiagonal() * fc.V;  // strains scale like q'
    double sigma = (line->W.transpose() * model.M * line->W).norm() * model.lambda_scale;
    if (!(sigma > 0) || !std::isfinite(sigma)) sigma = 1.0;
    line->sigma = sigma;
    const Projected p = project(*line, Vs, model.M, model.C, model.S, model.X, model.Q1);
    line->St = p.St;
    line->C = p.C;
    line->Qt = p.Qt;
    line->M = p.M;
    line->G = scaled(*line, model.G);
    line->whirl = model.whirl;
    line->first_to = model.steps.empty() ? model.length : model.first_piece_to;
    for (const PieceOperator& op : model.steps) {
      const Projected q = project(*line, Vs, op.M, op.C, op.S, op.X, op.Q1);
      line->steps.push_back({op.x_to, q.St, q.C, q.Qt, q.M, scaled(*line, op.G)});
    }
    for (int e = 0; e < 2; ++e) line->ends[e] = class_end(*line, model.ends[e], e == 0 ? 0.0 : model.length, si);
    for (const PointCondition& pc : model.points) line->points.push_back(class_end(*line, pc.cond, pc.x, si));
    lines_.push_back(std::move(line));
  }
}

std::vector<int> LineAnalysis::pick(const std::vector<ModeFamily>& families) const {
  std::vector<int> out;
  for (const auto& l : lines_)
    if (families.empty() || std::find(families.begin(), families.end(), l->family) != families.end())
      out.push_back(l->index);
  return out;
}

}  // namespace modalbench::dtfm
