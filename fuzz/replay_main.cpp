// Replays fuzz inputs through one target's LLVMFuzzerTestOneInput without libFuzzer, so that
// ctest (label fuzz-replay) runs the seed corpus and the past findings with any compiler.
//
//   fuzz_replay_<target> DIR_OR_FILE...
//
// Every regular file of each directory (in name order) is one input. A missing directory
// counts as empty (a target may have no findings yet), but at least one input must run.
// A file whose name starts with "loaded-" must load, one that starts with "refused-" must be
// refused with sylva::Error; any other file may do either. A crash, or an exception other
// than sylva::Error, ends the program as it would end the fuzzer.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> inputsOf(const fs::path& arg) {
  std::vector<fs::path> files;
  if (fs::is_regular_file(arg)) {
    files.push_back(arg);
  } else if (fs::is_directory(arg)) {
    for (const fs::directory_entry& e : fs::directory_iterator(arg))
      if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
  }
  return files;
}

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

int main(int argc, char** argv) {
  int inputs = 0, refused = 0, wrong = 0;
  for (int a = 1; a < argc; ++a) {
    for (const fs::path& file : inputsOf(argv[a])) {
      std::ifstream in(file, std::ios::binary);
      if (!in) {
        std::cerr << "cannot open " << file.string() << "\n";
        return 1;
      }
      const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      std::cerr << file.string() << ": ";  // named before it runs, in case it crashes
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      ++inputs;
      const bool was_refused = sylva_fuzz::last_outcome == sylva_fuzz::Outcome::kRefused;
      refused += was_refused;
      std::cerr << (was_refused ? "refused" : "loaded") << "\n";
      const std::string name = file.filename().string();
      if ((startsWith(name, "loaded-") && was_refused) || (startsWith(name, "refused-") && !was_refused)) {
        std::cerr << "  expected it to be " << (was_refused ? "loaded" : "refused") << ", but it was "
                  << (was_refused ? "refused" : "loaded") << "\n";
        ++wrong;
      }
    }
  }
  std::cout << inputs << " inputs replayed: " << inputs - refused << " loaded, " << refused
            << " refused with sylva::Error, " << wrong << " against the expectation of their name\n";
  return inputs == 0 || wrong > 0 ? 1 : 0;
}
