// `flexmbs compare`: two reduced bases of one body side by side, or a reduced body's system
// modes against its full FE model.
#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "app/command_support.h"
#include "app/commands.h"
#include "core/error.h"
#include "fem/assembly.h"
#include "fem/body_spec.h"
#include "fem/mass_properties.h"
#include "reduction/basis_comparison.h"
#include "reduction/full_model_modes.h"
#include "reduction/reduction_spec.h"
#include "sid/sid_file.h"

namespace flexmbs::app {
namespace {

struct CompareOptions {
  std::string a;
  std::string b;
  bool json = false;
  int modes = 0;  ///< --modes: the full model's modes; 0: the default (DefaultFullModelModes)
};

// The largest MAC matrix printed in the text report; JSON always has all of it.
constexpr Eigen::Index kLargestPrintedMac = 24;

// The eigensolver of the full model: the serial one, whatever the body file's reduction uses.
constexpr std::string_view kFullModelEigensolver = "spectra";

// What the full-model form compared against: the `full_model` item of the report.
struct FullModelNote {
  std::string method;       ///< the reduction method that decided how the model is held
  std::string method_from;  ///< "provenance" (A's file) or "body_file" (its reduction section)
  std::string held_by;      ///< FullModelConditions::Describe
  Eigen::Index dofs = 0;
  Eigen::Index modes = 0;   ///< full-model modes computed
  Eigen::VectorXd frequency_hz;  ///< of every full-model mode, ascending [Hz]
};

// Both sides compared, with what the report says about them.
struct Compared {
  std::vector<std::string> names_a, names_b;
  double mass_a_kg = 0.0;
  double mass_b_kg = 0.0;
  reduction::ErrorReference reference = reduction::ErrorReference::kA;
  reduction::BasisComparison c;
  std::optional<FullModelNote> full;  ///< set in the full-model form
};

// Whether `path` names a body file (YAML) rather than a reduced body.
bool IsBodyFile(const std::filesystem::path& path) {
  const std::string extension = path.extension().string();
  return extension == ".yaml" || extension == ".yml";
}

// The full model's modes by default: A's system modes and a margin of half as many (at least
// six), so that each of A's modes finds its partner among them.
Eigen::Index DefaultFullModelModes(Eigen::Index system_modes) {
  return system_modes + std::max<Eigen::Index>(6, (system_modes + 1) / 2);
}

Compared CompareTwoBodies(const CompareOptions& options) {
  if (options.modes > 0) {
    throw InputError(fmt::format("--modes {}: only when B is a body file (.yaml), whose full model it sizes",
                                 options.modes));
  }
  const sid::ReducedBody a = sid::ReadReducedBody(options.a);
  const sid::ReducedBody b = sid::ReadReducedBody(options.b);
  Compared out;
  try {
    out.c = reduction::CompareBases(a, b);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{} and {}: {}", options.a, options.b, e.what()));
  }
  out.names_a = a.mode_names;
  out.names_b = b.mode_names;
  out.mass_a_kg = a.mass;
  out.mass_b_kg = b.mass;
  return out;
}

// The reduction method A's basis was made by: from its provenance, checked against the body
// file's reduction section, or from that section if the file does not say.
reduction::ReductionMethod MethodOf(const CompareOptions& options, const sid::ReducedBody& a,
                                    const reduction::ReductionSpec& spec, FullModelNote* note) {
  const auto recorded = a.provenance.find("reduction_method");
  if (recorded == a.provenance.end()) {
    note->method_from = "body_file";
    return spec.method;
  }
  const std::optional<reduction::ReductionMethod> method = reduction::BasisReductionMethod(recorded->second);
  if (!method) {
    throw InputError(fmt::format("{}: provenance reduction_method: '{}' is not a basis flexmbs makes", options.a,
                                 recorded->second));
  }
  if (*method != spec.method) {
    throw InputError(fmt::format("{} and {}: A was reduced by {} (its provenance), the body file's reduction section "
                                 "asks for {}: compare a reduced body with the body file it was reduced from",
                                 options.a, options.b, reduction::MethodName(*method),
                                 reduction::MethodName(spec.method)));
  }
  note->method_from = "provenance";
  return *method;
}

// A's system modes against the full FE model of body file B, meshed and assembled as `reduce`
// does and constrained as A's basis constrains its system modes (reduction/full_model_modes.h).
Compared CompareWithFullModel(const CompareOptions& options) {
  const sid::ReducedBody a = sid::ReadReducedBody(options.a);
  const fem::BodySpec body = fem::LoadBodySpec(options.b);
  const reduction::ReductionSpec spec = reduction::LoadReductionSpec(options.b, body.node_sets);
  FullModelNote note;
  const reduction::ReductionMethod method = MethodOf(options, a, spec, &note);
  note.method = reduction::MethodName(method);

  Progress progress;
  progress.Show(fmt::format("meshing {} ...", body.geometry_file.string()));
  const fem::Mesh mesh = fem::BuildBodyMesh(body);
  try {
    reduction::CheckSameMesh(a.node_positions, mesh.nodes);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{} and {}: {}: compare a reduced body with the body file it was reduced from",
                                 options.a, options.b, e.what()));
  }
  progress.Show(fmt::format("assembling {} DOF ...", mesh.num_dofs()));
  const fem::SystemMatrices system = fem::AssembleBodySystem(body, mesh);
  const reduction::FeModel model(system.stiffness, system.mass, mesh.nodes);
  const reduction::FullModelConditions held =
      reduction::SystemModeConditions(method, reduction::ResolveConditions(spec, mesh.node_sets));
  note.held_by = held.Describe();
  note.dofs = mesh.num_dofs();

  Compared out;
  out.reference = reduction::ErrorReference::kB;
  const double zero_eigenvalue =
      eigensolvers::kZeroEigenvalue * system.stiffness.diagonal().sum() / system.mass.diagonal().sum();
  reduction::ModeSet reduced;
  try {
    reduced = reduction::SystemModes(a, zero_eigenvalue);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", options.a, e.what()));
  }
  const Eigen::Index count = options.modes > 0 ? options.modes : DefaultFullModelModes(reduced.size());
  progress.Show(fmt::format("solving the full model for {} modes ...", count));
  reduction::ModeSet full;
  try {
    const reduction::ReducedBasis basis =
        reduction::FullModelModes(model, held, count, *eigensolvers::MakeEigensolver(kFullModelEigensolver));
    full = reduction::BasisModes(basis, model);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: full model ({}): {}", options.b, note.held_by, e.what()));
  }
  progress.Clear();
  note.modes = full.size();
  note.frequency_hz = full.frequency_hz;
  out.c = reduction::CompareModes(reduced, full, out.reference);
  out.names_a = std::move(reduced.names);
  out.names_b = std::move(full.names);
  out.mass_a_kg = a.mass;
  out.mass_b_kg = fem::MassPropertiesFromMassMatrix(system.mass, mesh.nodes).mass_kg;
  out.full = note;
  return out;
}

// Effective modal mass per axis as a fraction of the body's mass.
Eigen::Vector3d MassFractions(double mass_kg, const Eigen::MatrixXd& effective) {
  return effective.colwise().sum().transpose() / mass_kg;
}

// "f_B / f_A - 1" or "f_A / f_B - 1".
std::string ErrorDefinition(reduction::ErrorReference reference) {
  return reference == reduction::ErrorReference::kA ? "f_B / f_A - 1" : "f_A / f_B - 1";
}

void PrintJson(const CompareOptions& options, const Compared& r) {
  const reduction::BasisComparison& c = r.c;
  nlohmann::json j;
  j["a"] = options.a;
  j["b"] = options.b;
  j["error_reference"] = r.reference == reduction::ErrorReference::kA ? "a" : "b";
  nlohmann::json pairs = nlohmann::json::array();
  for (const reduction::ModePair& p : c.pairs) {
    pairs.push_back({{"mode_a", r.names_a[static_cast<std::size_t>(p.a)]},
                     {"mode_b", r.names_b[static_cast<std::size_t>(p.b)]},
                     {"frequency_a_hz", p.frequency_a_hz}, {"frequency_b_hz", p.frequency_b_hz},
                     {"relative_error", p.relative_error}, {"mac", p.mac}});
  }
  j["pairs"] = pairs;
  j["mac"] = ToJson(c.mac);
  j["effective_mass_kg"] = {{"a", ToJson(c.effective_mass_a)}, {"b", ToJson(c.effective_mass_b)}};
  j["effective_mass_fraction"] = {{"a", ToJson(MassFractions(r.mass_a_kg, c.effective_mass_a))},
                                  {"b", ToJson(MassFractions(r.mass_b_kg, c.effective_mass_b))}};
  if (r.full) {
    j["full_model"] = {{"method", r.full->method}, {"method_from", r.full->method_from},
                       {"held_by", r.full->held_by}, {"dofs", r.full->dofs}, {"modes", r.full->modes},
                       {"frequency_hz", ToJson(r.full->frequency_hz)}, {"eigensolver", kFullModelEigensolver}};
  }
  fmt::print("{}\n", j.dump(2));
}

void PrintText(const CompareOptions& options, const Compared& r) {
  const reduction::BasisComparison& c = r.c;
  if (r.full) {
    fmt::print("A  {}: {} system modes (eigenpairs of its reduced Ke, Me, expanded by its basis)\n", options.a,
               r.names_a.size());
    fmt::print("B  {}: full FE model, {} DOF, {} lowest modes, constrained as A's {} basis constrains its system "
               "modes: {} (method from {})\n\n", options.b, r.full->dofs, r.full->modes, r.full->method, r.full->held_by,
               r.full->method_from == "provenance" ? "A's provenance" : "the body file");
  } else {
    fmt::print("A  {} ({} modes)\nB  {} ({} modes)\n\n", options.a, r.names_a.size(), options.b, r.names_b.size());
  }
  fmt::print("{:<24} {:>12}  {:<24} {:>12}  {:>10}  {:>8}\n", "mode A", "f_A [Hz]", "best MAC in B",
             "f_B [Hz]", "error", "MAC");
  for (const reduction::ModePair& p : c.pairs) {
    fmt::print("{:<24} {:>12.6g}  {:<24} {:>12.6g}  {:>+9.4f}%  {:>8.5f}\n", r.names_a[static_cast<std::size_t>(p.a)],
               p.frequency_a_hz, r.names_b[static_cast<std::size_t>(p.b)], p.frequency_b_hz,
               100.0 * p.relative_error, p.mac);
  }
  fmt::print("error = {}\n", ErrorDefinition(r.reference));
  const Eigen::Vector3d fraction_a = MassFractions(r.mass_a_kg, c.effective_mass_a);
  const Eigen::Vector3d fraction_b = MassFractions(r.mass_b_kg, c.effective_mass_b);
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

void RunCompare(const CompareOptions& options) {
  const Compared r = IsBodyFile(options.b) ? CompareWithFullModel(options) : CompareTwoBodies(options);
  if (options.json) {
    PrintJson(options, r);
  } else {
    PrintText(options, r);
  }
}

}  // namespace

void AddCompareCommand(CLI::App& app) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare two reduced bases of one body, or a reduced body's system modes with its full FE model: frequency "
      "errors, MAC matrix, effective modal mass");
  cmd->add_option("a", options->a, "Reduced body (.sid.h5)")->required();
  cmd->add_option("b", options->b,
                  "Reduced body of the same mesh (.sid.h5), or the body file A was reduced from (.yaml, .yml): its "
                  "full FE model")
      ->required();
  cmd->add_flag("--json", options->json, "Print the comparison as JSON (keys documented in docs/cli.md)");
  cmd->add_option("--modes", options->modes,
                  "Full-model modes to compute (B a body file; default: A's system modes plus half as many, at "
                  "least 6 more)")
      ->check(WholeNumberAtLeastOne());
  cmd->callback([options] { RunCompare(*options); });
}

}  // namespace flexmbs::app
