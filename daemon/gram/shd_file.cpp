// .shd reading and writing (see shd_file.h).
#include "gram/shd_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace acomms::gram {
namespace {

// Reads typed values out of the file's records, checking every bound.
class Records {
 public:
  Records(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {
    if (bytes.size() < 4) fail(0, "the file is " + std::to_string(bytes.size()) + " bytes; a .shd has at least 4");
    std::int32_t lrecl;
    std::memcpy(&lrecl, bytes.data(), 4);
    if (lrecl < 21 || lrecl > (1 << 24))
      fail(0, "LRecl = " + std::to_string(lrecl) + " words must be within [21, 16777216]");
    words_ = static_cast<std::size_t>(lrecl);
  }
  std::size_t words() const { return words_; }

  template <typename T>
  std::vector<T> read(std::size_t record, std::size_t offset_bytes, std::size_t count, const char* what) const {
    if (offset_bytes + count * sizeof(T) > 4 * words_)
      fail(record, std::string(what) + ": " + std::to_string(count) + " values do not fit in a record of " +
                       std::to_string(words_) + " words");
    const std::size_t start = 4 * words_ * record + offset_bytes;
    if (start + count * sizeof(T) > bytes_.size() || start / (4 * words_) != record)
      fail(record, std::string(what) + ": the file ends (at " + std::to_string(bytes_.size()) + " bytes) before it");
    std::vector<T> out(count);
    if (count) std::memcpy(out.data(), bytes_.data() + start, count * sizeof(T));
    return out;
  }
  [[noreturn]] void fail(std::size_t record, const std::string& why) const {
    throw ShdError(name_ + ": record " + std::to_string(record) + ": " + why);
  }

 private:
  std::string_view bytes_;
  const std::string& name_;
  std::size_t words_ = 0;
};

std::string text_field(const std::vector<char>& chars) {
  std::string s(chars.begin(), chars.end());
  s.erase(std::find(s.begin(), s.end(), '\0'), s.end());
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

template <typename T>
bool plausible_ranges(const std::vector<T>& r) {
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (!std::isfinite(r[i]) || r[i] < 0 || r[i] > 1e9) return false;
    if (i > 0 && r[i] < r[i - 1]) return false;
  }
  return true;
}

template <typename T>
std::vector<double> widen(const std::vector<T>& v) {
  return {v.begin(), v.end()};
}

}  // namespace

ShdField read_shd(std::string_view bytes, const std::string& file_name) {
  Records in(bytes, file_name);
  ShdField f;
  f.title = text_field(in.read<char>(0, 4, 80, "title"));
  f.plot_type = text_field(in.read<char>(1, 0, 10, "PlotType"));
  const auto counts = in.read<std::int32_t>(2, 0, 7, "Nfreq Ntheta NSx NSy NSz NRz NRr");
  static const char* kNames[] = {"Nfreq", "Ntheta", "NSx", "NSy", "NSz", "NRz", "NRr"};
  for (int i = 0; i < 7; ++i)
    if (counts[i] < 1 || counts[i] > (1 << 24))
      in.fail(2, std::string(kNames[i]) + " = " + std::to_string(counts[i]) + " must be within [1, 16777216]");
  f.n_freq = counts[0];
  f.n_theta = counts[1];
  f.n_sx = counts[2];
  f.n_sy = counts[3];
  const std::size_t nsz = counts[4], nrz = counts[5], nrr = counts[6];
  const std::size_t records = static_cast<std::size_t>(f.n_freq) * f.n_theta * nsz * nrz;
  if (records > kShdMaxValues || records * nrr > kShdMaxValues)
    in.fail(2, std::to_string(records) + " × " + std::to_string(nrr) + " pressure values; at most " +
                   std::to_string(kShdMaxValues) + " are read");

  // The layout: record 9 as float64 ranges, else as float32 (spec §7.5).
  bool new_layout = false;
  if (2 * nrr <= in.words()) {
    try {
      new_layout = plausible_ranges(in.read<double>(9, 0, nrr, "Rr"));
    } catch (const ShdError&) {
      new_layout = false;
    }
  }
  if (new_layout) {
    f.layout = ShdLayout::k2023;
    f.theta = in.read<double>(4, 0, f.n_theta, "theta");
    f.sx = in.read<double>(5, 0, f.n_sx, "Sx");
    f.sy = in.read<double>(6, 0, f.n_sy, "Sy");
    f.receiver_range_m = in.read<double>(9, 0, nrr, "Rr");
  } else {
    f.layout = ShdLayout::k2022;
    f.theta = widen(in.read<float>(4, 0, f.n_theta, "theta"));
    f.sx = widen(in.read<float>(5, 0, f.n_sx, "Sx"));
    f.sy = widen(in.read<float>(6, 0, f.n_sy, "Sy"));
    f.receiver_range_m = widen(in.read<float>(9, 0, nrr, "Rr"));
    if (!plausible_ranges(f.receiver_range_m))
      in.fail(9, "Rr is neither float64 nor float32 ranges that are finite, at least 0 and in order");
  }
  f.freq = in.read<double>(3, 0, f.n_freq, "freqVec");
  f.source_depth_m = in.read<float>(7, 0, nsz, "Sz");
  f.receiver_depth_m = in.read<float>(8, 0, nrz, "Rz");
  // Every pressure record must be in the file before any is read (nothing
  // is allocated for a header that claims more than the file holds).
  if (2 * nrr > in.words()) in.fail(2, "NRr = " + std::to_string(nrr) + " complex values do not fit in a record");
  if ((10 + records) * 4 * in.words() > bytes.size() + 4 * in.words())
    in.fail(10 + records - 1, "the file ends (at " + std::to_string(bytes.size()) + " bytes) before the last of " +
                                  std::to_string(records) + " pressure records");
  f.pressure.reserve(records * nrr);
  for (std::size_t k = 0; k < records; ++k) {
    const auto values = in.read<float>(10 + k, 0, 2 * nrr, "pressure");
    for (std::size_t i = 0; i < nrr; ++i) f.pressure.emplace_back(values[2 * i], values[2 * i + 1]);
  }
  return f;
}

namespace {

class RecordWriter {
 public:
  explicit RecordWriter(std::size_t words) : words_(words) {}
  template <typename T>
  void put(std::size_t record, std::size_t offset, const std::vector<T>& values) {
    const std::size_t start = 4 * words_ * record + offset;
    if (bytes_.size() < 4 * words_ * (record + 1)) bytes_.resize(4 * words_ * (record + 1), '\0');
    if (!values.empty()) std::memcpy(bytes_.data() + start, values.data(), values.size() * sizeof(T));
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::size_t words_;
  std::string bytes_;
};

template <typename To>
std::vector<To> narrow(const std::vector<double>& v) {
  return {v.begin(), v.end()};
}

}  // namespace

std::string write_shd(const ShdField& f, ShdLayout layout) {
  const std::size_t nsz = f.source_depth_m.size(), nrz = f.receiver_depth_m.size(), nrr = f.receiver_range_m.size();
  const std::size_t words = std::max<std::size_t>({41, 2 * f.freq.size(), 2 * f.theta.size(), 2 * f.sx.size(),
                                                   2 * f.sy.size(), nsz, nrz, 2 * nrr});
  RecordWriter out(words);
  out.put(0, 0, std::vector<std::int32_t>{static_cast<std::int32_t>(words)});
  std::vector<char> title(80, ' ');
  std::copy_n(f.title.begin(), std::min<std::size_t>(80, f.title.size()), title.begin());
  out.put(0, 4, title);
  std::vector<char> plot(10, ' ');
  std::copy_n(f.plot_type.begin(), std::min<std::size_t>(10, f.plot_type.size()), plot.begin());
  out.put(1, 0, plot);
  out.put(2, 0,
          std::vector<std::int32_t>{static_cast<std::int32_t>(f.freq.size()), static_cast<std::int32_t>(f.theta.size()),
                                    static_cast<std::int32_t>(f.sx.size()), static_cast<std::int32_t>(f.sy.size()),
                                    static_cast<std::int32_t>(nsz), static_cast<std::int32_t>(nrz),
                                    static_cast<std::int32_t>(nrr)});
  out.put(3, 0, f.freq);
  if (layout == ShdLayout::k2023) {
    out.put(2, 28, std::vector<double>{f.freq.empty() ? 0.0 : f.freq[0], 0.0});
    out.put(4, 0, f.theta);
    out.put(5, 0, f.sx);
    out.put(6, 0, f.sy);
    out.put(9, 0, f.receiver_range_m);
  } else {
    out.put(2, 28, std::vector<float>{0.0f});
    out.put(4, 0, narrow<float>(f.theta));
    out.put(5, 0, narrow<float>(f.sx));
    out.put(6, 0, narrow<float>(f.sy));
    out.put(9, 0, narrow<float>(f.receiver_range_m));
  }
  out.put(7, 0, f.source_depth_m);
  out.put(8, 0, f.receiver_depth_m);
  const std::size_t records = nrr ? f.pressure.size() / nrr : 0;
  for (std::size_t k = 0; k < records; ++k) {
    std::vector<float> values(2 * nrr);
    for (std::size_t i = 0; i < nrr; ++i) {
      values[2 * i] = f.pressure[k * nrr + i].real();
      values[2 * i + 1] = f.pressure[k * nrr + i].imag();
    }
    out.put(10 + k, 0, values);
  }
  return out.take();
}

}  // namespace acomms::gram
