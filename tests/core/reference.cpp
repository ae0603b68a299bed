#include "reference.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <vector>

#ifdef DLMFSI_HAVE_CGAL
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#endif

namespace dlmfsi::ref {

namespace {

mpq_class q(double v) { return mpq_class(v); }  // exact: every finite double is a rational

}  // namespace

#ifdef DLMFSI_HAVE_CGAL
bool have_exact() { return true; }

double exact_intersection_area(const Point a[3], const Point b[3]) {
  using K = CGAL::Exact_predicates_exact_constructions_kernel;
  const K::Triangle_2 ta(K::Point_2(a[0].x, a[0].y), K::Point_2(a[1].x, a[1].y), K::Point_2(a[2].x, a[2].y));
  const K::Triangle_2 tb(K::Point_2(b[0].x, b[0].y), K::Point_2(b[1].x, b[1].y), K::Point_2(b[2].x, b[2].y));
  if (ta.is_degenerate() || tb.is_degenerate()) return 0;
  const auto r = CGAL::intersection(ta, tb);
  K::FT area = 0;
  if (r) {
    if (const auto* t = boost::get<K::Triangle_2>(&*r)) {
      area = t->area();
    } else if (const auto* v = boost::get<std::vector<K::Point_2>>(&*r)) {
      for (std::size_t k = 1; k + 1 < v->size(); ++k) area += CGAL::area((*v)[0], (*v)[k], (*v)[k + 1]);
    }  // a point or a segment: area 0
  }
  return std::fabs(CGAL::to_double(CGAL::exact(area)));
}
#else
bool have_exact() { return false; }
double exact_intersection_area(const Point a[3], const Point b[3]) {
  return static_cast<double>(sutherland_hodgman_area(a, b));
}
#endif

double exact_triangle_area(const Point t[3]) {
  const mpq_class d = (q(t[1].x) - q(t[0].x)) * (q(t[2].y) - q(t[0].y)) - (q(t[1].y) - q(t[0].y)) * (q(t[2].x) - q(t[0].x));
  const mpq_class half = d / 2;
  return half.get_d();
}

int exact_orientation(Point a, Point b, Point c) {
  const mpq_class d = (q(b.x) - q(a.x)) * (q(c.y) - q(a.y)) - (q(b.y) - q(a.y)) * (q(c.x) - q(a.x));
  return sgn(d);
}

struct ExactSum::Impl {
  mpq_class s = 0;
};
ExactSum::ExactSum() : impl_(new Impl) {}
ExactSum::~ExactSum() { delete impl_; }
void ExactSum::add(double v) { impl_->s += q(v); }
double ExactSum::value() const { return impl_->s.get_d(); }

long double sutherland_hodgman_area(const Point a[3], const Point b[3]) {
  struct P {
    long double x, y;
  };
  auto ccw = [](const Point t[3], P out[3]) {
    for (int i = 0; i < 3; ++i) out[i] = {t[i].x, t[i].y};
    const long double o = (out[1].x - out[0].x) * (out[2].y - out[0].y) - (out[1].y - out[0].y) * (out[2].x - out[0].x);
    if (o < 0) std::swap(out[1], out[2]);
  };
  P ta[3], tb[3];
  ccw(a, ta);
  ccw(b, tb);
  std::vector<P> poly(ta, ta + 3);
  for (int j = 0; j < 3 && !poly.empty(); ++j) {
    const P p = tb[j], r = tb[(j + 1) % 3];
    auto side = [&](P s) { return (r.x - p.x) * (s.y - p.y) - (r.y - p.y) * (s.x - p.x); };
    std::vector<P> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const P s = poly[i], t = poly[(i + 1) % poly.size()];
      const long double ss = side(s), st = side(t);
      if (ss >= 0) out.push_back(s);
      if ((ss > 0 && st < 0) || (ss < 0 && st > 0)) {
        const long double u = ss / (ss - st);
        out.push_back({s.x + u * (t.x - s.x), s.y + u * (t.y - s.y)});
      }
    }
    poly = out;
  }
  long double area = 0;
  for (std::size_t i = 1; i + 1 < poly.size(); ++i)
    area += (poly[i].x - poly[0].x) * (poly[i + 1].y - poly[0].y) - (poly[i].y - poly[0].y) * (poly[i + 1].x - poly[0].x);
  return std::fabs(area / 2);
}

}  // namespace dlmfsi::ref
