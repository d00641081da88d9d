// core/fletcher32.h against HDF5's own Fletcher32 (H5_checksum_fletcher32, exported by
// libhdf5 though not in its public headers: the function the Fletcher32 filter calls).
#include "core/fletcher32.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

extern "C" std::uint32_t H5_checksum_fletcher32(const void* data, std::size_t length);

namespace flexmbs {
namespace {

std::uint32_t Hdf5Fletcher32(const std::vector<std::byte>& bytes) {
  return H5_checksum_fletcher32(bytes.data(), bytes.size());
}

TEST(Fletcher32, EqualsHdf5sForEveryLengthUpTo3000Bytes) {
  // Lengths across the 720-byte fold blocks, odd and even, random bytes and the bytes that
  // carry most (all 0xff: every fold meets a sum of 0xffff or more).
  std::mt19937 random(7);
  for (std::size_t length = 0; length <= 3000; ++length) {
    std::vector<std::byte> noise(length), ones(length, std::byte{0xff});
    for (std::byte& b : noise) b = static_cast<std::byte>(random() & 0xff);
    ASSERT_EQ(Fletcher32(noise), Hdf5Fletcher32(noise)) << length << " random bytes";
    ASSERT_EQ(Fletcher32(ones), Hdf5Fletcher32(ones)) << length << " bytes 0xff";
  }
}

TEST(Fletcher32, EqualsHdf5sOnAChunkOfDoubles) {
  // A writer's chunk: 1 MiB of doubles of mixed signs and exponents, then a trailing zero fill.
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> value(-1e3, 1e3);
  std::vector<double> doubles(131072);
  for (std::size_t i = 0; i < doubles.size(); ++i) doubles[i] = i % 5 == 0 ? 0.0 : value(random) * 1e-9 * i;
  std::vector<std::byte> bytes(doubles.size() * sizeof(double));
  std::memcpy(bytes.data(), doubles.data(), bytes.size());
  EXPECT_EQ(Fletcher32(bytes), Hdf5Fletcher32(bytes));
  bytes[1000] ^= std::byte{0x10};
  EXPECT_EQ(Fletcher32(bytes), Hdf5Fletcher32(bytes));
}

}  // namespace
}  // namespace flexmbs
