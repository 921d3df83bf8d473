// BELLHOP's binary pressure field (.shd, spec §7.5), read and written.
//
// Problem: the external engine answers in a file of fixed-length records
// whose layout changed in 2023 (float64 ranges, angles and source
// positions) and whose header says nothing about which layout it is.
// Decision: the spec's rule — record 9 read as float64 must give finite,
// non-negative, non-decreasing ranges, else the ≤ 2022 float32 layout is
// tried the same way; neither: refused. Every count and offset is checked
// against the file's size before it is used (the reader is fuzzed:
// tests/fuzz/gram_shd_fuzz.cpp); an error names the file, the record and
// the bound. Thread-safe: pure functions.
#pragma once

#include <complex>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace acomms::gram {

class ShdError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ShdLayout { k2023, k2022 };

struct ShdField {
  ShdLayout layout = ShdLayout::k2023;
  std::string title;      // record 0, trailing blanks removed
  std::string plot_type;  // record 1
  std::int32_t n_freq = 1, n_theta = 1, n_sx = 1, n_sy = 1;
  std::vector<double> freq, theta, sx, sy;
  std::vector<float> source_depth_m, receiver_depth_m;
  std::vector<double> receiver_range_m;
  // p[((ifreq·Ntheta + itheta)·NSz + isz)·NRz + irz][ir], flattened with
  // NRr per record.
  std::vector<std::complex<float>> pressure;
};

// Limits on what a reader accepts (a file is outside input).
inline constexpr std::size_t kShdMaxValues = 64u << 20;  // complex values

ShdField read_shd(std::string_view bytes, const std::string& file_name);

// The file of `field` in `layout` (for tests and stand-in engines).
std::string write_shd(const ShdField& field, ShdLayout layout);

}  // namespace acomms::gram
