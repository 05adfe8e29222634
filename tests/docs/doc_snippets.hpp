#pragma once
// Keeps the code in docs/ and README.md honest: a test marks a region of its own source with
// "// [<name> begin]" and "// [<name> end]", and checks that the page quotes the region
// verbatim (minus the indentation the region shares).

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace sylva_docs {

/// Lines of `path` strictly between the marker lines of region `name`, with their common
/// indentation removed if `dedent`.
inline std::string markedRegion(const std::string& path,
                                const std::string& name,
                                bool dedent = true) {
  const std::string begin = "[" + name + " begin]";
  const std::string end = "[" + name + " end]";
  std::ifstream in(path);
  std::vector<std::string> lines;
  bool inside = false;
  for (std::string line; std::getline(in, line);) {
    if (inside && line.find(end) != std::string::npos) break;
    if (inside) lines.push_back(line);
    if (line.find(begin) != std::string::npos) inside = true;
  }
  std::size_t indent = dedent ? std::string::npos : 0;
  if (dedent) {
    for (const std::string& line : lines)
      if (line.find_first_not_of(' ') != std::string::npos)
        indent = std::min(indent, line.find_first_not_of(' '));
  }
  std::string text;
  for (const std::string& line : lines)
    text += (line.size() > indent ? line.substr(indent) : std::string()) + "\n";
  return text;
}

/// The whole text of a file ("" if it cannot be read).
inline std::string fileText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

/// The repository root, from the path of this header (tests/docs/doc_snippets.hpp).
inline std::string repositoryRoot() {
  const std::string file = __FILE__;
  return file.substr(0, file.find_last_of('/')) + "/../..";
}

}  // namespace sylva_docs
