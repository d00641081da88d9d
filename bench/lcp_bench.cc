// Complementarity solvers of flexmbs against Siconos numerics 4.4 on the same problems in one run
// (docs/contact.md, "Measured against Siconos"): solve time against the number of contacts, with
// each solver's error (Siconos' own measure, which ours equals) and iterations. The problems are
// stacks of rigid bodies on the ground (tests/contact/complementarity_problems.h): with as many
// bodies as contacts, W = G M^-1 G^T is regular; with ten contacts per body ("rank-deficient") it
// has rank 6 per body. The LCP is the frictionless normal problem (W_NN, q_N) of the regular
// spatial stack; "default" is SolveFrictionContact (NSGS, then Newton). Times are the fastest of
// repeated solves (for at least --seconds each) in CPU seconds of this process, the steadier
// measure on a shared machine; ratio = Siconos' time / ours.
//
//   bench_lcp [--contacts 1,10,100,1000] [--tolerance 1e-8] [--seconds 0.2] [--newton-max 100]
//             [--lemke-max 1000] [--rank-deficient-max 100] [--parts lcp,2,3]
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <stdexcept>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "bench/command_line.h"
#include "contact/complementarity/friction_newton.h"
#include "contact/complementarity/friction_solver.h"
#include "contact/complementarity/lcp_pgs.h"
#include "contact/complementarity/lemke.h"
#include "contact/complementarity/nsgs.h"
#include "contact/complementarity/siconos_solvers.h"
#include "tests/contact/complementarity_problems.h"

namespace flexmbs::bench {
namespace {

using namespace flexmbs::contact;

struct Settings {
  std::vector<int> contacts{1, 10, 100, 1000};
  double tolerance = 1e-8;
  double seconds = 0.2;
  int newton_max = 100;  // largest problem for the dense global Newton solvers (O((d n)^3) per step)
  int lemke_max = 1000;  // largest LCP for the pivoting solvers
  int rank_deficient_max = 100;  // largest rank-deficient friction problem (NSGS needs ~1e4 sweeps)
  std::vector<std::string> parts{"lcp", "2", "3"};  // the LCP, planar and spatial friction tables
};

double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// One timed solver: its result's status and the CPU time of its fastest solve.
struct Timed {
  SolveStatus status;
  double seconds = 0.0;
};

template <class Solve>
Timed Time(const Solve& solve, double budget) {
  Timed t;
  t.seconds = std::numeric_limits<double>::infinity();
  const double start = CpuSeconds();
  do {
    const double before = CpuSeconds();
    t.status = solve();
    t.seconds = std::min(t.seconds, CpuSeconds() - before);
  } while (CpuSeconds() - start < budget);
  return t;
}

std::string Status(const Timed& t) {
  return fmt::format("{:9.3g} s {:6d} it {:9.2g}{}", t.seconds, t.status.iterations, t.status.error,
                     t.status.converged ? "" : " (no conv.)");
}

void Print(const std::string& problem, int contacts, const std::string& ours_name, const Timed& ours,
           const std::string& theirs_name, const Timed& theirs) {
  fmt::print("| {:<26} | {:>5} | {:<8} {} | {:<14} {} | {:7.2f} |\n", problem, contacts, ours_name, Status(ours),
             theirs_name, Status(theirs), theirs.seconds / ours.seconds);
}

void BenchLcp(int contacts, const Settings& s) {
  const FrictionContactProblem fc = testing::RigidBodiesOnGround(3, contacts, contacts, 0.0, 1).problem;
  std::vector<int> normal;
  for (int i = 0; i < contacts; ++i) normal.push_back(3 * i);
  const LcpProblem lcp{fc.W(normal, normal), fc.q(normal)};
  SiconosOptions siconos;
  siconos.tolerance = s.tolerance;
  siconos.max_iterations = 1000000;
  if (contacts <= s.lemke_max) {
    LemkeOptions lemke;
    lemke.tolerance = s.tolerance;
    Print("LCP (frictionless normal)", contacts, "Lemke", Time([&] { return SolveLcpLemke(lcp, lemke); }, s.seconds),
          "Siconos Lemke", Time([&] { return SiconosLcpLemke(lcp, siconos); }, s.seconds));
  }
  PgsOptions pgs;
  pgs.tolerance = s.tolerance;
  pgs.max_iterations = 1000000;
  Print("LCP (frictionless normal)", contacts, "PGS", Time([&] { return SolveLcpPgs(lcp, pgs); }, s.seconds),
        "Siconos PGS", Time([&] { return SiconosLcpPgs(lcp, siconos); }, s.seconds));
}

void BenchFriction(int d, int contacts, bool rank_deficient, const Settings& s) {
  const int bodies = rank_deficient ? std::max(1, contacts / 10) : contacts;
  const FrictionContactProblem fc = testing::RigidBodiesOnGround(d, bodies, contacts, 0.3, 1).problem;
  const std::string problem =
      fmt::format("{}-D friction mu 0.3{}", d, rank_deficient ? ", rank-def." : "");
  SiconosOptions siconos;
  siconos.tolerance = s.tolerance;
  siconos.max_iterations = 100000;
  NsgsOptions nsgs;
  nsgs.tolerance = s.tolerance;
  nsgs.max_iterations = 100000;
  const Timed siconos_nsgs = Time([&] { return SiconosFrictionNsgs(fc, siconos); }, s.seconds);
  Print(problem, contacts, "NSGS", Time([&] { return SolveFrictionNsgs(fc, nsgs); }, s.seconds), "Siconos NSGS",
        siconos_nsgs);
  FrictionContactOptions default_options;
  default_options.tolerance = s.tolerance;
  Print(problem, contacts, "default", Time([&] { return SolveFrictionContact(fc, default_options); }, s.seconds),
        "Siconos NSGS", siconos_nsgs);
  if (contacts > s.newton_max) return;
  FrictionNewtonOptions newton;
  newton.tolerance = s.tolerance;
  newton.max_iterations = 1000;
  const Timed ours_newton = Time([&] { return SolveFrictionNewton(fc, newton); }, s.seconds);
  if (d == 2) {
    Print(problem, contacts, "Newton", ours_newton, "Siconos NSGS", siconos_nsgs);
    return;
  }
  siconos.max_iterations = 1000;
  Print(problem, contacts, "Newton", ours_newton, "Siconos NSN_AC",
        Time([&] { return SiconosFrictionAlartCurnier(fc, siconos); }, s.seconds));
  Print(problem, contacts, "Newton", ours_newton, "Siconos PROX",
        Time([&] { return SiconosFrictionProximal(fc, siconos); }, s.seconds));
}

std::vector<std::string> ParseList(std::string_view text) {
  std::vector<std::string> items;
  std::stringstream stream{std::string(text)};
  std::string item;
  while (std::getline(stream, item, ',')) items.push_back(item);
  return items;
}

Settings Parse(int argc, char** argv) {
  Settings s;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string_view flag = argv[i];
    const char* value = argv[i + 1];
    if (flag == "--contacts") s.contacts = ParseIntList(value);
    else if (flag == "--tolerance") s.tolerance = std::atof(value);
    else if (flag == "--seconds") s.seconds = std::atof(value);
    else if (flag == "--newton-max") s.newton_max = std::atoi(value);
    else if (flag == "--lemke-max") s.lemke_max = std::atoi(value);
    else if (flag == "--rank-deficient-max") s.rank_deficient_max = std::atoi(value);
    else if (flag == "--parts") s.parts = ParseList(value);
    else throw std::invalid_argument(fmt::format("bench_lcp: unknown option '{}'", flag));
  }
  return s;
}

}  // namespace
}  // namespace flexmbs::bench

int main(int argc, char** argv) {
  using namespace flexmbs::bench;
  const Settings s = Parse(argc, argv);
  fmt::print("tolerance {:g} on Siconos' error measure; time: CPU seconds of the fastest solve; ratio = Siconos / ours\n\n",
             s.tolerance);
  fmt::print("| problem | contacts | flexmbs: time, iterations, error | Siconos: time, iterations, error | ratio |\n");
  fmt::print("|---|---:|---|---|---:|\n");
  const auto wanted = [&](const std::string& part) {
    return std::find(s.parts.begin(), s.parts.end(), part) != s.parts.end();
  };
  if (wanted("lcp")) {
    for (int n : s.contacts) BenchLcp(n, s);
  }
  for (int d : {2, 3}) {
    if (!wanted(std::to_string(d))) continue;
    for (bool rank_deficient : {false, true}) {
      for (int n : s.contacts) {
        if (!rank_deficient || n <= s.rank_deficient_max) BenchFriction(d, n, rank_deficient, s);
      }
    }
  }
  return 0;
}
