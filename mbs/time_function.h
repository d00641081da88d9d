#pragma once
// Scalar functions of time with their first and second derivatives: the excitations of drivers
// and loads (docs/mbs.md). Each kind has a one-line factory; the scene reader calls these.

#include <memory>
#include <vector>

namespace flexmbs::mbs {

/// f(t), f'(t) and f''(t) at one time, in the unit of the quantity per s^0, s^1, s^2.
struct TimeFunctionValue {
  double value = 0.0;
  double first_derivative = 0.0;
  double second_derivative = 0.0;
};

/// A scalar function of time t [s]. Immutable; shared by the drivers and loads that use it.
class TimeFunction {
 public:
  virtual ~TimeFunction() = default;
  /// f, f', f'' at t.
  virtual TimeFunctionValue Evaluate(double t) const = 0;
};

using TimeFunctionPtr = std::shared_ptr<const TimeFunction>;

/// f(t) = value.
TimeFunctionPtr MakeConstant(double value);

/// f(t) = offset + slope t.
TimeFunctionPtr MakeRamp(double offset, double slope);

/// f(t) = sum_k coefficients[k] (t - t0)^k (coefficients[0] first; empty gives 0).
TimeFunctionPtr MakePolynomial(std::vector<double> coefficients, double t0 = 0.0);

/// f(t) = amplitude sin(angular_frequency t + phase) + offset; angular_frequency [rad/s],
/// phase [rad].
TimeFunctionPtr MakeHarmonic(double amplitude, double angular_frequency, double phase, double offset);

/// The order of a smooth step: cubic 3s^2 - 2s^3 (continuous f'), quintic 10s^3 - 15s^4 + 6s^5
/// (continuous f'').
enum class SmoothStepOrder { kCubic, kQuintic };

/// f = f0 for t <= t0, f1 for t >= t1, and f0 + (f1 - f0) step((t - t0) / (t1 - t0)) between.
/// Throws InputError unless t1 > t0.
TimeFunctionPtr MakeSmoothStep(double t0, double f0, double t1, double f1, SmoothStepOrder order);

/// A spin-up to a constant rate (Kane, Ryan & Banerjee 1987): the angle [rad]
///   f = offset                                                        t <= 0
///   f = offset + (rate / T) (t^2 / 2 + (T / 2 pi)^2 (cos(2 pi t / T) - 1))   0 < t < T
///   f = offset + rate (t - T / 2)                                     t >= T
/// with f' rising from 0 to `rate` [rad/s] over T = `ramp_time` [s] and f'' = 0 at both ends.
/// Throws InputError unless ramp_time > 0.
TimeFunctionPtr MakeSpinUp(double rate, double ramp_time, double offset = 0.0);

/// The natural cubic spline through (times[k], values[k]) (f'' = 0 at both ends), continued
/// linearly outside [times.front(), times.back()] (so f stays twice continuously
/// differentiable). Throws InputError unless there are >= 2 points of equal count and the times
/// increase strictly.
TimeFunctionPtr MakeCubicSpline(std::vector<double> times, std::vector<double> values);

}  // namespace flexmbs::mbs
