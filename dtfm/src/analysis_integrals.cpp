// Integrals along x of a static solution's fields (detail::integrate_fields): what a plate's long
// edges' reactions need (dtfm_plate_reactions.cpp).
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include "analysis_detail.hpp"
#include "modalbench/numerics/balancing.hpp"
#include "modalbench/numerics/segment_dynamic_stiffness.hpp"

#include <unsupported/Eigen/MatrixFunctions>

namespace modalbench::dtfm::detail {

namespace {

// 8-point Gauss-Legendre on [-1, 1].
constexpr std::array<double, 8> kNode = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                         -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                         0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kWeight = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                           0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                           0.2223810344533745, 0.1012285362903763};

/// Each segment is integrated on kPanels equal panels of 8 Gauss points each.
constexpr int kPanels = 1;
constexpr std::size_t kPoints = 8 * kPanels;
/// Gauss point g of a segment of length h: its offset from the left node and its weight.
std::pair<double, double> gauss_point(std::size_t g, double h) {
  const double panel = h / kPanels;
  const std::size_t p = g / 8, k = g % 8;
  return {panel * (static_cast<double>(p) + 0.5 * (1 + kNode[k])), 0.5 * panel * kWeight[k]};
}

Eigen::MatrixXd expm(const Eigen::MatrixXd& A, double t) {
  Eigen::MatrixXd B = A * t;
  const Eigen::VectorXd s = balance_in_place(B, 20);
  return s.asDiagonal() * Eigen::MatrixXd(B.exp()) * s.cwiseInverse().asDiagonal();
}

/// What one segment length needs, formed once: its dynamic stiffness and exp(A t) at the Gauss points.
struct SegmentTransfer {
  Eigen::MatrixXd K;
  std::array<Eigen::MatrixXd, kPoints> T;
};

}  // namespace

void integrate_fields(const LineAnalysis::ClassLine& c, const std::vector<double>& x, double h_base,
                      const Eigen::VectorXd& d, const Eigen::VectorXd& f,
                      const std::vector<std::optional<SegmentLoad>>& loads, FieldIntegrals& out) {
  const int nn = static_cast<int>(x.size()), mc = c.mc;
  if (nn < 2) return;
  const double L = x.back();
  auto node_d = [&](int k) {
    Eigen::VectorXd v = d.segment(static_cast<Eigen::Index>(k) * mc, mc);
    if (const auto* e = c.condition_at(x, static_cast<std::size_t>(k))) v = e->B * v;
    return v;
  };
  std::map<std::pair<int, long long>, SegmentTransfer> transfer;  // by piece and length (in 1e-12 L)
  // The particular solutions at the Gauss points and at h, by piece, segment length and load.
  std::map<std::vector<double>, std::array<Eigen::VectorXd, kPoints + 1>> part;
  Eigen::VectorXd Iq = Eigen::VectorXd::Zero(mc), Ixq = Eigen::VectorXd::Zero(mc);
  Eigen::VectorXd Kd = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nn) * mc);
  for (int a = 0; a + 1 < nn; ++a) {
    const double xa = x[static_cast<std::size_t>(a)], h = x[static_cast<std::size_t>(a) + 1] - xa;
    const int piece = c.piece_of(xa, xa + h);
    const Eigen::MatrixXd A = c.state(0.0, piece);
    const long long key = std::llround(h / (1e-12 * L));
    auto it = transfer.find({piece, key});
    if (it == transfer.end()) {
      SegmentTransfer st;
      st.K = long_segment_dynamic_stiffness(A, h, doubling_levels(h, h_base)).K;
      for (std::size_t g = 0; g < kPoints; ++g) st.T[g] = expm(A, gauss_point(g, h).first);
      it = transfer.emplace(std::make_pair(piece, key), std::move(st)).first;
    }
    const SegmentTransfer& st = it->second;
    const std::optional<SegmentLoad>* ld =
        static_cast<std::size_t>(a) < loads.size() && loads[static_cast<std::size_t>(a)] ? &loads[static_cast<std::size_t>(a)] : nullptr;
    const std::array<Eigen::VectorXd, kPoints + 1>* yp = nullptr;
    Eigen::VectorXd yp_h = Eigen::VectorXd::Zero(2 * mc);
    if (ld) {
      // Segments of one piece, length and load (a patch, gravity) share their particular solutions.
      std::vector<double> sig = {static_cast<double>(piece), static_cast<double>(key)};
      sig.insert(sig.end(), (**ld).g0.data(), (**ld).g0.data() + (**ld).g0.size());
      sig.insert(sig.end(), (**ld).g1.data(), (**ld).g1.data() + (**ld).g1.size());
      auto pit = part.find(sig);
      if (pit == part.end()) {
        std::array<Eigen::VectorXd, kPoints + 1> v;  // at the Gauss points and at h
        for (std::size_t g = 0; g < kPoints; ++g) v[g] = particular(A, **ld, gauss_point(g, h).first);
        v[kPoints] = particular(A, **ld, h);
        pit = part.emplace(std::move(sig), std::move(v)).first;
      }
      yp = &pit->second;
      yp_h = pit->second[kPoints];
    }
    // The left node's state: its displacement and the segment's end force, K [d_a; d_b - d_p(h)]
    // = [-F(a+); F(b-) - f_p(h)].
    Eigen::VectorXd dd(2 * mc), eta(2 * mc);
    dd << node_d(a), node_d(a + 1) - yp_h.head(mc);
    eta << node_d(a), -(st.K.topRows(mc) * dd);
    // The nodes' share of K d (class coordinates; the loads' equivalent forces are in f) for the
    // conditions' forces below.
    Eigen::VectorXd da(2 * mc);
    da << node_d(a), node_d(a + 1);
    const Eigen::VectorXd Kda = st.K * da;
    Kd.segment(static_cast<Eigen::Index>(a) * mc, mc) += Kda.head(mc);
    Kd.segment(static_cast<Eigen::Index>(a + 1) * mc, mc) += Kda.tail(mc);
    for (std::size_t g = 0; g < kPoints; ++g) {
      const auto [t, w] = gauss_point(g, h);
      Eigen::VectorXd y = st.T[g] * eta;
      if (yp) y += (*yp)[g];
      Iq += w * y.head(mc);
      Ixq += w * (xa + t - 0.5 * L) * y.head(mc);
    }
  }
  // What each node's conditions exert: K d - f on its held coordinates (K d from the segments, the
  // equivalent nodal forces of the loads in f), -k d for its springs (as LineAnalysis::add_reactions
  // does, without assembling K again).
  for (int i = 0; i < nn; ++i) {
    const auto* ce = c.condition_at(x, static_cast<std::size_t>(i));
    if (!ce) continue;
    const Eigen::Index o = static_cast<Eigen::Index>(i) * mc;
    const Eigen::VectorXd KdB = ce->B.transpose() * Kd.segment(o, mc);
    Eigen::VectorXd rB = Eigen::VectorXd::Zero(mc);
    for (int j = ce->n_free; j < mc; ++j) rB[j] = KdB[j] - f[o + j];
    if (ce->n_free > 0 && ce->K.size() > 0) rB.head(ce->n_free) = -(ce->K * d.segment(o, ce->n_free));
    const Eigen::VectorXd fields = c.sigma * c.Winv.transpose() * (ce->B * rB);
    auto it = out.node_forces.find(ce->x);
    if (it == out.node_forces.end()) out.node_forces.emplace(ce->x, fields);
    else it->second += fields;
  }
  out.q += c.W * Iq;
  out.xq += c.W * Ixq;
  out.q0 += c.W * node_d(0);
  out.qL += c.W * node_d(nn - 1);
}

}  // namespace modalbench::dtfm::detail
