#pragma once
// Shared by the fuzz targets (fuzz/<target>.cpp) and the replay driver (fuzz/replay_main.cpp).
//
// Every loader reads files, so a target writes its input to files in a scratch folder of its
// own process and hands the loader their paths. An input that stands for several files holds
// them one after the other, separated by '@' (kSeparator), which none of the formats uses.
//
// The contract under test: any input either loads or is refused with sylva::Error. `run`
// catches sylva::Error only; any other exception escapes the target, and libFuzzer (or the
// replay driver) aborts on it. `require` turns a broken invariant of loaded data into an abort.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <unistd.h>

#include <sylva/core/error.hpp>

namespace sylva_fuzz {

inline constexpr char kSeparator = '@';

/// How the last input ended; the replay driver checks it against a file name's prefix.
enum class Outcome { kLoaded, kRefused };
inline Outcome last_outcome = Outcome::kLoaded;

/// Runs one input: a sylva::Error is an accepted refusal, anything else escapes.
template <typename Body>
int run(Body&& body) {
  try {
    body();
    last_outcome = Outcome::kLoaded;
  } catch (const sylva::Error&) {
    last_outcome = Outcome::kRefused;
  }
  return 0;
}

/// An invariant of data a loader accepted; a violation is a finding.
inline void require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz target: invariant violated: %s\n", what);
  std::abort();
}

/// This process's scratch folder, under /dev/shm when it is writable (no disk I/O), else under
/// the system's temporary folder ($TMPDIR); created on first use and reused, removed at exit.
class Scratch {
 public:
  explicit Scratch(const std::string& target) {
    const std::filesystem::path base =
        ::access("/dev/shm", W_OK) == 0 ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
    path_ = base / ("sylva_fuzz_" + target + "_" + std::to_string(static_cast<long>(::getpid())));
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
    std::filesystem::create_directories(path_, ec);
    require(std::filesystem::is_directory(path_), "cannot create the scratch folder");
  }
  ~Scratch() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;

  const std::filesystem::path& path() const { return path_; }

  /// Writes `bytes` to `file` in the folder, replacing it; returns its path.
  std::string write(const std::string& file, std::string_view bytes) const {
    const std::filesystem::path p = path_ / file;
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    require(static_cast<bool>(out), "cannot write a scratch file");
    return p.string();
  }

  /// Removes `file` from the folder (the loader then meets a missing file).
  void remove(const std::string& file) const {
    std::error_code ignored;
    std::filesystem::remove(path_ / file, ignored);
  }

 private:
  std::filesystem::path path_;
};

/// The parts of `bytes` between separators; at most `max_parts` (later ones are dropped).
inline std::vector<std::string_view> split(std::string_view bytes, std::size_t max_parts) {
  std::vector<std::string_view> parts;
  while (parts.size() < max_parts) {
    const std::size_t stop = bytes.find(kSeparator);
    parts.push_back(bytes.substr(0, stop));
    if (stop == std::string_view::npos) break;
    bytes.remove_prefix(stop + 1);
  }
  return parts;
}

/// Writes parts[i] to files[i]; removes the files that have no part.
inline void writeFiles(const Scratch& dir, const std::vector<std::string>& files,
                       const std::vector<std::string_view>& parts) {
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (i < parts.size())
      dir.write(files[i], parts[i]);
    else
      dir.remove(files[i]);
  }
}

inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace sylva_fuzz
