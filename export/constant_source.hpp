#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace thetad {

// `value` as a C++ literal that reads back as the same double: hexadecimal floating (%a), or
// std::numeric_limits' infinity/quiet_NaN for the non-finite.
std::string exact_literal(double value);

// The constant data of an exported controller as members of a class template over the scalar type
// (`template <class T> struct Design`): arrays written exactly in double and converted by the
// compiler, scalars likewise, and the FNV-1a checksum of the arrays in double and in float, which
// a data_intact<T>() in the header recomputes at run time.
class DesignSource {
 public:
  // A `static constexpr T NAME[N]` member (N ≥ 1: an empty array gets one unused zero).
  void add_array(const std::string& name, const std::vector<double>& values);
  // The same for integer data (indices): `static constexpr int NAME[N]`; not in the checksum.
  void add_indices(const std::string& name, const std::vector<int>& values);
  // `static constexpr T NAME`.
  void add_scalar(const std::string& name, double value);
  // `static constexpr int NAME` (also bools: 0 or 1).
  void add_integer(const std::string& name, long long value);

  // `template <class T> struct NAME { ... };` then the checksum function
  // `template <class T> std::uint64_t CHECKSUM_FUNCTION()` and the two expected values
  // kChecksumDouble, kChecksumFloat.
  std::string source(const std::string& name) const;
  std::uint64_t checksum_double() const { return checksum_double_; }
  std::uint64_t checksum_float() const { return checksum_float_; }

 private:
  std::string members_;
  std::vector<std::pair<std::string, std::size_t>> arrays_;  // name, length, in order
  std::uint64_t checksum_double_ = 0xcbf29ce484222325ull;     // FNV-1a offset basis
  std::uint64_t checksum_float_ = 0xcbf29ce484222325ull;
};

// A matrix's entries row by row, a vector's in order: the layout of the exported arrays.
std::vector<double> row_major(const Eigen::MatrixXd& matrix);
std::vector<double> entries(const Eigen::VectorXd& vector);

// A vector's elements in C++ source, `per_line` to a line, for an initializer list.
std::string literal_list(const std::vector<double>& values, const char* wrap_open, const char* wrap_close,
                         int per_line = 4);

}  // namespace thetad
