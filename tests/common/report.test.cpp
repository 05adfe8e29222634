// The examples' text report (examples/common/report.hpp): one result object printed as JSON or
// as indented text, tables for arrays of objects, list items where a table is too wide.
#include "sylva_catch.hpp"

#include <sstream>
#include <string>

#include "common/report.hpp"

namespace unity_common_report {

using nlohmann::json;

std::string text(const json& result) {
  std::ostringstream os;
  sylva_examples::printReport(os, "title", result);
  return os.str();
}

TEST_CASE("report: plain values first, then objects, numbers to 5 significant digits",
          "[examples][report]") {
  const json result = {{"zeta", {{"b", 2}, {"a", 1.0 / 3.0}}},
                       {"alpha", 12345678},
                       {"beta", 0.000123456789},
                       {"flag", true},
                       {"missing", nullptr},
                       {"name", "forest 1"},
                       {"empty", json::array()}};
  CHECK(text(result) ==
        "title\n"
        "  name: forest 1\n"
        "  alpha: 12345678\n"
        "  beta: 0.00012346\n"
        "  empty: (none)\n"
        "  flag: yes\n"
        "  missing: -\n"
        "  zeta:\n"
        "    a: 0.33333\n"
        "    b: 2\n");
}

TEST_CASE("report: an array of objects is a table, the naming columns first",
          "[examples][report]") {
  const json rows =
      json::array({{{"value", 1.5}, {"name", "a"}, {"inner", {{"x", 1}}}},
                   {{"value", 10}, {"name", "bb"}, {"inner", {{"x", 22}}}, {"extra", "e"}}});
  CHECK(text({{"rows", rows}}) ==
        "title\n"
        "  rows:\n"
        "    name  inner.x  value  extra\n"
        "       a        1    1.5      -\n"
        "      bb       22     10      e\n");
}

TEST_CASE("report: a table wider than the page becomes a list of items", "[examples][report]") {
  json row = {{"seed", 7}};
  for (int k = 0; k < 12; ++k) row["a_rather_long_member_name_" + std::to_string(k)] = k;
  const std::string out = text({{"runs", json::array({row, row})}});
  CHECK(out.find("    - seed: 7\n      a_rather_long_member_name_0: 0\n") != std::string::npos);
  CHECK(out.find("a_rather_long_member_name_0  ") == std::string::npos);  // no header row
}

TEST_CASE("report: arrays of values wrap, strings with spaces are quoted", "[examples][report]") {
  json numbers = json::array();
  for (int k = 0; k < 60; ++k) numbers.push_back(k);
  const std::string out = text({{"n", numbers}, {"words", {"one", "two words"}}});
  CHECK(out.find("  words: one \"two words\"\n") != std::string::npos);
  std::istringstream lines(out);
  int count = 0;
  for (std::string line; std::getline(lines, line);) {
    CHECK(line.size() <= 100);
    ++count;
  }
  CHECK(count == 4);  // the title, n on two lines, words
}

TEST_CASE("report: --json prints the object itself", "[examples][report]") {
  const json result = {{"b", 1.25}, {"a", {1, 2}}};
  std::ostringstream as_json, as_text;
  sylva_examples::writeResult(as_json, true, "title", result);
  sylva_examples::writeResult(as_text, false, "title", result);
  CHECK(json::parse(as_json.str()) == result);
  CHECK(as_text.str() == "title\n  a: 1 2\n  b: 1.25\n");
}

}  // namespace unity_common_report
