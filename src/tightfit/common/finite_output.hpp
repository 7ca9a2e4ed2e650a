#pragma once
/// No output file ever holds a NaN or an infinity. Every writer checks the numbers it
/// is about to write with the functions below, inside the write function it hands to
/// write_file_atomically (atomic_file.hpp): a non-finite number throws
/// NonFiniteOutput saying where it is (a JSON pointer, or an array, row and column),
/// write_file_atomically removes the unfinished temporary file and throws SolverError
/// "FILE: not written: non-finite number (nan) at /history/3/value", so the target
/// file is left as it was (or absent) and the CLI ends with exit code 3.
///
/// JSON is the one format that would otherwise hide such a number: nlohmann::json
/// writes NaN and ±inf as `null`. write_json_atomically checks the whole document.
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "tightfit/common/error.hpp"

namespace tightfit {

/// A non-finite number found in data about to be written; what() says where.
class NonFiniteOutput : public SolverError {
 public:
  using SolverError::SolverError;
};

/// "nan", "inf" or "-inf".
std::string non_finite_name(double value);

/// Throws NonFiniteOutput "non-finite number (nan) at /a/0/b" for the first NaN or
/// infinity in `json` (depth first, in document order); `json` holds numbers as
/// nlohmann stores them (integers are always finite).
void require_finite_json(const nlohmann::json& json);

/// Throws NonFiniteOutput "non-finite number (inf) in WHAT, element i" for the first
/// non-finite value of `values[0..count)`.
void require_finite_values(const double* values, std::size_t count, std::string_view what);
void require_finite_values(const float* values, std::size_t count, std::string_view what);

/// Throws NonFiniteOutput "non-finite number (nan) in WHAT, row r, column c" for the
/// first non-finite entry of a dense matrix (e.g. Points3 positions, a field's values).
template <class Derived>
void require_finite_matrix(const Eigen::DenseBase<Derived>& m, std::string_view what) {
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      if (!std::isfinite(static_cast<double>(m(r, c))))
        throw NonFiniteOutput(
            "non-finite number (" + non_finite_name(static_cast<double>(m(r, c))) + ") in " +
            std::string(what) + ", row " + std::to_string(r) + ", column " + std::to_string(c));
}

/// Writes `json.dump(indent)` and a newline to `path` atomically after
/// require_finite_json (SolverError naming the file and the JSON path otherwise; no
/// file is written).
void write_json_atomically(const std::filesystem::path& path, const nlohmann::json& json,
                           int indent = -1);

}  // namespace tightfit
