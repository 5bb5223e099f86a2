// The average of a function over an interval [x - h/2, x + h/2], for tests that compare a
// rendered pixel or texel (a box average of what it shows) with a closed-form response
// (EdgeTest, TextureSpaceTest): Gauss-Legendre, 8 points on each of 4 panels.
#pragma once

namespace sss::renderer::testing {

template <typename F>
double box_average(const F& f, double x, double h) {
  static const double gx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                               0.9602898564975363};
  static const double gw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                               0.1012285362903763};
  double sum = 0.0;
  const int panels = 4;
  const double ph = h / panels;
  for (int p = 0; p < panels; ++p) {
    const double c = x - 0.5 * h + (p + 0.5) * ph;
    for (int i = 0; i < 4; ++i)
      sum += gw[i] * (f(c - 0.5 * ph * gx[i]) + f(c + 0.5 * ph * gx[i])) * 0.5 * ph;
  }
  return sum / h;
}

}  // namespace sss::renderer::testing
