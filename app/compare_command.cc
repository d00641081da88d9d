// `flexmbs compare`: two reduced bases of one body side by side.
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/command_support.h"
#include "app/commands.h"
#include "core/error.h"
#include "reduction/basis_comparison.h"
#include "sid/sid_file.h"

namespace flexmbs::app {
namespace {

struct CompareOptions {
  std::string a;
  std::string b;
  bool json = false;
};

// The largest MAC matrix printed in the text report; JSON always has all of it.
constexpr Eigen::Index kLargestPrintedMac = 24;

// Effective modal mass per axis as a fraction of the body's mass.
Eigen::Vector3d MassFractions(const sid::ReducedBody& body, const Eigen::MatrixXd& effective) {
  return effective.colwise().sum().transpose() / body.mass;
}

void RunCompare(const CompareOptions& options) {
  const sid::ReducedBody a = sid::ReadReducedBody(options.a);
  const sid::ReducedBody b = sid::ReadReducedBody(options.b);
  reduction::BasisComparison c;
  try {
    c = reduction::CompareBases(a, b);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{} and {}: {}", options.a, options.b, e.what()));
  }
  const Eigen::Vector3d fraction_a = MassFractions(a, c.effective_mass_a);
  const Eigen::Vector3d fraction_b = MassFractions(b, c.effective_mass_b);
  if (options.json) {
    nlohmann::json j;
    j["a"] = options.a;
    j["b"] = options.b;
    nlohmann::json pairs = nlohmann::json::array();
    for (const reduction::ModePair& p : c.pairs) {
      pairs.push_back({{"mode_a", a.mode_names[static_cast<std::size_t>(p.a)]},
                       {"mode_b", b.mode_names[static_cast<std::size_t>(p.b)]},
                       {"frequency_a_hz", p.frequency_a_hz}, {"frequency_b_hz", p.frequency_b_hz},
                       {"relative_error", p.relative_error}, {"mac", p.mac}});
    }
    j["pairs"] = pairs;
    j["mac"] = ToJson(c.mac);
    j["effective_mass_kg"] = {{"a", ToJson(c.effective_mass_a)}, {"b", ToJson(c.effective_mass_b)}};
    j["effective_mass_fraction"] = {{"a", ToJson(fraction_a)}, {"b", ToJson(fraction_b)}};
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("A  {} ({} modes)\nB  {} ({} modes)\n\n", options.a, a.phi.cols(), options.b, b.phi.cols());
  fmt::print("{:<24} {:>12}  {:<24} {:>12}  {:>10}  {:>8}\n", "mode A", "f_A [Hz]", "best MAC in B",
             "f_B [Hz]", "error", "MAC");
  for (const reduction::ModePair& p : c.pairs) {
    fmt::print("{:<24} {:>12.6g}  {:<24} {:>12.6g}  {:>+9.4f}%  {:>8.5f}\n", a.mode_names[static_cast<std::size_t>(p.a)],
               p.frequency_a_hz, b.mode_names[static_cast<std::size_t>(p.b)], p.frequency_b_hz,
               100.0 * p.relative_error, p.mac);
  }
  fmt::print("\neffective modal mass / body mass (x, y, z): A {:.4f} {:.4f} {:.4f}, B {:.4f} {:.4f} {:.4f}\n",
             fraction_a(0), fraction_a(1), fraction_a(2), fraction_b(0), fraction_b(1), fraction_b(2));
  if (c.mac.rows() <= kLargestPrintedMac && c.mac.cols() <= kLargestPrintedMac) {
    fmt::print("\nMAC (rows: modes of A, columns: modes of B)\n");
    for (Eigen::Index i = 0; i < c.mac.rows(); ++i) {
      for (Eigen::Index j = 0; j < c.mac.cols(); ++j) fmt::print("{:5.2f}", c.mac(i, j));
      fmt::print("\n");
    }
  }
}

}  // namespace

void AddCompareCommand(CLI::App& app) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Compare two reduced bases of one body: frequency errors, MAC matrix, effective modal mass");
  cmd->add_option("a", options->a, "Reference reduced body (.sid.h5)")->required();
  cmd->add_option("b", options->b, "Reduced body to compare with it (.sid.h5)")->required();
  cmd->add_flag("--json", options->json, "Print the comparison as JSON (keys documented in docs/cli.md)");
  cmd->callback([options] { RunCompare(*options); });
}

}  // namespace flexmbs::app
