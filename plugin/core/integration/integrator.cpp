#include "integration/integrator.hpp"

#include <algorithm>
#include <cmath>

namespace dlmfsi {

int nonlinear_rule_degree(int product_degree, double nonlinearity) {
  const double d = std::min(std::max(nonlinearity, 1e-300), kLeafNonlinearity);
  const int k = std::max(1, static_cast<int>(std::ceil(11.0 / -std::log10(d / 3))) - 1);
  return std::min(kMaxQforder, product_degree + 2 * k);
}

}  // namespace dlmfsi
