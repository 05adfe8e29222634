#pragma once
/// @file
/// sylva's single error mechanism: every public operation that receives bad input throws
/// `sylva::Error` with an `ErrorCode` and a sentence naming the problem. A throwing filter
/// operation leaves the filter's mean and covariance bit-identical to before (strong
/// exception guarantee): all checks and all arithmetic that can fail happen before any
/// member is written.

#include <stdexcept>
#include <string>

namespace sylva {

enum class ErrorCode {
  kNonFinite,            ///< NaN or Inf in an input, a prediction or a Jacobian
  kUnknownId,            ///< no landmark with this id
  kDuplicateId,          ///< a landmark with this id already exists
  kWrongLandmarkType,    ///< model's landmark type does not match the slot's
  kNotPositiveDefinite,  ///< a covariance (noise or innovation) is not positive definite
  kNegativeTimeStep,     ///< dt < 0 (or not finite)
  kDegenerateGeometry,   ///< the model is undefined here (e.g. landmark at the sensor)
  kInvalidArgument,      ///< any other malformed argument (sizes, ranges)
  kMalformedData,        ///< a data file or stream could not be parsed
  kOutOfDomain,          ///< an update would move a landmark out of its domain (radius <= 0)
};

inline const char* toString(ErrorCode code) {
  switch (code) {
    case ErrorCode::kNonFinite: return "non-finite value";
    case ErrorCode::kUnknownId: return "unknown id";
    case ErrorCode::kDuplicateId: return "duplicate id";
    case ErrorCode::kWrongLandmarkType: return "wrong landmark type";
    case ErrorCode::kNotPositiveDefinite: return "not positive definite";
    case ErrorCode::kNegativeTimeStep: return "negative time step";
    case ErrorCode::kDegenerateGeometry: return "degenerate geometry";
    case ErrorCode::kInvalidArgument: return "invalid argument";
    case ErrorCode::kMalformedData: return "malformed data";
    case ErrorCode::kOutOfDomain: return "out of domain";
  }
  return "unknown error";
}

/// The exception every sylva operation throws on bad input.
class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const std::string& what)
      : std::runtime_error(std::string("sylva: ") + toString(code) + ": " + what), code_(code) {}
  ErrorCode code() const noexcept { return code_; }

 private:
  ErrorCode code_;
};

/// Throws `Error(code, what)`. Kept out of line of the hot path by [[noreturn]].
[[noreturn]] inline void fail(ErrorCode code, const std::string& what) { throw Error(code, what); }

}  // namespace sylva
