#pragma once

// Where the checksums' cost goes in writing and reading a `.sid.h5` body (bench_sid_file
// --parts; docs/h5.md, "Cost of the checksums").

#include <filesystem>

#include "sid/reduced_body.h"

namespace flexmbs::bench {

/// Prints, for `body` in one run (CPU s, the fastest of `repeat`): the content digest (SHA-256
/// through OpenSSL) and the two Fletcher32 implementations over its mode shapes, and the mode
/// shapes written and read through HDF5 itself contiguous, chunked without a filter, and
/// chunked with HDF5's Fletcher32 filter at chunk sizes of 64 KiB to 16 MiB, and through
/// flexmbs's h5::Group (chunks written with their checksums by H5Dwrite_chunk), in files in `dir`.
void PrintChecksumParts(const sid::ReducedBody& body, const std::filesystem::path& dir, int repeat);

}  // namespace flexmbs::bench
