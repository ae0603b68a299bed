#include "validation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "errors.hpp"

namespace dlmfsi {

void check_components(const Basis& basis, const std::vector<int>& components, const std::string& side,
                      const std::string& space) {
  for (int c : components)
    if (c < 0 || c >= basis.components())
      throw Error(side + " component " + std::to_string(c) + " out of range (the " + space + " has " +
                  std::to_string(basis.components()) + ")");
}

namespace {

std::string number(double v) {
  char s[40];
  std::snprintf(s, sizeof s, "%g", v);
  return s;
}

}  // namespace

void check_options(const Basis& fluid_space, const Basis& multiplier, const CouplingOptions& opt) {
  const auto& f = opt.fluid_components;
  const auto& s = opt.solid_components;
  if (f.size() != s.size())
    throw Error("fluid and solid component lists differ in length (" + std::to_string(f.size()) + " and " +
                std::to_string(s.size()) + ")");
  if (f.empty()) throw Error("no components to couple (fluid and solid are empty)");
  check_components(fluid_space, f, "fluid", "fluid space");
  check_components(multiplier, s, "solid", "multiplier space");
  // A pair listed twice would be added twice: the matrix doubled on that block.
  for (size_t q = 0; q < f.size(); ++q)
    for (size_t p = 0; p < q; ++p)
      if (f[p] == f[q] && s[p] == s[q])
        throw Error("the pair fluid component " + std::to_string(f[q]) + " with solid component " +
                    std::to_string(s[q]) + " is listed twice (positions " + std::to_string(p) + " and " +
                    std::to_string(q) + " of fluid= and solid=)");
  if (opt.gradient == CouplingOptions::Gradient::Listing && f.size() != 2)
    throw Error("gradient=\"listing\" needs exactly two component pairs (a 2D vector field)");
  if (!std::isfinite(opt.c1)) throw Error("c1=" + number(opt.c1) + " is not finite");
  if (!std::isfinite(opt.c2)) throw Error("c2=" + number(opt.c2) + " is not finite");
  if (opt.qforder < -1 || opt.qforder > kMaxQforder)
    throw Error("qforder=" + std::to_string(opt.qforder) + " out of range (0 to " + std::to_string(kMaxQforder) +
                "; a rule of degree " + std::to_string(kMaxQforder) + " has 961 points per piece)");
  if (opt.subdivide < -1 || opt.subdivide > kMaxSubdivide)
    throw Error("subdivide=" + std::to_string(opt.subdivide) + " out of range (0 to " +
                std::to_string(kMaxSubdivide) + ": each curved solid triangle is split into 4^subdivide, at most " +
                std::to_string(1 << (2 * kMaxSubdivide)) + ")");
  if (!(opt.tol > 0 && opt.tol < 1)) throw Error("tol=" + number(opt.tol) + " must lie in (0, 1)");
  if (!(opt.outside_tol >= 0)) throw Error("outsidetol=" + number(opt.outside_tol) + " must be >= 0 (not NaN)");
  if (opt.threads < 1) throw Error("threads=" + std::to_string(opt.threads) + " must be at least 1");
  if (opt.parts < 1 || opt.part < 0 || opt.part >= opt.parts)
    throw Error("part=[" + std::to_string(opt.part) + ", " + std::to_string(opt.parts) +
                "] needs 0 <= rank < size");
}

void check_finite(const CsrMatrix& matrix, const CouplingOptions& opt) {
  for (size_t e = 0; e < matrix.value.size(); ++e) {
    if (std::isfinite(matrix.value[e])) continue;
    const auto row = std::upper_bound(matrix.start.begin(), matrix.start.end(), static_cast<int>(e)) - matrix.start.begin() - 1;
    throw Error("the coupling overflows: entry (" + std::to_string(row) + ", " + std::to_string(matrix.column[e]) +
                ") is " + number(matrix.value[e]) + "; c1=" + number(opt.c1) + " and c2=" + number(opt.c2) +
                " are too large for these meshes");
  }
}

}  // namespace dlmfsi
