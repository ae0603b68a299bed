#include "fe/lattice3d.hpp"

#include <cmath>
#include <mutex>
#include <utility>

#include "fe/matrix_inverse.hpp"

namespace dlmfsi {

Point3 lattice_point3(int d, int m) {
  if (d == 0) return {0.25, 0.25, 0.25};
  int a, b, c;
  monomial_exponents3(m, a, b, c);
  return {static_cast<double>(a) / d, static_cast<double>(b) / d, static_cast<double>(c) / d};
}

const std::vector<MonomialParent3>& monomial_parents3() {
  static const auto table = [] {
    std::vector<MonomialParent3> all(monomial_count3(kMaxLatticeDegree), MonomialParent3{-1, -1});
    for (int m = 4; m < monomial_count3(kMaxLatticeDegree); ++m) {
      int a, b, c;
      monomial_exponents3(m, a, b, c);
      all[m] = a > 0 ? MonomialParent3{monomial_index3(a - 1, b, c), 0}
               : b > 0 ? MonomialParent3{monomial_index3(a, b - 1, c), 1}
                       : MonomialParent3{monomial_index3(a, b, c - 1), 2};
    }
    return all;
  }();
  return table;
}

const std::vector<MonomialDerivative3>& monomial_derivatives3(int d) {
  static const auto table = [] {
    std::vector<std::vector<MonomialDerivative3>> all(kMaxLatticeDegree + 1);
    for (int deg = 0; deg <= kMaxLatticeDegree; ++deg)
      for (int m = 0; m < monomial_count3(deg); ++m) {
        int e[3];
        monomial_exponents3(m, e[0], e[1], e[2]);
        MonomialDerivative3 r{};
        for (int i = 0; i < 3; ++i) {
          if (e[i] == 0) {
            r.index[i] = -1;
            r.factor[i] = 0;
            continue;
          }
          int f[3] = {e[0], e[1], e[2]};
          --f[i];
          r.index[i] = monomial_index3(f[0], f[1], f[2]);
          r.factor[i] = e[i];
        }
        all[deg].push_back(r);
      }
    return all;
  }();
  return table[d];
}

// Each degree's inverse on first use (std::call_once: threads may ask together), not all of them at once: a
// process that fits P1 spaces only does not invert the degree-8 Vandermonde matrix (165 x 165).
const std::vector<double>& vandermonde_inverse3(int d) {
  static std::vector<double> inv[kMaxLatticeDegree + 1];
  static std::once_flag made[kMaxLatticeDegree + 1];
  std::call_once(made[d], [d] {
    const int n = monomial_count3(d);
    std::vector<double> v(static_cast<size_t>(n) * n);  // V[p][m] = monomial m at lattice point p
    for (int p = 0; p < n; ++p) monomial_values3(d, lattice_point3(d, p), &v[static_cast<size_t>(p) * n]);
    inv[d] = inverse(v, n);
  });
  return inv[d];
}

}  // namespace dlmfsi
