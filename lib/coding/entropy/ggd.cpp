// GGD model: see ggd.h. Incomplete gamma by its power series (x < a + 1) and by the
// modified Lentz evaluation of its continued fraction (x >= a + 1), the textbook
// split (Abramowitz & Stegun 6.5.29 and 6.5.31) written from the formulas.
#include "coding/entropy/ggd.h"

#include <cmath>
#include <limits>

namespace eqmesh {
namespace {

constexpr double kEps = 1e-16;
constexpr int kMaxIter = 2000;

// P(a, x) by the series x^a e^-x / Gamma(a+1) * sum_n x^n / ((a+1)...(a+n)).
double GammaSeries(double a, double x) {
  double term = 1.0 / a;
  double sum = term;
  for (int n = 1; n < kMaxIter; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::fabs(term) < std::fabs(sum) * kEps) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) by the continued fraction e^-x x^a / Gamma(a) * 1/(x+1-a- 1(1-a)/(x+3-a- ...)).
double GammaContinuedFraction(double a, double x) {
  const double tiny = std::numeric_limits<double>::min() / kEps;
  double b = x + 1.0 - a;
  double c = 1.0 / tiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < kMaxIter; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < kEps) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

IncompleteGamma RegularizedGamma(double a, double x) {
  if (x <= 0.0) return {0.0, 1.0};
  if (std::isinf(x)) return {1.0, 0.0};
  if (x < a + 1.0) {
    const double p = GammaSeries(a, x);
    return {p, 1.0 - p};
  }
  const double q = GammaContinuedFraction(a, x);
  return {1.0 - q, q};
}

UnitGgd::UnitGgd(double shape) : nu_(shape) {
  const double lg1 = std::lgamma(1.0 / nu_);
  const double lg2 = std::lgamma(2.0 / nu_);
  const double lg3 = std::lgamma(3.0 / nu_);
  eta_ = std::exp(0.5 * (lg3 - lg1));
  log_norm_ = std::log(nu_ * eta_ / 2.0) - lg1;
  first_scale_ = std::exp(lg2 - lg1) / (2.0 * eta_);
}

double UnitGgd::Density(double x) const {
  return std::exp(log_norm_ - std::pow(eta_ * std::fabs(x), nu_));
}

UnitGgd::EdgeGammas UnitGgd::AtEdge(double t) const {
  EdgeGammas e;
  e.u = std::isinf(t) ? t : std::pow(eta_ * t, nu_);
  for (int k = 0; k < 3; ++k) e.g[k] = RegularizedGamma((k + 1) / nu_, e.u);
  return e;
}

UnitGgd::Moments UnitGgd::Between(const EdgeGammas& lo, const EdgeGammas& hi) const {
  // Each moment k is a scaled difference of regularized gammas at a = (k+1)/nu; the
  // difference is taken on whichever side (P or Q) is small, to avoid cancellation.
  auto diff = [&](int k) {
    const double a = (k + 1) / nu_;
    if (lo.u >= a) return lo.g[k].q - hi.g[k].q;
    return hi.g[k].p - lo.g[k].p;
  };
  Moments m;
  m.mass = 0.5 * diff(0);
  m.first = first_scale_ * diff(1);
  m.second = 0.5 * diff(2);  // unit variance: the full second moment is 1
  return m;
}

UnitGgd::Moments UnitGgd::OnInterval(double lo, double hi) const {
  return Between(AtEdge(lo), AtEdge(hi));
}

double UnitGgd::TwoSidedTail(double t) const {
  return RegularizedGamma(1.0 / nu_, std::pow(eta_ * t, nu_)).q;
}

double UnitGgd::TwoSidedTailPowerMoment(double t) const {
  // (eta|X|)^nu is Gamma(1/nu, 1) distributed; E[U; U > u0] = Gamma(1/nu + 1, u0) / Gamma(1/nu).
  return RegularizedGamma(1.0 / nu_ + 1.0, std::pow(eta_ * t, nu_)).q / nu_;
}

double GgdAbsToRmsRatio(double shape) {
  return std::exp(std::lgamma(2.0 / shape) - 0.5 * (std::lgamma(1.0 / shape) + std::lgamma(3.0 / shape)));
}

}  // namespace eqmesh
