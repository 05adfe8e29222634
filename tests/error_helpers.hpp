#pragma once
// Test helper: true when `f()` throws sylva::Error with exactly `code`.
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

}  // namespace sylva_test
