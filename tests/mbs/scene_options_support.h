#pragma once
// The integrator options a scene's `simulation` section gives: a scene of one rigid box with an
// implicit run to t = 1 s and the given extra lines, loaded through LoadScene.

#include <string>

#include "mbs/ode_integrator.h"

namespace flexmbs::testing {

/// The integrator options of that scene with `extra_lines` (each "  key: value\n") added to its
/// simulation section. Throws what LoadScene throws (InputError for a bad value).
mbs::OdeOptions LoadImplicitIntegratorOptions(const std::string& extra_lines);

}  // namespace flexmbs::testing
