#include "map/split.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "errors.hpp"
#include "geometry/predicates.hpp"

namespace dlmfsi {

namespace {

// Exact identity of a dyadic reference point.
struct Key {
  uint64_t x, y;
  bool operator==(const Key& o) const { return x == o.x && y == o.y; }
};
struct KeyHash {
  size_t operator()(const Key& k) const { return std::hash<uint64_t>()(k.x * 0x9E3779B97F4A7C15ull ^ k.y); }
};
Key key(Point p) {
  Key k;
  std::memcpy(&k.x, &p.x, sizeof k.x);
  std::memcpy(&k.y, &p.y, sizeof k.y);
  return k;
}

struct Tri {
  Point q[3];
  int depth;
};

}  // namespace

Error crossed_chords(int k, int orientation) {
  return Error("the straight image of a part of solid triangle " + std::to_string(k) + " is " +
               (orientation == 0 ? "flat" : "clockwise") +
               " although the map does not fold there (its chords cross): the default curved method integrates it");
}

bool split_image(const MappedTriangle& mt, int level, double target, int max_depth, int max_leaves,
                 std::vector<MapPart>& parts) {
  parts.clear();
  std::unordered_map<Key, Point, KeyHash> image;
  auto image_of = [&](Point xi) {
    auto it = image.find(key(xi));
    if (it != image.end()) return it->second;
    const Point x = mt.at(xi).x;
    if (!std::isfinite(x.x) || !std::isfinite(x.y))
      throw Error("the map is NaN or Inf inside solid triangle " + std::to_string(mt.k));
    image.emplace(key(xi), x);
    return x;
  };
  // Leaves, split until nearly affine.
  std::vector<Tri> leaves, stack{{{{0, 0}, {1, 0}, {0, 1}}, 0}};
  std::vector<double> leaf_nonlinearity;
  while (!stack.empty()) {
    const Tri t = stack.back();
    stack.pop_back();
    double nl = 0;
    if (t.depth >= level) {
      const Point img[3] = {image_of(t.q[0]), image_of(t.q[1]), image_of(t.q[2])};
      nl = nonlinearity_on(mt, t.q, img);
      if (nl <= target) {
        leaves.push_back(t);
        leaf_nonlinearity.push_back(nl);
        continue;
      }
      if (t.depth >= level + max_depth || static_cast<int>(leaves.size() + stack.size()) + 4 > max_leaves) return false;
    }
    const Point m01 = 0.5 * (t.q[0] + t.q[1]), m12 = 0.5 * (t.q[1] + t.q[2]), m20 = 0.5 * (t.q[2] + t.q[0]);
    stack.push_back({{t.q[0], m01, m20}, t.depth + 1});
    stack.push_back({{m01, t.q[1], m12}, t.depth + 1});
    stack.push_back({{m20, m12, t.q[2]}, t.depth + 1});
    stack.push_back({{m12, m20, m01}, t.depth + 1});
  }
  std::unordered_set<Key, KeyHash> corners;
  for (const Tri& t : leaves)
    for (const Point& p : t.q) corners.insert(key(p));
  // The points of finer leaves on edge (a, b), in order from a: the midpoint when it is a corner, recursively.
  std::vector<Point> boundary;
  auto hanging = [&](auto&& self, Point a, Point b) -> void {
    const Point m = 0.5 * (a + b);
    if (!corners.count(key(m))) return;
    self(self, a, m);
    boundary.push_back(m);
    self(self, m, b);
  };
  // A curved image's outer boundary is replaced by the chords between the images of the level-L points
  // on the triangle's edges, whatever the leaves inside: a point between two of them is placed on their
  // chord, at the same fraction. The solid triangle sharing that edge uses the same chords, so the
  // triangles' parts meet without gap or overlap.
  const double steps = std::ldexp(1.0, level);
  auto corner_of_part = [&](Point xi) {
    if (mt.straight) return image_of(xi);
    // the outer edge xi through xi, as the parameter s along it and its end points
    Point from, to;
    double s;
    if (xi.y == 0) {
      s = xi.x;
      from = {0, 0}, to = {1, 0};
    } else if (xi.x == 0) {
      s = xi.y;
      from = {0, 0}, to = {0, 1};
    } else if (xi.x + xi.y == 1) {
      s = xi.y;
      from = {1, 0}, to = {0, 1};
    } else {
      return image_of(xi);
    }
    const double a = std::floor(s * steps) / steps;
    if (a == s) return image_of(xi);
    const double t = (s - a) * steps, b = a + 1 / steps;
    const Point pa = image_of(from + a * (to - from)), pb = image_of(from + b * (to - from));
    return pa + t * (pb - pa);
  };
  auto add = [&](const Point xi[3], double nl) {
    MapPart part;
    for (int i = 0; i < 3; ++i) {
      part.xi[i] = xi[i];
      part.y[i] = corner_of_part(xi[i]);
    }
    part.nonlinearity = nl;
    const int o = orient2d(part.y[0], part.y[1], part.y[2]);
    if (o <= 0) throw crossed_chords(mt.k, o);
    parts.push_back(part);
  };
  for (size_t l = 0; l < leaves.size(); ++l) {
    const Tri& t = leaves[l];
    boundary.clear();
    for (int i = 0; i < 3; ++i) {
      boundary.push_back(t.q[i]);
      hanging(hanging, t.q[i], t.q[(i + 1) % 3]);
    }
    if (boundary.size() == 3) {
      add(t.q, leaf_nonlinearity[l]);
      continue;
    }
    const Point c = (1.0 / 3) * (t.q[0] + t.q[1] + t.q[2]);
    for (size_t i = 0; i < boundary.size(); ++i) {
      const Point fan[3] = {c, boundary[i], boundary[(i + 1) % boundary.size()]};
      add(fan, leaf_nonlinearity[l]);
    }
  }
  return true;
}

}  // namespace dlmfsi
