#pragma once
// Test helper: a fresh folder under the system's temporary directory for the files a test case
// writes (loader tests write their own small inputs), removed again at the end of the case.
// Its name carries the process id: ctest runs test cases as parallel processes, and two
// cases must never share (and delete) each other's folder.
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace sylva_test {

struct TempFolder {
  std::filesystem::path path;

  explicit TempFolder(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("sylva_test_" + name + "_" + std::to_string(static_cast<long>(::getpid())))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  /// Writes `text` byte for byte to `file` in the folder; returns the file's path.
  std::string write(const std::string& file, const std::string& text) const {
    std::ofstream(path / file, std::ios::binary) << text;
    return (path / file).string();
  }
};

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace sylva_test
