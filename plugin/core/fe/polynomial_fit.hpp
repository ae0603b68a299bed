// The steps of fitting a basis by polynomials on the reference element that do not depend on the
// dimension (PolynomialBasis on triangles, PolynomialBasis3 on tetrahedra).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <initializer_list>
#include <vector>

#include "fe/basis.hpp"

namespace dlmfsi {

// The basis functions the listed components are carried by, as dof * components + component, sorted,
// each once.
template <int D>
std::vector<int> listed_functions(const BasisOf<D>& basis, const std::vector<int>& components) {
  std::vector<int> functions;
  const int nc = basis.components();
  for (int c : components) {
    int first, last;
    basis.component_dofs(c, first, last);
    for (int d = first; d < last; ++d) functions.push_back(d * nc + c);
  }
  std::sort(functions.begin(), functions.end());
  functions.erase(std::unique(functions.begin(), functions.end()), functions.end());
  return functions;
}

// The monomial coefficients c[f * nm + m] of the functions on element k: interpolation at the nm lattice
// points lattice(q), c = V^-1 values with inverse = V^-1 (row-major) the lattice's Vandermonde inverse;
// monomials(xi, v) writes the nm monomials at xi (V's rows). sample: room for BasisOf::values.
//
// The zeros a function's exact polynomial has (the monomials it lacks: P1b's linear functions have 4 of
// P1b3d's 35) come out as round-off, of the order of u |V^-1 row| max|values|. They are set to exactly zero,
// so that the evaluations skip them (sum_monomials, PolynomialTerms3), when two conditions hold: each is
// below 16 u |V^-1 row m|_1 max|values| (the values' own round-off, a few ulps of the function's size,
// carried by row m), and the fit without them reproduces the lattice values at least as closely as the raw
// fit, up to a factor 2 and 4 ulps (max_q |V c - values|): the interpolant moves by less than its round-off.
template <int D, class Lattice, class Monomials>
void fit_on_lattice(const BasisOf<D>& basis, int k, const std::vector<int>& functions, int nm,
                    const std::vector<double>& inverse, Lattice lattice, Monomials monomials, double* sample,
                    double* c) {
  constexpr int kSlots = BasisOf<D>::kSlots;
  constexpr double u = 0x1p-53;
  const std::size_t width = functions.size(), count = static_cast<std::size_t>(nm);
  std::vector<double> values(count * width), vandermonde(count * count), row_size(count, 0.0);
  for (int q = 0; q < nm; ++q) {
    const auto xi = lattice(q);
    basis.values(k, xi, sample);
    for (std::size_t f = 0; f < width; ++f) values[q * width + f] = sample[functions[f] * kSlots];
    monomials(xi, &vandermonde[q * count]);
  }
  for (std::size_t m = 0; m < count; ++m)
    for (std::size_t q = 0; q < count; ++q) row_size[m] += std::fabs(inverse[m * count + q]);
  std::vector<double> snapped(count);
  // max_q |V a - values of f|
  auto residual = [&](const double* a, std::size_t f) {
    double worst = 0;
    for (std::size_t q = 0; q < count; ++q) {
      double s = -values[q * width + f];
      for (std::size_t m = 0; m < count; ++m) s += vandermonde[q * count + m] * a[m];
      worst = std::max(worst, std::fabs(s));
    }
    return worst;
  };
  for (std::size_t f = 0; f < width; ++f) {
    double* cf = c + f * count;
    double size = 0;
    for (std::size_t q = 0; q < count; ++q) size = std::max(size, std::fabs(values[q * width + f]));
    bool any = false;
    for (std::size_t m = 0; m < count; ++m) {
      double s = 0;
      for (std::size_t q = 0; q < count; ++q) s += inverse[m * count + q] * values[q * width + f];
      cf[m] = s;
      const bool zero = s != 0 && std::fabs(s) <= 16 * u * row_size[m] * size;
      snapped[m] = zero ? 0.0 : s;
      any = any || zero;
    }
    if (any && residual(snapped.data(), f) <= 2 * residual(cf, f) + 4 * u * size)
      std::copy(snapped.begin(), snapped.end(), cf);
  }
}

// out[p] = sum_m c[m] mono[m * n + p], p < n: a fitted function at n points whose monomial values are
// stored monomial by monomial (monomial 0 is 1), summed in the order of the monomials. Zero coefficients
// are skipped (the monomials a sparse basis such as P1b's does not have): the same sums.
inline void sum_monomials(const double* c, int nm, const double* mono, int n, double* out) {
  for (int p = 0; p < n; ++p) out[p] = c[0];
  for (int m = 1; m < nm; ++m) {
    const double cm = c[m];
    if (cm == 0) continue;
    const double* row = mono + static_cast<std::size_t>(m) * n;
    for (int p = 0; p < n; ++p) out[p] += cm * row[p];
  }
}

// Does the fit (nm coefficients per function) give the basis values sample (BasisOf::values' layout) at a
// point where the monomials take the values v? Up to round-off relative to the sum of the terms' sizes.
template <int D>
bool fit_matches(const double* coefficients, int nm, const double* v, const std::vector<int>& functions,
                 const double* sample) {
  for (std::size_t f = 0; f < functions.size(); ++f) {
    double s = 0, scale = 0;
    for (int m = 0; m < nm; ++m) {
      s += coefficients[f * nm + m] * v[m];
      scale += std::fabs(coefficients[f * nm + m] * v[m]);
    }
    if (std::fabs(s - sample[functions[f] * BasisOf<D>::kSlots]) > 1e-12 * (scale + 1)) return false;
  }
  return true;
}

// Are the listed functions' values in sample (BasisOf<D>::values' layout) first (one per function) bit for bit?
// False when first is empty (nothing kept to compare with).
template <int D>
bool same_values(const double* sample, const std::vector<int>& functions, const std::vector<double>& first) {
  if (first.empty()) return false;
  for (std::size_t f = 0; f < functions.size(); ++f)
    if (std::memcmp(&sample[static_cast<std::size_t>(functions[f]) * BasisOf<D>::kSlots], &first[f],
                    sizeof(double)) != 0)
      return false;
  return true;
}

// Does evaluate(xi, out) (BasisOf::evaluate's layout) give the basis on element 0, values and derivatives,
// at the points xi? Relative to the largest entry; sample and check: room for BasisOf::evaluate.
template <int D, class Evaluate>
bool fit_reproduces(const BasisOf<D>& basis, std::initializer_list<typename BasisOf<D>::Reference> points,
                    Evaluate evaluate, const std::vector<int>& functions, double* sample, double* check) {
  constexpr int kSlots = BasisOf<D>::kSlots;
  double worst = 0, scale = 1e-300;
  for (const auto& xi : points) {
    basis.evaluate(0, xi, sample);
    evaluate(xi, check);
    for (int f : functions)
      for (int d = 0; d < kSlots; ++d) {
        worst = std::max(worst, std::fabs(sample[f * kSlots + d] - check[f * kSlots + d]));
        scale = std::max(scale, std::fabs(sample[f * kSlots + d]));
      }
  }
  return !(worst > 1e-9 * scale);
}

// Components of a vector space built from one scalar element carry the same polynomials: per function, an
// earlier function whose coefficients (nm each) equal its own bit for bit and that is no twin itself, or -1.
inline std::vector<int> twin_functions(const std::vector<double>& coefficients, int nm) {
  const std::size_t count = coefficients.size() / nm;
  std::vector<int> twin(count, -1);
  for (std::size_t f = 1; f < count; ++f)
    for (std::size_t g = 0; g < f && twin[f] < 0; ++g)
      if (twin[g] < 0 && std::equal(&coefficients[f * nm], &coefficients[f * nm] + nm, &coefficients[g * nm]))
        twin[f] = static_cast<int>(g);
  return twin;
}

// Do element k's fitted functions add up to 1 (the constant function's degrees of freedom all 1, as for
// Lagrange elements)? Monomial 0 is the constant; the coefficients of the n functions, nm each, from c.
inline bool partition_of_unity(const double* c, int n, int nm) {
  for (int m = 0; m < nm; ++m) {
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += c[static_cast<std::size_t>(i) * nm + m];
    if (std::fabs(sum - (m == 0 ? 1 : 0)) > 1e-10) return false;
  }
  return true;
}

// One element's sum for field_monomials: the count functions' coefficients (n = NM > 0 ? NM : nm each, from c)
// weighted by the values at their dofs (NF > 0: count = NF, both fixed at compile time so the loops unroll).
// sums: where the sums are formed before they are stored to o (o itself, or with NM > 0 a local array the
// compiler keeps in registers: o may alias values and c).
template <int NM, int NF>
inline void field_element(const double* values, const int* dofs, const int* local_dof, int count, const double* c,
                          bool unity, int nm, double* o) {
  const int n = NM > 0 ? NM : nm;
  const int nf = NF > 0 ? NF : count;
  double local[NM > 0 ? NM : 1];
  double* sums = NM > 0 ? local : o;
  const double value = values[dofs[local_dof[0]]];
  if (unity) {
    for (int m = 0; m < n; ++m) sums[m] = 0.0;
    for (int i = 1; i < nf; ++i) {
      const double v = values[dofs[local_dof[i]]] - value;
      const double* ci = c + static_cast<std::size_t>(i) * n;
      for (int m = 0; m < n; ++m) sums[m] += v * ci[m];
    }
    sums[0] += value;
  } else {
    // the first term added to zero (+ 0.0: a -0 term gives +0, as a sum from zero does)
    for (int m = 0; m < n; ++m) sums[m] = value * c[m] + 0.0;
    for (int i = 1; i < nf; ++i) {
      c += n;
      const double v = values[dofs[local_dof[i]]];
      for (int m = 0; m < n; ++m) sums[m] += v * c[m];
    }
  }
  if (NM > 0)
    for (int m = 0; m < n; ++m) o[m] = sums[m];
}

// field_monomials' loop over the elements, for local_dof's functions (count of them, nm monomials each;
// field_element<NM, NF>: NM, NF fixed when nonzero).
template <int NM, int NF, int D, class Fit>
void field_elements(const BasisOf<D>& space, const double* const* values, int fields, const Fit& fit, int nm,
                    const std::vector<int>& local_dof, int first, int last, double* out, std::size_t offset,
                    std::size_t stride) {
  const int nd = space.local_dofs();
  const int* const table = space.dof_table();
  const int count = static_cast<int>(local_dof.size());
  std::vector<int> asked(nd);  // the dofs from dofs() when there is no table
  const double* unity_checked = nullptr;
  bool unity = false;
  for (int k = first; k < last; ++k) {
    double* o = out + static_cast<std::size_t>(k) * stride + offset;
    const int* dofs = asked.data();
    if (table)
      dofs = table + static_cast<std::size_t>(k) * nd;
    else
      space.dofs(k, asked.data());
    const double* c = fit.coefficients(k);
    if (c != unity_checked) {  // elements that share a fit (the same pointer) share the answer
      unity_checked = c;
      unity = partition_of_unity(c, count, nm);
    }
    for (int f = 0; f < fields; ++f, o += nm)
      field_element<NM, NF>(values[f], dofs, local_dof.data(), count, c, unity, nm, o);
  }
}

// Fields' polynomials on the elements [first, last), fields values[0..fields) on one space and fit: out[k *
// stride + offset + f * nm + m] = the coefficient of monomial m, on element k, of the sum over the fitted
// functions g of values[f][global dof of g] * (function g) (Fit: PolynomialBasis or PolynomialBasis3 of nm
// monomials, fitted on space), summed from zero in the functions' order. Where the functions add up to 1
// the sum is taken relative to the first function's value v0, sum_g (v_g - v0) g + v0 (the non-constant
// coefficients without the v0 sum_g c_g = 0 they would carry): a map of an element of size h at distance R
// from 0 then has non-constant coefficients to relative precision eps instead of eps R / h (v_g - v0 is
// exact for values within a factor 2 of each other). An element's dofs are asked once for all the fields.
template <int D, class Fit>
void field_monomials(const BasisOf<D>& space, const double* const* values, int fields, const Fit& fit, int nm,
                     int first, int last, double* out, std::size_t offset, std::size_t stride) {
  std::vector<int> local_dof;
  for (int f : fit.functions()) local_dof.push_back(f / space.components());
  if (local_dof.empty()) {
    for (int k = first; k < last; ++k) {
      double* o = out + static_cast<std::size_t>(k) * stride + offset;
      std::fill(o, o + static_cast<std::size_t>(fields) * nm, 0.0);
    }
    return;
  }
  const int count = static_cast<int>(local_dof.size());
  if (nm == D + 1 && count == D + 1)  // affine maps from P1 or P13d: the loops unrolled
    field_elements<D + 1, D + 1>(space, values, fields, fit, nm, local_dof, first, last, out, offset, stride);
  else if (nm == D + 1)
    field_elements<D + 1, 0>(space, values, fields, fit, nm, local_dof, first, last, out, offset, stride);
  else
    field_elements<0, 0>(space, values, fields, fit, nm, local_dof, first, last, out, offset, stride);
}

// One field: out[k * stride + offset + m] (the same sums).
template <int D, class Fit>
void field_monomials(const BasisOf<D>& space, const double* values, const Fit& fit, int nm, int first, int last,
                     double* out, std::size_t offset, std::size_t stride) {
  field_monomials(space, &values, 1, fit, nm, first, last, out, offset, stride);
}

}  // namespace dlmfsi
