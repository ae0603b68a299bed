#include "solid/law_assembly.hpp"

#include <algorithm>
#include <string>

#include "errors.hpp"

namespace dlmfsi {

RuleGradients::RuleGradients(const Basis& basis, int elements, const std::vector<int>& components,
                             const std::vector<RulePoint>& rule)
    : elements_(elements), points_(static_cast<int>(rule.size())), components_(static_cast<int>(components.size())),
      dof_count_(basis.dof_count()) {
  const int nc = basis.components(), nd = basis.local_dofs();
  if (components_ < 1 || components_ > 2) throw Error("RuleGradients: one or two components");
  for (int c : components)
    if (c < 0 || c >= nc)
      throw Error("component " + std::to_string(c) + " out of range (the space has " + std::to_string(nc) + ")");
  if (components_ == 2 && components[0] == components[1])
    throw Error("the two position components are the same (" + std::to_string(components[0]) + ")");
  if (points_ < 1) throw Error("the rule has no points");
  // the local dofs carrying a listed component, in increasing order
  std::vector<char> carries(nd, 0);
  for (int c : components) {
    int first = 0, last = 0;
    basis.component_dofs(c, first, last);
    for (int df = first; df < last; ++df) carries[df] = 1;
  }
  for (int df = 0; df < nd; ++df)
    if (carries[df]) local_.push_back(df);
  const size_t nf = local_.size();
  stride_ = nf * components_ * 2;
  dofs_.resize(static_cast<size_t>(elements) * nf);
  gradients_.resize(static_cast<size_t>(elements) * points_ * stride_);
  std::vector<int> all(nd);
  std::vector<double> out(static_cast<size_t>(nd) * nc * Basis::kSlots);
  for (int k = 0; k < elements; ++k) {
    basis.dofs(k, all.data());
    for (size_t f = 0; f < nf; ++f) dofs_[k * nf + f] = all[local_[f]];
    for (int q = 0; q < points_; ++q) {
      basis.evaluate(k, rule[q].xi, out.data());
      double* g = &gradients_[(static_cast<size_t>(k) * points_ + q) * stride_];
      for (size_t f = 0; f < nf; ++f)
        for (int c = 0; c < components_; ++c)
          for (int d = 0; d < 2; ++d)
            g[(f * components_ + c) * 2 + d] = out[(static_cast<size_t>(local_[f]) * nc + components[c]) * Basis::kSlots + 1 + d];
    }
  }
}

namespace {

void check(const LawProblem& p) {
  if (!p.position || !p.x.gradients || !p.y.gradients || !p.rule || !p.areas || !p.x.coefficients ||
      !p.y.coefficients)
    throw Error("the law's problem is incomplete");
  if (p.position->components() != 2) throw Error("the position needs two components");
  const int n = p.position->elements();
  for (const RuleGradients* g : {p.x.gradients, p.y.gradients}) {
    if (g->components() != 1) throw Error("a map component is one component of its space");
    if (g->elements() != n) throw Error("the map is not defined on the mesh of the position's space");
    if (g->points() != p.position->points()) throw Error("the map is tabulated on another rule");
  }
  if (p.position->points() != static_cast<int>(p.rule->size())) throw Error("the position is tabulated on another rule");
  if (static_cast<int>(p.areas->size()) != n) throw Error("one area per solid triangle expected");
  if (p.first < 0 || p.first > n || (p.last >= 0 && (p.last < p.first || p.last > n)))
    throw Error("the elements " + std::to_string(p.first) + " .. " + std::to_string(p.last) + " are not a range of the " +
                std::to_string(n) + " solid triangles");
}

int last_element(const LawProblem& p) { return p.last < 0 ? p.position->elements() : p.last; }

// Fl = Grad [XL, YL] at point q of element k, row by row.
Gradient2 map_gradient(const LawProblem& p, int k, int q) {
  Gradient2 fl{};
  for (int r = 0; r < 2; ++r) {
    const MapComponent& m = r == 0 ? p.x : p.y;
    const double* g = m.gradients->at(k, q);
    const int* dofs = m.gradients->dofs(k);
    const int nf = m.gradients->functions();
    double dx = 0, dy = 0;
    for (int f = 0; f < nf; ++f) {
      const double c = m.coefficients[dofs[f]];
      dx += c * g[2 * f];
      dy += c * g[2 * f + 1];
    }
    fl[2 * r] = dx;
    fl[2 * r + 1] = dy;
  }
  return fl;
}

// e's message without the prefix Error adds, behind "solid triangle k: ".
[[noreturn]] void at_element(int k, const Error& e) {
  const std::string what = e.what(), prefix = Error("").what();
  throw Error("solid triangle " + std::to_string(k) + ": " + what.substr(what.rfind(prefix, 0) == 0 ? prefix.size() : 0));
}

}  // namespace

const CsrMatrix& LawAssembly::matrix(const LawProblem& p, const std::vector<Triplet>* plus) {
  check(p);
  const int n = p.position->dof_count();
  triplets_[1].clear();
  if (plus) {
    for (const Triplet& e : *plus)
      if (e.row < 0 || e.row >= n || e.col < 0 || e.col >= n)
        throw Error("the matrix added (plus=) has an entry (" + std::to_string(e.row) + ", " + std::to_string(e.col) +
                    ") outside " + std::to_string(n) + " x " + std::to_string(n));
    triplets_[1] = *plus;
  }
  const RuleGradients& pos = *p.position;
  const int nf = pos.functions(), np = pos.points();
  std::vector<Triplet>& triplets = triplets_[0];
  triplets.clear();
  const int last = last_element(p);
  triplets.reserve(static_cast<size_t>(last - p.first) * nf * nf);
  std::vector<double> ke(static_cast<size_t>(nf) * nf), th(static_cast<size_t>(nf) * 4);
  double t[16];
  for (int k = p.first; k < last; ++k) {
    std::fill(ke.begin(), ke.end(), 0.0);
    for (int q = 0; q < np; ++q) {
      try {
        tangent(p.law, p.constants, map_gradient(p, k, q), t);
      } catch (const Error& e) {
        at_element(k, e);
      }
      const double wa = (*p.areas)[k] * (*p.rule)[q].weight;
      const double* g = pos.at(k, q);  // function f's gradient: g[4 f .. 4 f + 3], row by row
      for (int b = 0; b < nf; ++b)
        for (int i = 0; i < 4; ++i)
          th[4 * b + i] = wa * (t[4 * i] * g[4 * b] + t[4 * i + 1] * g[4 * b + 1] + t[4 * i + 2] * g[4 * b + 2] +
                                t[4 * i + 3] * g[4 * b + 3]);
      for (int a = 0; a < nf; ++a) {
        const double* ga = g + 4 * a;
        double* row = &ke[static_cast<size_t>(a) * nf];
        for (int b = 0; b < nf; ++b) {
          const double* tb = &th[4 * b];
          row[b] += ga[0] * tb[0] + ga[1] * tb[1] + ga[2] * tb[2] + ga[3] * tb[3];
        }
      }
    }
    const int* dofs = pos.dofs(k);
    for (int a = 0; a < nf; ++a)
      for (int b = 0; b < nf; ++b) triplets.emplace_back(dofs[a], dofs[b], ke[static_cast<size_t>(a) * nf + b]);
  }
  return sum(n);
}

const CsrMatrix& LawAssembly::sum(int n) {
  if (matrix_.rows == n && matrix_.cols == n) {
    in_place_.start(matrix_);
    if (in_place_.sum_rows(0, n, triplets_.data(), triplets_.size())) return matrix_;
  }
  matrix_ = compress(n, n, triplets_);
  return matrix_;
}

void LawAssembly::rhs(const LawProblem& p, std::vector<double>& out) const {
  check(p);
  const RuleGradients& pos = *p.position;
  const int nf = pos.functions(), np = pos.points();
  out.assign(pos.dof_count(), 0.0);
  const int last = last_element(p);
  for (int k = p.first; k < last; ++k) {
    const int* dofs = pos.dofs(k);
    for (int q = 0; q < np; ++q) {
      Gradient2 r{};
      try {
        r = linearization_stress(p.law, p.constants, map_gradient(p, k, q));
      } catch (const Error& e) {
        at_element(k, e);
      }
      const double wa = (*p.areas)[k] * (*p.rule)[q].weight;
      const double* g = pos.at(k, q);
      for (int a = 0; a < nf; ++a) {
        const double* ga = g + 4 * a;
        out[dofs[a]] += wa * (r[0] * ga[0] + r[1] * ga[1] + r[2] * ga[2] + r[3] * ga[3]);
      }
    }
  }
}

}  // namespace dlmfsi
