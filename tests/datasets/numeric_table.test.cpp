// readNumericTable: the reader under the dataset loaders. Blank-separated and CSV rows,
// comments, CRLF, and a clear error naming file and line for every kind of malformed row.

#include <clocale>
#include <cstdlib>
#include <string>
#include <vector>

#include <sylva/datasets/numeric_table.hpp>

#include "sylva_catch.hpp"
#include "temp_folder.hpp"

namespace unity_datasets_numeric_table {

using sylva::datasets::NumericRow;
using sylva::datasets::NumericTableFormat;
using sylva_test::contains;
using sylva_test::TempFolder;

/// Reads `text` with `format`; returns the rows, or the kMalformedData message in `error`.
std::vector<std::vector<double>> readText(const std::string& text, const NumericTableFormat& format, std::string& error) {
  const TempFolder dir("numeric_table");
  const std::string path = dir.write("table.dat", text);
  std::vector<std::vector<double>> rows;
  error.clear();
  try {
    sylva::datasets::readNumericTable(path, format, [&](const NumericRow& row) {
      rows.emplace_back();
      for (int i = 0; i < row.size(); ++i) rows.back().push_back(row[i]);
    });
  } catch (const sylva::Error& e) {
    error = e.code() == sylva::ErrorCode::kMalformedData ? e.what() : "wrong code";
  }
  return rows;
}

NumericTableFormat fields(int lo, int hi) {
  NumericTableFormat f;
  f.min_fields = lo;
  f.max_fields = hi;
  return f;
}

}  // namespace unity_datasets_numeric_table

using namespace unity_datasets_numeric_table;

TEST_CASE("readNumericTable reads blank-separated rows with comments, CRLF and trailing blanks", "[datasets]") {
  std::string error;
  const auto rows = readText(
      "# header line\r\n"
      "#  another\r\n"
      "1248446188.323 \t63\t1.5 -0.25 \r\n"
      "\r\n"
      "   # indented comment\n"
      "2\t7 1e-3 .5\n",
      fields(4, 4), error);
  REQUIRE(error.empty());
  REQUIRE(rows.size() == 2);
  CHECK(rows[0][0] == 1248446188.323);
  CHECK(rows[0][1] == 63.0);
  CHECK(rows[0][3] == -0.25);
  CHECK(rows[1][2] == 1e-3);
  CHECK(rows[1][3] == 0.5);
}

TEST_CASE("readNumericTable names the file, the line and the problem of a malformed row", "[datasets]") {
  std::string error;
  readText("1 2 3\n4 5 x6\n", fields(3, 3), error);
  CHECK(contains(error, "table.dat:2: field 3 is not a finite number: 'x6'"));
  readText("1 2 3\n\n# c\n4 5\n", fields(3, 3), error);
  CHECK(contains(error, "table.dat:4: expected 3 fields, got 2"));
  readText("1 2 3 4 5\n", fields(2, 4), error);
  CHECK(contains(error, "table.dat:1: expected 2 to 4 fields, got 5"));
  readText("1 nan 3\n", fields(3, 3), error);
  CHECK(contains(error, ":1: field 2 is not a finite number: 'nan'"));
  readText("1 inf 3\n", fields(3, 3), error);
  CHECK(contains(error, "field 2 is not a finite number"));
  readText("1 1e999 3\n", fields(3, 3), error);
  CHECK(contains(error, "field 2 is not a finite number: '1e999'"));
  readText("1 2,5 3\n", fields(3, 3), error);
  CHECK(contains(error, "field 2 is not a finite number: '2,5'"));
  readText("1 2 3\n", fields(3, 3), error);
  CHECK(error.empty());
}

TEST_CASE("readNumericTable reads CSV and refuses empty fields", "[datasets]") {
  NumericTableFormat csv = fields(3, 3);
  csv.delimiters = ",";
  csv.allow_non_finite = true;
  std::string error;
  const auto rows = readText("1, 2 ,inf\r\n4,nan,6\n", csv, error);
  REQUIRE(error.empty());
  REQUIRE(rows.size() == 2);
  CHECK(rows[0][1] == 2.0);
  CHECK(std::isinf(rows[0][2]));
  CHECK(std::isnan(rows[1][1]));
  readText("1,,3\n", csv, error);
  CHECK(contains(error, ":1: field 2 is not a number: ''"));
  readText("1,2,\n", csv, error);
  CHECK(contains(error, ":1: the line ends with an empty field"));
}

TEST_CASE("readNumericTable: a delimiter set that mixes a blank with another character, at the end of a line",
          "[datasets]") {
  // Such a set is read like blanks: a run of delimiters separates two fields, and a run at the
  // end of a line ends it (it once threw std::out_of_range there).
  for (const char* delimiters : {" ,", " ;", "\t|"}) {
    NumericTableFormat f = fields(2, 2);
    f.delimiters = delimiters;
    const std::string b(1, delimiters[0]);  // the set's blank
    const std::string d(1, delimiters[1]);  // and its other character
    std::string error;
    const auto rows = readText("1" + d + "2" + d + "\n3" + b + d + b + "4" + d + d + "\n", f, error);
    INFO("delimiters '" << delimiters << "': " << error);
    REQUIRE(error.empty());
    REQUIRE(rows.size() == 2);
    CHECK(rows[0] == std::vector<double>{1.0, 2.0});
    CHECK(rows[1] == std::vector<double>{3.0, 4.0});
    readText("1" + d + "2" + d + "x" + d + "\n", f, error);
    CHECK(contains(error, ":1: field 3 is not a finite number: 'x'"));
  }
}

TEST_CASE("readNumericTable: a missing file, whole numbers and the callback's own checks", "[datasets]") {
  std::string error;
  try {
    sylva::datasets::readNumericTable("/nonexistent/sylva/table.dat", fields(1, 1), [](const NumericRow&) {});
  } catch (const sylva::Error& e) {
    error = e.what();
  }
  CHECK(contains(error, "/nonexistent/sylva/table.dat: cannot open the file"));

  const TempFolder dir("numeric_table_rules");
  const std::string path = dir.write("ids.dat", "7 1.0\n8.5 2.0\n");
  std::vector<long> ids;
  try {
    sylva::datasets::readNumericTable(path, fields(2, 2), [&](const NumericRow& row) {
      ids.push_back(row.integer(0, "the id"));
    });
  } catch (const sylva::Error& e) {
    error = e.what();
  }
  CHECK(ids == std::vector<long>{7});
  CHECK(contains(error, "ids.dat:2: the id must be a whole number, got 8.5"));

  const std::string times = dir.write("times.dat", "1.0\n2.0\n1.5\n");
  double previous = -1e300;
  try {
    sylva::datasets::readNumericTable(times, fields(1, 1), [&](const NumericRow& row) {
      sylva::datasets::requireNonDecreasing(row, previous, row[0], "the time");
      previous = row[0];
    });
  } catch (const sylva::Error& e) {
    error = e.what();
  }
  CHECK(contains(error, "times.dat:3: the time goes back in time: 1.5 after 2"));
}

TEST_CASE("readNumericTable: decimal notation only, a leading plus, and values beyond double", "[datasets]") {
  std::string error;
  auto rows = readText("+1.5 -2e-3\n+.5 1E2\n", fields(2, 2), error);
  REQUIRE(error.empty());
  REQUIRE(rows.size() == 2);
  CHECK(rows[0] == std::vector<double>{1.5, -2e-3});
  CHECK(rows[1] == std::vector<double>{0.5, 100.0});
  for (const char* bad : {"0x1p3", "+-1", "++1", "+", "1,5", "1e400", "-1e400", "1.5.2"}) {
    INFO(bad);
    readText(std::string("1 ") + bad + "\n", fields(2, 2), error);
    CHECK(contains(error, std::string(":1: field 2 is not a finite number: '") + bad + "'"));
  }
}

namespace unity_datasets_numeric_table {

/// Compiles a comma-decimal locale (de_DE.UTF-8) into `dir` with glibc's localedef and makes
/// the C library use it for numbers; false when this machine cannot (no localedef, or no
/// locale sources: Debian's `locales` package).
bool useCommaDecimalLocale(const TempFolder& dir) {
  if (std::setlocale(LC_NUMERIC, "de_DE.UTF-8") == nullptr) {
    const std::string command =
        "localedef -i de_DE -f UTF-8 '" + (dir.path / "de_DE.UTF-8").string() + "' > /dev/null 2>&1";
    if (std::system(command.c_str()) != 0) return false;
    ::setenv("LOCPATH", dir.path.c_str(), 1);  // glibc reads it at every setlocale
    if (std::setlocale(LC_NUMERIC, "de_DE.UTF-8") == nullptr) return false;
  }
  return std::strtod("1.5", nullptr) == 1.0;  // the C library now stops at the '.'
}

}  // namespace unity_datasets_numeric_table

TEST_CASE("readNumericTable reads '.' as the decimal point whatever the process locale", "[datasets]") {
  const TempFolder dir("numeric_table_locale");
  const std::string path = dir.write("table.dat", "1.5 -2.25e1\n");
  const bool comma_locale = useCommaDecimalLocale(dir);
  std::vector<double> values;
  std::string error;
  try {
    sylva::datasets::readNumericTable(path, fields(2, 2), [&](const NumericRow& row) {
      values = {row[0], row[1]};
    });
  } catch (const sylva::Error& e) {
    error = e.what();
  }
  std::setlocale(LC_NUMERIC, "C");
  ::unsetenv("LOCPATH");
  if (!comma_locale) {
    WARN("skipped: no comma-decimal locale (de_DE.UTF-8) could be made here (Debian: apt-get install locales)");
    SUCCEED("skipped");
    return;
  }
  INFO(error);
  CHECK(values == std::vector<double>{1.5, -22.5});
}
