#pragma once
// The 8-point Gauss-Legendre rule on [-1, 1] (Abramowitz & Stegun 25.4.30): the nodes +-node[i]
// share weight[i]; exact for polynomials of degree <= 15.
#include <array>

namespace modalbench::gauss_legendre8 {

inline constexpr std::array<double, 4> node = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                               0.9602898564975363};
inline constexpr std::array<double, 4> weight = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                                 0.1012285362903763};

}  // namespace modalbench::gauss_legendre8
