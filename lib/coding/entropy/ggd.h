// Generalized Gaussian density (GGD) with unit variance, as in Lavu, Choi, Baraniuk
// (SGP 2003), eq. (1), and LoPresto, Ramchandran, Orchard (DCC 1997):
//   f(x) = nu*eta / (2 Gamma(1/nu)) * exp(-(eta |x|)^nu),
//   eta  = sqrt(Gamma(3/nu) / Gamma(1/nu))          (sigma = 1).
// Probabilities and partial moments over [0, t] reduce to the regularized lower
// incomplete gamma function P(a, (eta t)^nu) with a = 1/nu, 2/nu, 3/nu.
//
// Double precision, used offline (table generator) and by the encoder's parameter
// estimation. Nothing the decoder must reproduce bit for bit is computed here.
#pragma once

namespace eqmesh {

// Regularized incomplete gamma functions for a > 0, x >= 0. Both are computed so the
// smaller of the two is accurate to relative precision (series for x < a + 1,
// continued fraction otherwise), which bin masses deep in the tail need.
struct IncompleteGamma {
  double p;  // P(a, x) = gamma(a, x) / Gamma(a)
  double q;  // Q(a, x) = 1 - P(a, x)
};
IncompleteGamma RegularizedGamma(double a, double x);

class UnitGgd {
 public:
  explicit UnitGgd(double shape);

  double shape() const { return nu_; }
  double eta() const { return eta_; }
  double Density(double x) const;

  // Mass, first and second moments of the density over [lo, hi] with 0 <= lo <= hi
  // (hi may be +infinity). Tail differences use Q so tiny masses keep their digits.
  struct Moments {
    double mass = 0;
    double first = 0;   // integral of x f(x)
    double second = 0;  // integral of x^2 f(x)
  };
  Moments OnInterval(double lo, double hi) const;

  // The three regularized gammas at t, so consecutive bins share their common edge.
  struct EdgeGammas {
    double u = 0;  // (eta t)^nu
    IncompleteGamma g[3];
  };
  EdgeGammas AtEdge(double t) const;
  Moments Between(const EdgeGammas& lo, const EdgeGammas& hi) const;

  // E[(eta |X|)^nu ; |X| > t], for the high-rate entropy of a tail.
  double TwoSidedTailPowerMoment(double t) const;
  // log of the density at 0.
  double LogDensityAtZero() const { return log_norm_; }

  // Probability that |X| > t.
  double TwoSidedTail(double t) const;

 private:
  double nu_;
  double eta_;
  double log_norm_;       // log(nu*eta / (2 Gamma(1/nu)))
  double first_scale_;    // Gamma(2/nu) / (2 eta Gamma(1/nu))
};

// E|X| / sqrt(E X^2) of a GGD of shape nu: a scale-free statistic that increases
// monotonically with nu (1/sqrt(3)... -> sqrt(2/pi) at nu = 2), used to fit shapes.
double GgdAbsToRmsRatio(double shape);

}  // namespace eqmesh
