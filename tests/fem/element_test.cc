#include <gtest/gtest.h>

#include "fem/reference_element.h"

namespace flexmbs::fem {
namespace {
TEST(ReferenceElement, Builds) { EXPECT_EQ(ReferenceElement::Of(ElementType::kHex20).num_nodes(), 20); }
}  // namespace
}  // namespace flexmbs::fem
