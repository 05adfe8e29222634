#pragma once
// Test helpers: whether `f()` throws sylva::Error with exactly `code`, and the message it throws.
#include <string>

#include <sylva/core/error.hpp>

namespace sylva_test {

template <typename F>
bool throwsCode(F&& f, sylva::ErrorCode code) {
  try {
    f();
  } catch (const sylva::Error& e) {
    return e.code() == code;
  }
  return false;
}

/// The message of the sylva::Error that `f()` throws with `code`; "wrong code" when it throws
/// another code, "" when it throws nothing.
template <typename F>
std::string errorMessage(F&& f, sylva::ErrorCode code) {
  try {
    f();
  } catch (const sylva::Error& e) {
    return e.code() == code ? std::string(e.what()) : std::string("wrong code");
  }
  return "";
}

}  // namespace sylva_test
