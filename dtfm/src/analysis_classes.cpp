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
    line->W = s.asDiagonal() * fc.V;
    line->Winv = fc.V.transpose() * si.asDiagonal();
    const Eigen::MatrixXd& W = line->W;
    const Eigen::MatrixXd Vs = si.asDiagonal() * fc.V;  // strains scale like q'
    Eigen::MatrixXd Mc = W.transpose() * model.M * W;
    double sigma = Mc.norm() * model.lambda_scale;
    if (!(sigma > 0) || !std::isfinite(sigma)) sigma = 1.0;
    line->sigma = sigma;
    const Eigen::MatrixXd Cc = sigma * (Vs.transpose() * model.C * Vs);
    const Eigen::MatrixXd Sc = line->Winv * model.S * W;
    const Eigen::MatrixXd Xc = W.transpose() * model.X * W / sigma;
    const Eigen::MatrixXd Qc = W.transpose() * model.Q1 * W / sigma;
    line->C = 0.5 * (Cc + Cc.transpose());
    line->M = Mc / sigma;
    line->M = 0.5 * (line->M + line->M.transpose());
    line->St = Sc + line->C * Xc;
    line->Qt = Qc - Xc.transpose() * line->C * Xc;
    line->Qt = 0.5 * (line->Qt + line->Qt.transpose());
    for (int e = 0; e < 2; ++e) {
      const auto& end = model.ends[e];
      auto& ce = line->ends[e];
      const int mc = line->mc;
      Eigen::MatrixXd Nc(mc, 0);
      if (end.N.cols() > 0) {
        const Eigen::MatrixXd raw = line->Winv * end.N;
        Eigen::JacobiSVD<Eigen::MatrixXd> svd(raw, Eigen::ComputeThinU);
        if (svd.info() != Eigen::Success) throw std::runtime_error("dtfm: SVD of the end conditions failed");
        const auto& sv = svd.singularValues();
        // Relative to the size of the map, not to the largest singular value: an end whose
        // admissible motions all lie outside this class projects to rounding noise, whose
        // largest value must not pass as an admissible direction (a pinned end of a 2 x 2
        // section let the axial class move freely: rigid 0 and the free-free axial mode).
        const double map_scale = line->Winv.norm();
        int r = 0;
        for (Eigen::Index i = 0; i < sv.size(); ++i)
          if (sv[i] > 1e-10 * map_scale) ++r;
        Nc = svd.matrixU().leftCols(r);
      }
      ce.n_free = static_cast<int>(Nc.cols());
      ce.B = Eigen::MatrixXd::Identity(mc, mc);
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
        ce.K = G.transpose() * end.K * G / sigma;
        ce.K = 0.5 * (ce.K + ce.K.transpose());
      } else {
        ce.K = Eigen::MatrixXd(0, 0);
      }
    }
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
