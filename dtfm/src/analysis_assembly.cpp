// LineAnalysis assembly: segment dynamic stiffnesses into K(lambda), and the Wittrick-Williams count.
#include "modalbench/dtfm/analysis.hpp"

#include <exception>
#include <system_error>
#include <thread>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

#include "analysis_detail.hpp"
#include "modalbench/numerics/segment_dynamic_stiffness.hpp"

namespace modalbench::dtfm {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using detail::AssemblyInfo;

template <class Mat>
void transform_end(Mat& k, const Eigen::MatrixXd& B, int mc, bool left) {
  using Scalar = typename Mat::Scalar;
  const Mat Bs = B.template cast<Scalar>();
  if (left) {
    k.topLeftCorner(mc, mc) = (Bs.transpose() * k.topLeftCorner(mc, mc) * Bs).eval();
    k.topRightCorner(mc, mc) = (Bs.transpose() * k.topRightCorner(mc, mc)).eval();
    k.bottomLeftCorner(mc, mc) = (k.bottomLeftCorner(mc, mc) * Bs).eval();
  } else {
    k.bottomRightCorner(mc, mc) = (Bs.transpose() * k.bottomRightCorner(mc, mc) * Bs).eval();
    k.bottomLeftCorner(mc, mc) = (Bs.transpose() * k.bottomLeftCorner(mc, mc)).eval();
    k.topRightCorner(mc, mc) = (k.topRightCorner(mc, mc) * Bs).eval();
  }
}

/// Long-segment stiffness by doubling, real or complex (the pieces the base length allows).
LongSegment long_segment(const Eigen::MatrixXd& A, double h, int levels) {
  return long_segment_dynamic_stiffness(A, h, levels);
}
LongSegmentC long_segment(const Eigen::MatrixXcd& A, double h, int levels) {
  return long_segment_dynamic_stiffness(A, h, levels);
}
int clamped_of(const LongSegment& s) { return s.clamped_below; }
int clamped_of(const LongSegmentC&) { return 0; }
double log_tdf_of(const LongSegment& s) { return s.log_abs_det_tdf; }
double log_tdf_of(const LongSegmentC&) { return 0.0; }

template <class Tri, class Mat, class Scalar>
AssemblyInfo assemble_into(Tri& K, const LineAnalysis::ClassLine& c, Scalar lambda, const std::vector<double>& x,
                           double h_base, double& max_asym) {
  const int nn = static_cast<int>(x.size()), mc = c.mc;
  using Seg = decltype(long_segment(std::declval<Mat>(), 1.0, 0));
  std::vector<Mat> A(static_cast<std::size_t>(c.pieces()));
  std::vector<std::tuple<double, int, Seg>> cache;
  AssemblyInfo info;
  for (int i = 0; i + 1 < nn; ++i) {
    const double h = x[i + 1] - x[i];
    const int piece = c.piece_of(x[i], x[i + 1]);
    const Seg* hit = nullptr;
    for (const auto& e : cache)
      if (std::get<1>(e) == piece && std::abs(h - std::get<0>(e)) <= 1e-9 * h) hit = &std::get<2>(e);
    if (!hit) {
      Mat& Ap = A[static_cast<std::size_t>(piece)];
      if (Ap.size() == 0) Ap = c.state(lambda, piece);
      const int levels = detail::doubling_levels(h, h_base);
      cache.emplace_back(h, piece, long_segment(Ap, h, levels));
      hit = &std::get<2>(cache.back());
      max_asym = std::isfinite(hit->asymmetry) ? std::max(max_asym, hit->asymmetry) : kInf;
      info.min_pivot_rel = std::min(info.min_pivot_rel, hit->min_pivot_rel);
    }
    info.clamped_below += clamped_of(*hit);
    info.log_poles += log_tdf_of(*hit);
    const auto* left = c.condition_at(x, static_cast<std::size_t>(i));
    const auto* right = c.condition_at(x, static_cast<std::size_t>(i) + 1);
    if (left && left->identity) left = nullptr;
    if (right && right->identity) right = nullptr;
    if (left || right) {
      Mat k = hit->K;
      if (left) transform_end(k, left->B, mc, true);
      if (right) transform_end(k, right->B, mc, false);
      K.add_segment(i, k);
    } else {
      K.add_segment(i, hit->K);
    }
  }
  // Springs and masses on the admissible motions of every node with conditions; the rest held.
  for (int node = 0; node < nn; ++node) {
    const auto* ce = c.condition_at(x, static_cast<std::size_t>(node));
    if (!ce) continue;
    Mat term = Mat::Zero(ce->n_free, ce->n_free);
    if (ce->n_free > 0 && ce->K.size() > 0) term += ce->K.template cast<Scalar>();
    if (ce->mass_scaled.size() > 0) term -= lambda * ce->mass_scaled.template cast<Scalar>();
    if (ce->gyro_scaled.size() > 0) term += c.whirl_term(lambda) * ce->gyro_scaled.template cast<Scalar>();
    if (ce->n_free > 0 && term.norm() > 0) {
      Mat pad = Mat::Zero(2 * mc, 2 * mc);
      if (node + 1 < nn) pad.topLeftCorner(ce->n_free, ce->n_free) = term;
      else pad.block(mc, mc, ce->n_free, ce->n_free) = term;
      K.add_segment(node + 1 < nn ? node : nn - 2, pad);
    }
    for (int j = ce->n_free; j < mc; ++j) K.hold(node, j);
  }
  return info;
}

}  // namespace

thread_local LineAnalysis::Tally* LineAnalysis::tally_ = nullptr;

void LineAnalysis::side_by_side(std::size_t n, const std::function<void(std::size_t)>& task) {
  if (n < 2 || tally_ || std::thread::hardware_concurrency() < 2) {
    for (std::size_t i = 0; i < n; ++i) task(i);
    return;
  }
  Tally mine, theirs;
  std::exception_ptr e_mine, e_theirs;
  auto run = [&](std::size_t first, Tally& t, std::exception_ptr& e) {
    tally_ = &t;
    try {
      for (std::size_t i = first; i < n; i += 2) task(i);
    } catch (...) {
      e = std::current_exception();
    }
    tally_ = nullptr;
  };
  std::thread worker;
  try {
    worker = std::thread(run, std::size_t{1}, std::ref(theirs), std::ref(e_theirs));
  } catch (const std::system_error&) {
    // No second thread to be had (a process or address-space limit): all of it here, in order.
    for (std::size_t i = 0; i < n; ++i) task(i);
    return;
  }
  run(0, mine, e_mine);
  worker.join();
  for (const Tally* t : {&mine, &theirs}) {
    max_asymmetry_ = std::max(max_asymmetry_, t->asymmetry);
    max_unknowns_ = std::max(max_unknowns_, t->unknowns);
    evaluations_ += t->evaluations;
  }
  threads_used_ = 2;
  if (e_mine) std::rethrow_exception(e_mine);
  if (e_theirs) std::rethrow_exception(e_theirs);
}

LineAnalysis::Assembled LineAnalysis::assemble(const ClassLine& c, double lambda, const Mesh& mesh) {
  Assembled out{BlockTridiagonal(static_cast<int>(mesh.x.size()), c.mc), {}};
  double& asymmetry = tally_ ? tally_->asymmetry : max_asymmetry_;
  long& unknowns = tally_ ? tally_->unknowns : max_unknowns_;
  out.info = assemble_into<BlockTridiagonal, Eigen::MatrixXd, double>(out.K, c, lambda, mesh.x,
                                                                      mesh.h_base, asymmetry);
  unknowns = std::max<long>(unknowns, out.K.free_dofs());
  return out;
}

ComplexBlockTridiagonal LineAnalysis::assemble(const ClassLine& c, std::complex<double> lambda, const Mesh& mesh) {
  ComplexBlockTridiagonal K(static_cast<int>(mesh.x.size()), c.mc);
  double& asymmetry = tally_ ? tally_->asymmetry : max_asymmetry_;
  long& unknowns = tally_ ? tally_->unknowns : max_unknowns_;
  assemble_into<ComplexBlockTridiagonal, Eigen::MatrixXcd, std::complex<double>>(K, c, lambda, mesh.x,
                                                                                 mesh.h_base, asymmetry);
  unknowns = std::max<long>(unknowns, K.free_dofs());
  return K;
}

CountDet LineAnalysis::count_det(const ClassLine& c, double lambda, const Mesh& mesh) {
  ++(tally_ ? tally_->evaluations : evaluations_);
  // A segment whose condensed middle block is nearly singular (lambda close to a clamped
  // frequency of a sub-piece) is split at its middle: the global LDL^T then pivots across it.
  Mesh use = mesh;
  for (int attempt = 0;; ++attempt) {
    const Assembled a = assemble(c, lambda, use);
    if (a.info.min_pivot_rel < 1e-10 && attempt < 4) {
      use = refined(use);
      continue;
    }
    const auto in = a.K.inertia();
    // Wittrick-Williams: J = J0 (segments) + s{K}; det K * prod det Tdf has no poles.
    return {in.negative + a.info.clamped_below, in.log_abs_det + a.info.log_poles};
  }
}

int LineAnalysis::count_below(double lambda, const std::vector<ModeFamily>& families) {
  int n = 0;
  for (int c : pick(families)) {
    const Mesh mesh = mesh_for(*lines_[c], std::max(lambda, 0.0), {});
    n += count_det(*lines_[c], lambda, mesh).count;
  }
  return n;
}

}  // namespace modalbench::dtfm
