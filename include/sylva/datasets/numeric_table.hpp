#pragma once
/// @file
/// `readNumericTable`: the reader under every dataset loader. It reads a plain-text table of
/// numbers one row at a time and makes sure that a malformed file is never skipped silently.
///
/// The format covers the public datasets' text files:
/// - fields are separated by any run of the delimiter characters (default: space and TAB;
///   pass "," for CSV, where an empty field is an error);
/// - a line whose first non-blank character is the comment character (default '#') and an
///   empty line are skipped;
/// - CRLF and LF line endings are both accepted, and so is trailing whitespace;
/// - every field must be a whole number in decimal notation ("12", "-0.5", "+3e-2"), read by
///   `std::from_chars`, so the process locale (a comma as decimal separator, say) does not
///   change what a file means. Hexadecimal floats are refused. "nan" and "inf" are refused
///   unless `allow_non_finite` is set; so is a value outside the range of double.
///
/// Errors: a file that cannot be opened, a field that is not a number, or a row with too few
/// or too many fields throw `sylva::Error(kMalformedData)`. The message names the file, the
/// line number and what is wrong. The callback checks its own rules with `row.fail(...)`,
/// which gives the same message form.

#include <charconv>
#include <cmath>
#include <system_error>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sylva/core/error.hpp"

namespace sylva::datasets {

/// Throws kMalformedData as "file:line: what" ("file: what" when line <= 0).
[[noreturn]] inline void failMalformed(const std::string& file, long line, const std::string& what) {
  std::ostringstream os;
  os << file;
  if (line > 0) os << ":" << line;
  os << ": " << what;
  fail(ErrorCode::kMalformedData, os.str());
}

struct NumericTableFormat {
  int min_fields = 1;               ///< fewer fields on a row is an error
  int max_fields = 1;               ///< more fields on a row is an error
  std::string delimiters = " \t";   ///< characters that separate fields
  char comment = '#';               ///< a line starting with it (after blanks) is skipped
  bool allow_non_finite = false;    ///< accept "nan" / "inf" fields
};

/// One row of a table, handed to the callback of `readNumericTable`.
class NumericRow {
 public:
  NumericRow(const std::string& file, long line) : file_(file), line_(line) {}

  int size() const { return static_cast<int>(values_.size()); }
  double operator[](int i) const { return values_[static_cast<std::size_t>(i)]; }
  long line() const { return line_; }
  const std::string& file() const { return file_; }

  /// Field `i` as an integer; a field with a fractional part is an error.
  long integer(int i, const char* name) const {
    const double v = (*this)[i];
    if (!(std::abs(v) < 9.0e15) || v != std::floor(v))
      fail(std::string(name) + " must be a whole number, got " + text(i));
    return static_cast<long>(v);
  }

  /// The field as it was written, for messages.
  const std::string& text(int i) const { return texts_[static_cast<std::size_t>(i)]; }

  /// Throws kMalformedData naming this row's file and line.
  [[noreturn]] void fail(const std::string& what) const { failMalformed(file_, line_, what); }

 private:
  template <typename Callback>
  friend void readNumericTable(const std::string&, const NumericTableFormat&, Callback&&);

  const std::string& file_;
  long line_;
  std::vector<double> values_;
  std::vector<std::string> texts_;
};

namespace detail {

/// Parses a whole field; false if any character is left over or the value is out of the range
/// of double. Locale-independent: std::from_chars always reads '.' as the decimal point.
inline bool parseField(const std::string& field, bool allow_non_finite, double& value) {
  const char* first = field.data();
  const char* const last = field.data() + field.size();
  // from_chars refuses a leading '+', which strtod (and so the files' writers) accept.
  if (first != last && *first == '+' && last - first > 1 && first[1] != '-' && first[1] != '+') ++first;
  if (first == last) return false;
  const auto [end, error] = std::from_chars(first, last, value, std::chars_format::general);
  if (error != std::errc() || end != last) return false;
  return allow_non_finite || std::isfinite(value);
}

}  // namespace detail

/// Calls `on_row(const NumericRow&)` for every data row of `path`, in file order.
template <typename Callback>
void readNumericTable(const std::string& path, const NumericTableFormat& format, Callback&& on_row) {
  if (format.min_fields < 1 || format.max_fields < format.min_fields || format.delimiters.empty())
    fail(ErrorCode::kInvalidArgument, "readNumericTable: need 1 <= min_fields <= max_fields and a delimiter");
  std::ifstream in(path);
  if (!in) failMalformed(path, 0, "cannot open the file");
  const bool csv = format.delimiters.find_first_of(" \t") == std::string::npos;
  NumericRow row(path, 0);
  std::string line;
  while (std::getline(in, line)) {
    ++row.line_;
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t'))
      line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == format.comment) continue;
    row.values_.clear();
    row.texts_.clear();
    std::size_t pos = first;
    while (true) {
      std::size_t stop = line.find_first_of(format.delimiters, pos);
      if (stop == std::string::npos) stop = line.size();
      std::string field = line.substr(pos, stop - pos);
      if (csv) {  // blanks around a CSV field are allowed, an empty field is not
        const std::size_t b = field.find_first_not_of(" \t");
        const std::size_t e = field.find_last_not_of(" \t");
        field = b == std::string::npos ? std::string() : field.substr(b, e - b + 1);
      }
      double value = 0.0;
      if (csv && field.empty() && stop == line.size() && !row.values_.empty())
        row.fail("the line ends with an empty field");
      if (!detail::parseField(field, format.allow_non_finite, value)) {
        std::ostringstream os;
        os << "field " << row.values_.size() + 1 << " is not a "
           << (format.allow_non_finite ? "number" : "finite number") << ": '" << field << "'";
        row.fail(os.str());
      }
      row.values_.push_back(value);
      row.texts_.push_back(field);
      if (stop == line.size()) break;
      // After a CSV delimiter comes a field, possibly empty (then refused above). Between
      // blank-separated fields any run of blanks counts once, and the line has no trailing
      // blanks left, so another field follows.
      pos = csv ? stop + 1 : line.find_first_not_of(format.delimiters, stop);
      // A delimiter set that mixes a blank with another character (" ,") leaves that
      // character at the end of a line: a trailing run of delimiters ends it, as blanks do.
      if (pos == std::string::npos) break;
    }
    if (row.size() < format.min_fields || row.size() > format.max_fields) {
      std::ostringstream os;
      os << "expected ";
      if (format.min_fields == format.max_fields)
        os << format.min_fields;
      else
        os << format.min_fields << " to " << format.max_fields;
      os << " fields, got " << row.size();
      row.fail(os.str());
    }
    on_row(static_cast<const NumericRow&>(row));
  }
}

/// Reads a file that holds exactly one data row of `fields` comma-separated numbers (comments
/// aside) and hands it to `on_row`; throws kMalformedData naming the file (and the line) for a
/// second row, for none, or for a row of another length.
template <typename Callback>
void readSingleCsvRow(const std::string& path, int fields, const char* what, Callback&& on_row) {
  NumericTableFormat format;
  format.min_fields = fields;
  format.max_fields = fields;
  format.delimiters = ",";
  bool seen = false;
  readNumericTable(path, format, [&](const NumericRow& row) {
    if (seen) row.fail(std::string("a ") + what + " file holds one row");
    on_row(row);
    seen = true;
  });
  if (!seen) failMalformed(path, 0, std::string("no ") + what + " row in the file");
}

/// Checks that a row's time does not go back: throws naming the row otherwise.
inline void requireNonDecreasing(const NumericRow& row, double previous, double time, const char* what) {
  if (time < previous) {
    std::ostringstream os;
    os.precision(15);
    os << what << " goes back in time: " << time << " after " << previous;
    row.fail(os.str());
  }
}

/// The first and last time of one file of a recording.
struct FileTimeSpan {
  std::string file;
  double first = 0.0;
  double last = 0.0;
};

/// Throws kMalformedData for two files of one recording whose time spans disagree by more than
/// `gap` seconds, naming both files and their spans (a truncated copy shows up this way).
[[noreturn]] inline void failTimeSpanMismatch(const FileTimeSpan& a, const FileTimeSpan& b, double gap) {
  std::ostringstream os;
  os.precision(15);
  os << "the files cover different time spans: " << a.file << " [" << a.first << ", " << a.last << "] s, "
     << b.file << " [" << b.first << ", " << b.last << "] s (more than " << gap << " s apart; a truncated file?)";
  fail(ErrorCode::kMalformedData, os.str());
}

}  // namespace sylva::datasets
