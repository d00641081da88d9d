#pragma once

#include <stdexcept>
#include <string>

namespace flexmbs::mbs {

/// A simulation that cannot go on: the integrator failed (step size too small, too many steps,
/// Newton failure, a state that is no longer finite) or the model broke down (a singular
/// constraint Jacobian). Valid input, so not an InputError; a property of the scene and its
/// settings, so not an InternalError. The message is one line and names the time; time() gives
/// it [s], so a caller can keep the results up to there.
class SimulationError : public std::runtime_error {
 public:
  SimulationError(double time, const std::string& what) : std::runtime_error(what), time_(time) {}
  /// Where the simulation stopped [s].
  double time() const { return time_; }

 private:
  double time_;
};

}  // namespace flexmbs::mbs
