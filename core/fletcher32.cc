#include "core/fletcher32.h"

#include <array>

namespace flexmbs {
namespace {

/// HDF5 folds both sums after this many words: the most that cannot overflow 32 bits.
constexpr std::size_t kBlockWords = 360;
/// Words summed side by side (independent lanes the compiler can vectorise).
constexpr std::size_t kLanes = 8;

std::uint32_t Fold(std::uint32_t sum) { return (sum & 0xffff) + (sum >> 16); }

std::uint32_t Word(const std::byte* p) {
  return (std::to_integer<std::uint32_t>(p[0]) << 8) | std::to_integer<std::uint32_t>(p[1]);
}

}  // namespace

std::uint32_t Fletcher32(std::span<const std::byte> bytes) {
  const std::byte* p = bytes.data();
  std::size_t words = bytes.size() / 2;
  std::uint32_t sum1 = 0, sum2 = 0;
  while (words > 0) {
    const std::size_t block = words < kBlockWords ? words : kBlockWords;
    words -= block;
    // Within a block the sums are exact integers (no fold, no overflow), so they may be
    // regrouped: with the block's words w_i, i = 0 .. n - 1, sum1 gains the sum of w_i and sum2
    // gains n sum1 + the sum of (n - i) w_i. Lane l holds the words i = 8 j + l: a = the sum
    // of its words, b = the sum of (J - j) w_(8j+l) over its J rows; then the sum of (n - i)
    // w_i over the lanes' part (n = 8 J) is 8 (the sum of b) - (the sum of l a_l).
    const std::size_t rows = block / kLanes;
    std::array<std::uint32_t, kLanes> a{}, b{};
    for (std::size_t j = 0; j < rows; ++j, p += 2 * kLanes) {
      for (std::size_t l = 0; l < kLanes; ++l) {
        b[l] += a[l];
        a[l] += Word(p + 2 * l);
      }
    }
    std::uint64_t sum_a = 0, sum_b = 0, lane_weighted = 0;
    for (std::size_t l = 0; l < kLanes; ++l) {
      b[l] += a[l];
      sum_a += a[l];
      sum_b += b[l];
      lane_weighted += l * a[l];
    }
    std::uint32_t s1 = sum1 + static_cast<std::uint32_t>(sum_a);
    std::uint32_t s2 = sum2 + static_cast<std::uint32_t>(kLanes * rows) * sum1 +
                       static_cast<std::uint32_t>(kLanes * sum_b - lane_weighted);
    for (std::size_t i = kLanes * rows; i < block; ++i, p += 2) {
      s1 += Word(p);
      s2 += s1;
    }
    sum1 = Fold(s1);
    sum2 = Fold(s2);
  }
  if (bytes.size() % 2 != 0) {
    sum1 += std::to_integer<std::uint32_t>(*p) << 8;
    sum2 += sum1;
    sum1 = Fold(sum1);
    sum2 = Fold(sum2);
  }
  sum1 = Fold(sum1);
  sum2 = Fold(sum2);
  return (sum2 << 16) | sum1;
}

}  // namespace flexmbs
