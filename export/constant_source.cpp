#include "export/constant_source.hpp"

#include <bit>
#include <cmath>
#include <cstdio>

namespace thetad {

namespace {

// export/onboard/step_common.hpp's fnv1a on one value's bit pattern, least significant byte first.
template <class Bits>
std::uint64_t fnv1a(Bits bits, std::uint64_t hash) {
  for (unsigned byte = 0; byte < sizeof(Bits); ++byte) {
    hash ^= static_cast<std::uint64_t>((bits >> (8 * byte)) & 0xffu);
    hash *= 0x100000001b3ull;
  }
  return hash;
}

std::string hexadecimal(std::uint64_t value) {
  char text[32];
  std::snprintf(text, sizeof text, "0x%016llxull", static_cast<unsigned long long>(value));
  return text;
}

}  // namespace

std::string exact_literal(double value) {
  if (std::isnan(value)) return "std::numeric_limits<double>::quiet_NaN()";
  if (std::isinf(value)) return value > 0 ? "std::numeric_limits<double>::infinity()" : "-std::numeric_limits<double>::infinity()";
  char text[40];
  std::snprintf(text, sizeof text, "%a", value);
  return text;
}

std::vector<double> row_major(const Eigen::MatrixXd& matrix) {
  std::vector<double> values;
  for (Eigen::Index r = 0; r < matrix.rows(); ++r)
    for (Eigen::Index c = 0; c < matrix.cols(); ++c) values.push_back(matrix(r, c));
  return values;
}

std::vector<double> entries(const Eigen::VectorXd& vector) { return {vector.data(), vector.data() + vector.size()}; }

std::string literal_list(const std::vector<double>& values, const char* wrap_open, const char* wrap_close,
                         int per_line) {
  std::string s;
  for (std::size_t i = 0; i < values.size(); ++i) {
    s += i % static_cast<std::size_t>(per_line) == 0 ? "\n      " : " ";
    s += wrap_open + exact_literal(values[i]) + wrap_close + ",";
  }
  return s;
}

void DesignSource::add_array(const std::string& name, const std::vector<double>& values) {
  const std::vector<double> stored = values.empty() ? std::vector<double>{0.0} : values;
  members_ += "  static constexpr T " + name + "[" + std::to_string(stored.size()) + "] = {" +
              literal_list(stored, "T(", ")") + "\n  };\n";
  arrays_.emplace_back(name, stored.size());
  for (const double value : stored) {
    checksum_double_ = fnv1a(std::bit_cast<std::uint64_t>(value), checksum_double_);
    checksum_float_ = fnv1a(std::bit_cast<std::uint32_t>(static_cast<float>(value)), checksum_float_);
  }
}

void DesignSource::add_indices(const std::string& name, const std::vector<int>& values) {
  std::string list;
  for (std::size_t i = 0; i < values.size(); ++i) list += (i % 24 == 0 ? "\n      " : " ") + std::to_string(values[i]) + ",";
  members_ += "  static constexpr int " + name + "[" + std::to_string(values.size()) + "] = {" + list + "\n  };\n";
}

void DesignSource::add_scalar(const std::string& name, double value) {
  members_ += "  static constexpr T " + name + " = T(" + exact_literal(value) + ");\n";
}

void DesignSource::add_integer(const std::string& name, long long value) {
  members_ += "  static constexpr int " + name + " = " + std::to_string(value) + ";\n";
}

std::string DesignSource::source(const std::string& name) const {
  std::string s = "template <class T>\nstruct " + name + " {\n" + members_ + "};\n\n";
  s += "// The arrays' FNV-1a checksum in the scalar type they are stored in: data_intact<T>() compares\n"
       "// it with the generator's, e.g. at start-up, to find a corrupted flash image.\n";
  s += "inline constexpr std::uint64_t kChecksumDouble = " + hexadecimal(checksum_double_) + ";\n";
  s += "inline constexpr std::uint64_t kChecksumFloat = " + hexadecimal(checksum_float_) + ";\n";
  s += "template <class T>\nstd::uint64_t data_checksum() {\n  std::uint64_t hash = thetad_onboard::kFnvOffset;\n";
  for (const auto& [array, length] : arrays_)
    s += "  hash = thetad_onboard::fnv1a(" + name + "<T>::" + array + ", " + std::to_string(length) + ", hash);\n";
  s += "  return hash;\n}\n";
  s += "template <class T>\nbool data_intact() {\n"
       "  return data_checksum<T>() == (sizeof(T) == sizeof(double) ? kChecksumDouble : kChecksumFloat);\n}\n";
  return s;
}

}  // namespace thetad
