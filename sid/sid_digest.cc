#include "sid/sid_digest.h"

#include <algorithm>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/sha256.h"
#include "core/xxh3.h"
#include "sid/sid_layout.h"

namespace flexmbs::sid {
namespace {

/// Feeds the fields of a body to `Hash` (Sha256 or Xxh3_128) so that no two different bodies
/// give the same bytes.
template <typename Hash>
class BodyHasher {
 public:
  void Text(std::string_view text) {
    Integer(static_cast<std::int64_t>(text.size()));
    hash_.Update(text.data(), text.size());
  }
  void Integer(std::int64_t value) { hash_.Update(&value, sizeof value); }
  /// The number of `items`, then `each` of them in turn.
  template <typename Items, typename Each>
  void Sequence(const Items& items, Each each) {
    Integer(static_cast<std::int64_t>(items.size()));
    for (const auto& item : items) each(item);
  }
  void Texts(const std::vector<std::string>& texts) {
    Sequence(texts, [this](const std::string& t) { Text(t); });
  }
  void Indices(const std::vector<int>& indices) {
    Sequence(indices, [this](int i) { Integer(i); });
  }
  void Matrix(const Eigen::Ref<const Eigen::MatrixXd>& m) {
    Integer(m.rows());
    Integer(m.cols());
    for (Eigen::Index c = 0; c < m.cols(); ++c) {
      hash_.Update(m.col(c).data(), static_cast<std::size_t>(m.rows()) * sizeof(double));
    }
  }
  void Taylor(std::string_view name, const TaylorMatrix& block) {
    Text(name);
    Matrix(block.m0);
    Sequence(block.m1, [this](const Eigen::MatrixXd& m) { Matrix(m); });
    Sequence(block.m2, [this](const Eigen::MatrixXd& m) { Matrix(m); });
  }
  std::string HexDigest() { return hash_.HexDigest(); }

 private:
  Hash hash_;
};

/// `items` (nodes or surfaces) in the order of their names: the order the reader gets them back
/// in (a group's members are listed by name), whatever order the body held them in.
template <typename Item>
std::vector<const Item*> ByName(const std::vector<Item>& items) {
  std::vector<const Item*> sorted;
  for (const Item& item : items) sorted.push_back(&item);
  std::sort(sorted.begin(), sorted.end(), [](const Item* a, const Item* b) { return a->name < b->name; });
  return sorted;
}

/// The digest of `body` with the hash `Hash` (ContentDigest).
template <typename Hash>
std::string DigestWith(const ReducedBody& body) {
  BodyHasher<Hash> h;
  h.Text(body.name);
  h.Matrix(Eigen::Matrix<double, 1, 1>::Constant(body.mass));
  h.Matrix(body.center_of_mass);
  h.Matrix(body.inertia_about_center_of_mass);
  h.Texts(body.mode_names);
  h.Texts(body.mode_kinds);
  h.Matrix(body.frequency_hz);
  h.Matrix(body.relative_residuals);
  h.Text(body.damping);
  for (const layout::InvariantField& field : layout::kInvariants) h.Taylor(field.name, body.*field.member);
  h.Integer(body.stiffening.empty() ? 0 : 1);
  if (!body.stiffening.empty()) {
    for (const Eigen::MatrixXd& K : body.stiffening.K0t) h.Matrix(K);
    for (const Eigen::MatrixXd& K : body.stiffening.K0r) h.Matrix(K);
    for (const Eigen::MatrixXd& K : body.stiffening.K0omega) h.Matrix(K);
  }
  h.Matrix(body.node_positions);
  h.Sequence(body.node_sets, [&h](const auto& set) {
    h.Text(set.first);
    h.Indices(set.second);
  });
  h.Matrix(body.phi);
  h.Sequence(ByName(body.nodes), [&h](const Node* node) {
    h.Text(node->name);
    h.Indices(node->fe_nodes);
    h.Text(node->coupling);
    for (const layout::NodeField& field : layout::kNodeFields) h.Taylor(field.name, node->*field.member);
  });
  h.Sequence(ByName(body.surfaces), [&h](const ContactSurface* surface) {
    h.Text(surface->name);
    h.Indices(surface->fe_nodes);
    h.Matrix(surface->vertices);
    h.Indices(surface->face_sizes);
    h.Indices(surface->face_vertices);
    h.Matrix(surface->face_normals);
    h.Matrix(surface->phi);
  });
  h.Indices(body.visual_surface.face_sizes);
  h.Indices(body.visual_surface.face_nodes);
  return h.HexDigest();
}

}  // namespace

std::string ContentDigest(const ReducedBody& body, DigestAlgorithm algorithm) {
  return algorithm == DigestAlgorithm::kSha256 ? DigestWith<Sha256>(body) : DigestWith<Xxh3_128>(body);
}

}  // namespace flexmbs::sid
