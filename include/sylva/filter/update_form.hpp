#pragma once
/// @file
/// Covariance update forms, chosen at compile time (`BasicEkf<UpdateForm, Robot, ...>`).
///
/// - `SymmetricUpdate` (default): P -= W W^T with W = P H^T L^-T, L the Cholesky factor of
///   the innovation covariance S. It is the textbook P - P H^T S^-1 H P written so that the
///   subtracted term is symmetric positive semi-definite by construction; only the lower
///   triangle of P is touched (the filter keeps the lower triangle authoritative).
/// - `JosephUpdate`: P = (I - K H) P (I - K H)^T + K R K^T, which stays symmetric positive
///   semi-definite even for a sub-optimal gain. It works on the full matrix and costs about
///   three passes over P instead of half of one; see docs/benchmarks.md.

namespace sylva {

struct SymmetricUpdate {
  static constexpr const char* kName = "SymmetricUpdate";
};

struct JosephUpdate {
  static constexpr const char* kName = "JosephUpdate";
};

}  // namespace sylva
