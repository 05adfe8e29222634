#pragma once
/// @file
/// Covariance update forms, chosen at compile time (`BasicEkf<UpdateForm, Robot, ...>`).
///
/// - `SymmetricUpdate` (default): P -= W W^T with W = P H^T L^-T, L the Cholesky factor of
///   the innovation covariance S. It is the textbook P - P H^T S^-1 H P written so that the
///   subtracted term is symmetric positive semi-definite by construction; only the lower
///   triangle of P is touched (the filter keeps the lower triangle authoritative).
/// - `JosephUpdate`: P = (I - K H) P (I - K H)^T + K R K^T, which stays symmetric positive
///   semi-definite even for a sub-optimal gain. It is computed in product form on the full
///   matrix: mirror the lower triangle, A = (I - K H) P, then A - (A H^T) K^T + K R K^T, i.e.
///   several full passes over P instead of half of one (7-10x the symmetric form's time at
///   n = 100..2000 in docs/update-benchmarks.md).

namespace sylva {

struct SymmetricUpdate {
  static constexpr const char* kName = "SymmetricUpdate";
};

struct JosephUpdate {
  static constexpr const char* kName = "JosephUpdate";
};

}  // namespace sylva
