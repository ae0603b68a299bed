#include "fe/rules.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <utility>

#include "errors.hpp"

namespace dlmfsi {

namespace {

// P_n(x) and P_n'(x) by the three-term recurrence (n >= 1, |x| < 1).
void legendre(int n, double x, double& p, double& dp) {
  double p0 = 1, p1 = x;
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  p = p1;
  dp = n * (x * p1 - p0) / (x * x - 1);
}

}  // namespace

void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(n, 0);
  weights.assign(n, 0);
  const double pi = std::acos(-1.0);
  for (int i = 0; i < n; ++i) {
    // Newton on P_n from the Chebyshev-like first guess.
    double x = std::cos(pi * (i + 0.75) / (n + 0.5)), p, dp;
    for (int it = 0; it < 100; ++it) {
      legendre(n, x, p, dp);
      const double dx = p / dp;
      x -= dx;
      if (std::fabs(dx) < 1e-16) break;
    }
    legendre(n, x, p, dp);  // the derivative at the converged node, for the weight 2 / ((1 - x^2) P_n'^2)
    nodes[i] = 0.5 * (1 - x);
    weights[i] = 1.0 / ((1 - x * x) * dp * dp);  // half of the [-1,1] weight
  }
}

namespace {

// The symmetric orbits of a point in barycentric coordinates: (a, a, 1-2a) gives 3 points, (a, b, c) 6.
void orbit3(std::vector<RulePoint>& r, double a, double w) {
  r.push_back({{a, a}, w});
  r.push_back({{1 - 2 * a, a}, w});
  r.push_back({{a, 1 - 2 * a}, w});
}

void orbit6(std::vector<RulePoint>& r, double a, double b, double w) {
  const double c = 1 - a - b;
  for (auto [u, v] : {std::pair{a, b}, std::pair{b, a}, std::pair{a, c}, std::pair{c, a}, std::pair{b, c}, std::pair{c, b}})
    r.push_back({{u, v}, w});
}

// A fully symmetric rule as its orbits: the centroid's weight (0: none), (a, w) of the 3-point orbits and
// (a, b, w) of the 6-point ones (each point's weight w).
struct SymmetricTriangleRule {
  double centroid;
  std::vector<std::array<double, 2>> three;
  std::vector<std::array<double, 3>> six;
};
void add_orbits(std::vector<RulePoint>& r, const SymmetricTriangleRule& rule) {
  if (rule.centroid > 0) r.push_back({{1.0 / 3, 1.0 / 3}, rule.centroid});
  for (const auto& [a, w] : rule.three) orbit3(r, a, w);
  for (const auto& [a, b, w] : rule.six) orbit6(r, a, b, w);
}

std::vector<RulePoint> make_rule(int degree) {
  // Degrees 9 to 20: fully symmetric rules of positive weights and interior points whose nodes and weights were
  // solved for this project (tests/reference/triangle_rules.cpp: Levenberg-Marquardt on the moment equations of an
  // orthonormal basis from random starts, polished in __float128) to a relative residual below 1e-18 on every
  // monomial; Rules tests their exactness.
  std::vector<RulePoint> r;
  if (degree <= 1) {
    r.push_back({{1.0 / 3, 1.0 / 3}, 1.0});
  } else if (degree == 2) {
    orbit3(r, 1.0 / 6, 1.0 / 3);
  } else if (degree == 4) {  // Dunavant
    orbit3(r, 0.445948490915965, 0.223381589678011);
    orbit3(r, 0.091576213509771, 0.109951743655322);
  } else if (degree == 5) {  // Radon
    const double s = std::sqrt(15.0);
    r.push_back({{1.0 / 3, 1.0 / 3}, 9.0 / 40});
    orbit3(r, (6 - s) / 21, (155 - s) / 1200);
    orbit3(r, (6 + s) / 21, (155 + s) / 1200);
  } else if (degree == 6) {  // Dunavant
    orbit3(r, 0.249286745170910, 0.116786275726379);
    orbit3(r, 0.063089014491502, 0.050844906370207);
    orbit6(r, 0.310352451033784, 0.053145049844817, 0.082851075618374);
  } else if (degree == 7 || degree == 8) {  // Dunavant degree 8 (16 points; the product rule of degree 7 has 20)
    r.push_back({{1.0 / 3, 1.0 / 3}, 0.144315607677787});
    orbit3(r, 0.459292588292723, 0.095091634267285);
    orbit3(r, 0.170569307751760, 0.103217370534718);
    orbit3(r, 0.050547228317031, 0.032458497623198);
    orbit6(r, 0.263112829634638, 0.008394777409958, 0.027230314174435);
  } else if (degree <= 10) {  // 25 points
    add_orbits(r, {0.07989450474123971,
                   {{0.42508621060209056, 0.07112380223237734},
                    {0.023308867510000192, 0.008223818690464195}},
                   {{0.6113138261813976, 0.029946031954170886, 0.03735985623430527},
                    {0.6283074002134925, 0.14792562620953445, 0.04543059229617002},
                    {0.14329537042686716, 0.8210720699856294, 0.03088665688456399}}});
  } else if (degree <= 12) {  // 33 points
    add_orbits(r, {0,
                   {{0.2712103850121159, 0.0628582242178851},
                    {0.43972439229446025, 0.043692544538038405},
                    {0.12757614554158592, 0.034796112930708945},
                    {0.48821738977380486, 0.025731066440455336},
                    {0.02131735045321037, 0.006166261051559018}},
                   {{0.115343494534698, 0.6089432357797878, 0.040371557766380926},
                    {0.11625191590759715, 0.8580140335440727, 0.017316231108658892},
                    {0.28132558098993954, 0.022838332222257028, 0.022356773202303445}}});
  } else if (degree <= 14) {  // 42 points
    add_orbits(r, {0,
                   {{0.17720553241254344, 0.042162588736993016},
                    {0.4889639103621786, 0.02188358136942889},
                    {0.019390961248701048, 0.004923403602400082},
                    {0.27347752830883865, 0.051774104507291585},
                    {0.41764471934045394, 0.03278835354412535},
                    {0.0617998830908726, 0.014433699669776668}},
                   {{0.336861459796345, 0.5702222908466832, 0.038571510787060684},
                    {0.29837288213625773, 0.01464695005565441, 0.01443630811353384},
                    {0.05712475740364794, 0.7706085547749965, 0.024665753212563674},
                    {0.8797571713701712, 0.001268330932872025, 0.005010228838500672}}});
  } else if (degree <= 16) {  // 55 points
    add_orbits(r, {0.045336165011820174,
                   {{0.012425572001444092, 0.0021701899268099494},
                    {0.45669426695387466, 0.025995430454676734},
                    {0.0854025394079332, 0.016808612142963718},
                    {0.4917483834189159, 0.014450554675084729}},
                   {{0.6019550183082784, 0.07429547899133068, 0.023303948876596207},
                    {0.640363470419211, 0.20622099278664205, 0.019459968320083402},
                    {0.6612991922259872, 0.014160772533794792, 0.011671172337246865},
                    {0.9121067306168079, 0.07127004615948627, 0.00711372280818943},
                    {0.48506759880447436, 0.32315912848634387, 0.04010893323335543},
                    {0.17807138906021477, 0.014539694958941855, 0.009482262879360846},
                    {0.07127876283214786, 0.7383433055660659, 0.01825823711009689}}});
  } else if (degree <= 18) {  // 67 points
    add_orbits(r, {0.030748521239115856,
                   {{0.07243870556733287, 0.013790286604766938},
                    {0.15163850697260486, 0.020318338845458396},
                    {0.4110671018759195, 0.033471994059847895},
                    {0.003758944341068346, 0.0005320056169477805},
                    {0.4749182113240457, 0.013107027491738756},
                    {0.2656146099053742, 0.03111639660200613}},
                   {{0.38504403441316365, 0.5245289252324957, 0.01532825819455314},
                    {0.9402249256838527, 0.04727614183265178, 0.004217516774744443},
                    {0.6439263069481049, 0.3020619577128708, 0.016365908413986566},
                    {0.7553984164057089, 0.06612245802840339, 0.01691165391748008},
                    {0.014331524778941954, 0.13277883027138934, 0.007641704972719636},
                    {0.14906691012577383, 0.5823597834782123, 0.02759288648857948},
                    {0.41106566867461836, 0.5772425066507145, 0.009586124474361505},
                    {0.2565061597742415, 0.7329888214065166, 0.007729835280006227}}});
  } else if (degree <= 20) {  // 79 points
    add_orbits(r, {0.027820221402906232,
                   {{0.44555105695592484, 0.018904799866464896},
                    {0.39342534781709987, 0.027576101258140917},
                    {0.476245611540499, 0.014203650606816881},
                    {0.18629499774454095, 0.01834692594850583},
                    {0.1093835967117146, 0.015660461552149067},
                    {0.2545792676733391, 0.028166402615040494},
                    {0.037310880598884696, 0.004322550821331155},
                    {0.010976141028397763, 0.0015976815821332397}},
                   {{0.5701446928909734, 0.00983154829280256, 0.007391363000510596},
                    {0.8616840189364867, 0.09995229628813866, 0.008291423055227716},
                    {0.5423318041724281, 0.1398080719917999, 0.023383491463655474},
                    {0.3331348173095875, 0.6118777035474257, 0.017334451134438666},
                    {0.6781657378896355, 0.10622720472027004, 0.01544521564419846},
                    {0.06409058560843406, 0.0048549376076237535, 0.002259739204251731},
                    {0.19851813222878817, 0.7549215028635475, 0.01197279715790938},
                    {0.0075707805046965285, 0.8332955118382362, 0.004405794837116995},
                    {0.010737212856011088, 0.7086813757203236, 0.00715640047691537}}});
  } else {
    std::vector<double> xu, wu, xv, wv;
    gauss_legendre((degree + 3) / 2, xu, wu);
    gauss_legendre((degree + 2) / 2, xv, wv);
    for (size_t i = 0; i < xu.size(); ++i)
      for (size_t j = 0; j < xv.size(); ++j)
        r.push_back({{xu[i], (1 - xu[i]) * xv[j]}, 2 * wu[i] * wv[j] * (1 - xu[i])});
  }
  return r;
}

}  // namespace

namespace {

// Eigenvalues d[0..n) and first components z[0..n) of the normalized eigenvectors of the symmetric
// tridiagonal matrix with diagonal d and off-diagonal e[1..n) (e[0] unused): implicit QL with shifts.
void tridiagonal_eigen(int n, std::vector<double>& d, std::vector<double> e, std::vector<double>& z) {
  z.assign(n, 0.0);
  z[0] = 1;  // the first row of the eigenvector matrix, rotated along with it
  for (int i = 1; i < n; ++i) e[i - 1] = e[i];
  e[n - 1] = 0;
  for (int l = 0; l < n; ++l) {
    for (int iter = 0; iter < 60; ++iter) {
      int m = l;
      for (; m < n - 1; ++m) {
        const double dd = std::fabs(d[m]) + std::fabs(d[m + 1]);
        if (std::fabs(e[m]) + dd == dd) break;
      }
      if (m == l) break;
      double g = (d[l + 1] - d[l]) / (2 * e[l]);
      double r = std::hypot(g, 1.0);
      g = d[m] - d[l] + e[l] / (g + (g >= 0 ? r : -r));
      double s = 1, c = 1, p = 0;
      int i = m - 1;
      for (; i >= l; --i) {
        double f = s * e[i];
        const double b = c * e[i];
        r = std::hypot(f, g);
        e[i + 1] = r;
        if (r == 0) {
          d[i + 1] -= p;
          e[m] = 0;
          break;
        }
        s = f / r;
        c = g / r;
        g = d[i + 1] - p;
        r = (d[i] - g) * s + 2 * c * b;
        p = s * r;
        d[i + 1] = g + p;
        g = c * r - b;
        f = z[i + 1];
        z[i + 1] = s * z[i] + c * f;
        z[i] = c * z[i] - s * f;
      }
      if (r == 0 && i >= l) continue;
      d[l] -= p;
      e[l] = g;
      e[m] = 0;
    }
  }
}

}  // namespace

void gauss_jacobi(int n, int alpha, std::vector<double>& nodes, std::vector<double>& weights) {
  // Jacobi polynomials P^(alpha, 0) on [-1, 1] (weight (1 - x)^alpha): recurrence coefficients
  //   a_k = (beta^2 - alpha^2) / ((2k + s)(2k + s + 2)), s = alpha + beta,
  //   b_k = sqrt(4k (k + alpha)(k + beta)(k + s) / ((2k + s)^2 (2k + s + 1)(2k + s - 1))),
  // mu0 = 2^(alpha + 1) / (alpha + 1); then u = (1 + x) / 2 and w = mu0 z^2 / 2^(alpha + 1).
  const double a = alpha, b = 0, s = a + b;
  std::vector<double> d(n), e(n, 0.0), z;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * k + s;
    d[k] = k == 0 ? (b - a) / (s + 2) : (b * b - a * a) / (t * (t + 2));
    if (k > 0) e[k] = std::sqrt(4.0 * k * (k + a) * (k + b) * (k + s) / (t * t * (t + 1) * (t - 1)));
  }
  tridiagonal_eigen(n, d, e, z);
  nodes.resize(n);
  weights.resize(n);
  for (int i = 0; i < n; ++i) {
    nodes[i] = 0.5 * (1 + d[i]);
    weights[i] = z[i] * z[i] / (alpha + 1);
  }
}

namespace {

// The fully symmetric orbits of the tetrahedron in barycentric coordinates (l0, l1, l2, l3), xi = (l1, l2, l3): the
// distinct permutations of (a, a, a, 1 - 3a) (4 points), (a, a, 1/2 - a, 1/2 - a) (6) and (a, a, b, 1 - 2a - b) (12).
void tet_orbit(std::vector<RulePoint3>& r, double l0, double l1, double l2, double l3, double w) {
  double l[4] = {l0, l1, l2, l3};
  std::sort(l, l + 4);
  do {
    r.push_back({{l[1], l[2], l[3]}, w});
  } while (std::next_permutation(l, l + 4));
}

// A symmetric rule as its orbits: the centroid's weight (0: none), (a, w) of the 4- and 6-point orbits and
// (a, b, w) of the 12-point ones.
struct SymmetricTetRule {
  double centroid;
  std::vector<std::array<double, 2>> four, six;
  std::vector<std::array<double, 3>> twelve;
};
void add_orbits(std::vector<RulePoint3>& r, const SymmetricTetRule& rule) {
  if (rule.centroid > 0) r.push_back({{0.25, 0.25, 0.25}, rule.centroid});
  for (const auto& [a, w] : rule.four) tet_orbit(r, a, a, a, 1 - 3 * a, w);
  for (const auto& [a, w] : rule.six) tet_orbit(r, a, a, 0.5 - a, 0.5 - a, w);
  for (const auto& [a, b, w] : rule.twelve) tet_orbit(r, a, a, b, 1 - 2 * a - b, w);
}

std::vector<RulePoint3> make_tetrahedron_rule(int degree) {
  // Degrees 6 to 9: symmetric rules of positive weights and interior points whose nodes and weights were solved
  // for this project (Levenberg-Marquardt on the moment equations of the monomials of degree <= d, from random
  // starts, in long double: tests/reference/tet_rules.cpp) to a relative residual below 3e-18; Rules3d tests their
  // exactness.
  std::vector<RulePoint3> r;
  if (degree <= 1) {
    r.push_back({{0.25, 0.25, 0.25}, 1.0});
  } else if (degree == 2) {
    const double a = (5 - std::sqrt(5.0)) / 20, b = 1 - 3 * a;
    for (Point3 p : {Point3{a, a, a}, Point3{b, a, a}, Point3{a, b, a}, Point3{a, a, b}}) r.push_back({p, 0.25});
  } else if (degree == 4 || degree == 5) {
    // The symmetric 14-point rule of degree 5: two orbits (a, a, a, 1 - 3a) and one (b, b, 1/2 - b, 1/2 - b)
    // in barycentric coordinates; nodes and weights solved here from the six moment equations of the
    // symmetric polynomials of degree <= 5 (1, e2, e3, e2^2, e4, e2 e3), to round-off.
    auto orbit4 = [&r](double a, double w) {
      const double c = 1 - 3 * a;
      for (Point3 p : {Point3{a, a, a}, Point3{c, a, a}, Point3{a, c, a}, Point3{a, a, c}}) r.push_back({p, w});
    };
    orbit4(0.09273525031089248, 0.07349304311636379);
    orbit4(0.31088591926330084, 0.11268792571801808);
    const double b = 0.045503704125646534, c = 0.5 - b, w = 0.04254602077707878;
    // barycentric (l0, l1, l2, l3) with two entries b and two c; xi = (l1, l2, l3)
    for (Point3 p : {Point3{b, c, c}, Point3{c, b, c}, Point3{c, c, b}, Point3{c, b, b}, Point3{b, c, b}, Point3{b, b, c}})
      r.push_back({p, w});
  } else if (degree == 6) {  // 24 points
    add_orbits(r, {0,
                   {{0.04067395853461135329, 0.01007721105532064302},
                    {0.21460287125915202813, 0.03992275025816749295},
                    {0.32233789014227551059, 0.05535718154365472154}},
                   {},
                   {{0.06366100187501752523, 0.26967233145831580820, 0.04821428571428571417}}});
  } else if (degree == 7) {  // 35 points
    add_orbits(r, {0.09548528946413084351,
                   {{0.31570114977820279816, 0.04232958120996703152}},
                   {{0.44951017740160363154, 0.03189692783285757978}},
                   {{0.02126547254148324585, 0.14663881381848494612, 0.00811077082990334143},
                    {0.18883383102600104725, 0.57517163758700002527, 0.03720713072833462122}}});
  } else if (degree == 8) {  // 46 points
    add_orbits(r, {0,
                   {{0.18539211760901462379, 0.05126301990120182295},
                    {0.31410780894440602188, 0.04212302416359392642},
                    {0.04283141252687828489, 0.00776554864705012116},
                    {0.10930628154107751554, 0.02701792157460298669}},
                   {{0.06462940043521914389, 0.03640704652985120528}},
                   {{0.20407814692684679128, 0.00734203187358797511, 0.01525203919964275186},
                    {0.02138774158259253885, 0.24032851903376047498, 0.00715459943994869309}}});
  } else if (degree == 9) {  // 59 points
    add_orbits(r, {0.05942427407823516444,
                   {{0.03844283845688364696, 0.00491347682899620000},
                    {0.32193410844093379137, 0.03002253210617367433},
                    {0.05894354191779926913, 0.00350221462995435463},
                    {0.16079498373195971036, 0.02508524034080994214}},
                   {{0.10981360578029863471, 0.03774735126099255860}},
                   {{0.03434075911662890041, 0.21318575213272120974, 0.01049500531540353072},
                    {0.45991125650134587655, 0.00136624234012613164, 0.00798908908681615515},
                    {0.18521906312458674877, 0.03309853023840172605, 0.01984905249211971408}}});
  } else {  // the collapsed product of Gauss-Jacobi rules
    const int n = (degree + 2) / 2;
    std::vector<double> xu, wu, xv, wv, xw, ww;
    gauss_jacobi(n, 2, xu, wu);
    gauss_jacobi(n, 1, xv, wv);
    gauss_jacobi(n, 0, xw, ww);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k)
          r.push_back({{xu[i], (1 - xu[i]) * xv[j], (1 - xu[i]) * (1 - xv[j]) * xw[k]}, 6 * wu[i] * wv[j] * ww[k]});
  }
  return r;
}

}  // namespace

const std::vector<RulePoint3>& tetrahedron_rule(int degree) {
  constexpr int kMax = 40;
  if (degree < 0 || degree > kMax) throw Error("quadrature degree " + std::to_string(degree) + " outside [0, 40]");
  static std::vector<RulePoint3> rules[kMax + 1];
  static std::once_flag once;
  std::call_once(once, [] {
    for (int d = 0; d <= kMax; ++d) rules[d] = make_tetrahedron_rule(d);
  });
  return rules[degree];
}

const LineRule& line_rule(int degree) {
  constexpr int kMax = 40;
  if (degree < 0 || degree > kMax) throw Error("quadrature degree " + std::to_string(degree) + " outside [0, 40]");
  static LineRule rules[kMax + 1];
  static std::once_flag once;
  std::call_once(once, [] {
    for (int d = 0; d <= kMax; ++d) gauss_legendre(d / 2 + 1, rules[d].nodes, rules[d].weights);
  });
  return rules[degree];
}

const std::vector<RulePoint>& triangle_rule(int degree) {
  constexpr int kMax = 60;
  if (degree < 0 || degree > kMax) throw Error("quadrature degree " + std::to_string(degree) + " outside [0, 60]");
  static std::vector<RulePoint> rules[kMax + 1];
  static std::once_flag once;
  std::call_once(once, [] {
    for (int d = 0; d <= kMax; ++d) rules[d] = make_rule(d);
  });
  return rules[degree];
}

}  // namespace dlmfsi
