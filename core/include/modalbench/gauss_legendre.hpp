#pragma once
// The 8-point Gauss-Legendre rule on [-1, 1] (Abramowitz & Stegun 25.4.30): the nodes +-node[i]
// share weight[i]; exact for polynomials of degree <= 15.
#include <array>
#include <cstddef>

namespace modalbench::gauss_legendre8 {

inline constexpr std::array<double, 4> node = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                               0.9602898564975363};
inline constexpr std::array<double, 4> weight = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                                 0.1012285362903763};

/// The integral of f over [a, b] by the rule on `parts` equal parts.
template <class F>
double integrate(const F& f, double a, double b, int parts) {
  const double h = (b - a) / parts;
  double sum = 0;
  for (int k = 0; k < parts; ++k) {
    const double mid = a + (k + 0.5) * h;
    for (std::size_t g = 0; g < node.size(); ++g)
      for (const double sign : {-1.0, 1.0}) sum += weight[g] * 0.5 * h * f(mid + sign * 0.5 * h * node[g]);
  }
  return sum;
}

}  // namespace modalbench::gauss_legendre8
