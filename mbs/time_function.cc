#include "mbs/time_function.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "core/error.h"

namespace flexmbs::mbs {
namespace {

class Polynomial final : public TimeFunction {
 public:
  Polynomial(std::vector<double> coefficients, double t0) : coefficients_(std::move(coefficients)), t0_(t0) {}

  // Horner's scheme for f, f' and f'' together.
  TimeFunctionValue Evaluate(double t) const override {
    const double s = t - t0_;
    TimeFunctionValue f;
    for (auto c = coefficients_.rbegin(); c != coefficients_.rend(); ++c) {
      f.second_derivative = f.second_derivative * s + 2.0 * f.first_derivative;
      f.first_derivative = f.first_derivative * s + f.value;
      f.value = f.value * s + *c;
    }
    return f;
  }

 private:
  std::vector<double> coefficients_;
  double t0_;
};

class Harmonic final : public TimeFunction {
 public:
  Harmonic(double amplitude, double angular_frequency, double phase, double offset)
      : amplitude_(amplitude), omega_(angular_frequency), phase_(phase), offset_(offset) {}

  TimeFunctionValue Evaluate(double t) const override {
    const double angle = omega_ * t + phase_;
    return {amplitude_ * std::sin(angle) + offset_, amplitude_ * omega_ * std::cos(angle),
            -amplitude_ * omega_ * omega_ * std::sin(angle)};
  }

 private:
  double amplitude_, omega_, phase_, offset_;
};

class SpinUp final : public TimeFunction {
 public:
  SpinUp(double rate, double ramp_time, double offset) : rate_(rate), ramp_time_(ramp_time), offset_(offset) {}

  TimeFunctionValue Evaluate(double t) const override {
    if (t <= 0.0) return {offset_, 0.0, 0.0};
    if (t >= ramp_time_) return {offset_ + rate_ * (t - 0.5 * ramp_time_), rate_, 0.0};
    const double omega = 2.0 * std::numbers::pi / ramp_time_;  // of the ramp's cosine [rad/s]
    const double slope = rate_ / ramp_time_;                     // the mean angular acceleration
    return {offset_ + slope * (0.5 * t * t + (std::cos(omega * t) - 1.0) / (omega * omega)),
            slope * (t - std::sin(omega * t) / omega), slope * (1.0 - std::cos(omega * t))};
  }

 private:
  double rate_, ramp_time_, offset_;
};

class SmoothStep final : public TimeFunction {
 public:
  SmoothStep(double t0, double f0, double t1, double f1, SmoothStepOrder order)
      : t0_(t0), f0_(f0), duration_(t1 - t0), jump_(f1 - f0), order_(order) {}

  TimeFunctionValue Evaluate(double t) const override {
    const double s = std::clamp((t - t0_) / duration_, 0.0, 1.0);
    double step, ds, dds;  // step(s) and its derivatives with respect to s
    if (order_ == SmoothStepOrder::kCubic) {
      step = s * s * (3.0 - 2.0 * s);
      ds = 6.0 * s * (1.0 - s);
      dds = 6.0 - 12.0 * s;
    } else {
      step = s * s * s * (10.0 + s * (-15.0 + 6.0 * s));
      ds = 30.0 * s * s * (1.0 - s) * (1.0 - s);
      dds = 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s);
    }
    if (t <= t0_ || t >= t0_ + duration_) ds = dds = 0.0;
    return {f0_ + jump_ * step, jump_ * ds / duration_, jump_ * dds / (duration_ * duration_)};
  }

 private:
  double t0_, f0_, duration_, jump_;
  SmoothStepOrder order_;
};

// Natural cubic spline in the second-derivative form (Press et al., "Numerical Recipes", 3rd
// ed., sec. 3.3): on [t_k, t_k+1] with A = (t_k+1 - t)/h, B = 1 - A,
// f = A f_k + B f_k+1 + ((A^3 - A) M_k + (B^3 - B) M_k+1) h^2 / 6, M = f'' at the knots.
class CubicSpline final : public TimeFunction {
 public:
  CubicSpline(std::vector<double> times, std::vector<double> values)
      : t_(std::move(times)), f_(std::move(values)), m_(t_.size(), 0.0) {
    // Thomas algorithm for h_k-1 M_k-1 + 2 (h_k-1 + h_k) M_k + h_k M_k+1 = 6 (slope_k - slope_k-1),
    // M_0 = M_n-1 = 0.
    const std::size_t n = t_.size();
    std::vector<double> diagonal(n, 1.0), rhs(n, 0.0), upper(n, 0.0);
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const double h0 = t_[k] - t_[k - 1], h1 = t_[k + 1] - t_[k];
      const double lower = (k == 1) ? 0.0 : h0;
      diagonal[k] = 2.0 * (h0 + h1) - lower * upper[k - 1];
      upper[k] = h1 / diagonal[k];
      rhs[k] = (6.0 * ((f_[k + 1] - f_[k]) / h1 - (f_[k] - f_[k - 1]) / h0) - lower * rhs[k - 1]) / diagonal[k];
    }
    for (std::size_t k = n - 2; k >= 1; --k) m_[k] = rhs[k] - upper[k] * m_[k + 1];
  }

  TimeFunctionValue Evaluate(double t) const override {
    if (t <= t_.front()) return Linear(0, t - t_.front());
    if (t >= t_.back()) return Linear(t_.size() - 1, t - t_.back());
    const std::size_t k = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
    const double h = t_[k + 1] - t_[k];
    const double a = (t_[k + 1] - t) / h, b = 1.0 - a;
    return {a * f_[k] + b * f_[k + 1] + ((a * a * a - a) * m_[k] + (b * b * b - b) * m_[k + 1]) * h * h / 6.0,
            (f_[k + 1] - f_[k]) / h - (3.0 * a * a - 1.0) / 6.0 * h * m_[k] + (3.0 * b * b - 1.0) / 6.0 * h * m_[k + 1],
            a * m_[k] + b * m_[k + 1]};
  }

 private:
  // The tangent line at end knot k (f'' = 0 there), at distance dt from it.
  TimeFunctionValue Linear(std::size_t k, double dt) const {
    const std::size_t interval = (k == 0) ? 0 : k - 1;
    const double h = t_[interval + 1] - t_[interval];
    const double secant = (f_[interval + 1] - f_[interval]) / h;
    // f' at the knots of a natural spline: secant -/+ h M_other / 6.
    const double slope = (k == 0) ? secant - h * m_[1] / 6.0 : secant + h * m_[k - 1] / 6.0;
    return {f_[k] + slope * dt, slope, 0.0};
  }

  std::vector<double> t_, f_, m_;
};

}  // namespace

TimeFunctionPtr MakeConstant(double value) { return MakePolynomial({value}); }

TimeFunctionPtr MakeRamp(double offset, double slope) { return MakePolynomial({offset, slope}); }

TimeFunctionPtr MakePolynomial(std::vector<double> coefficients, double t0) {
  return std::make_shared<Polynomial>(std::move(coefficients), t0);
}

TimeFunctionPtr MakeHarmonic(double amplitude, double angular_frequency, double phase, double offset) {
  return std::make_shared<Harmonic>(amplitude, angular_frequency, phase, offset);
}

TimeFunctionPtr MakeSmoothStep(double t0, double f0, double t1, double f1, SmoothStepOrder order) {
  if (!(t1 > t0)) throw InputError(fmt::format("smooth step: end time {} must be > start time {}", t1, t0));
  return std::make_shared<SmoothStep>(t0, f0, t1, f1, order);
}

TimeFunctionPtr MakeSpinUp(double rate, double ramp_time, double offset) {
  if (!(ramp_time > 0.0)) throw InputError(fmt::format("spin up: ramp time {} must be > 0", ramp_time));
  return std::make_shared<SpinUp>(rate, ramp_time, offset);
}

TimeFunctionPtr MakeCubicSpline(std::vector<double> times, std::vector<double> values) {
  if (times.size() != values.size()) {
    throw InputError(fmt::format("cubic spline: {} times but {} values", times.size(), values.size()));
  }
  if (times.size() < 2) throw InputError(fmt::format("cubic spline: {} points, need >= 2", times.size()));
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(times[k] > times[k - 1])) {
      throw InputError(fmt::format("cubic spline: times must increase strictly: times[{}] = {} after times[{}] = {}",
                                   k, times[k], k - 1, times[k - 1]));
    }
  }
  return std::make_shared<CubicSpline>(std::move(times), std::move(values));
}

}  // namespace flexmbs::mbs
