#pragma once
// The parameter checks the contact laws share: one-line InputErrors naming the parameter and
// its value (the caller adds the file and the item).

#include <string_view>

namespace flexmbs::contact {

/// InputError "<what> <value> must be finite and >= 0" unless value is finite and >= 0.
void RequireNonNegative(std::string_view what, double value);
/// InputError "<what> <value> must be finite and > 0" unless value is finite and > 0.
void RequirePositive(std::string_view what, double value);
/// InputError "restitution <e> must be in (0, 1]" unless 0 < e <= 1.
void RequireRestitution(double restitution);

}  // namespace flexmbs::contact
