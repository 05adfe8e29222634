// Fuzz target: sylva::datasets::readNumericTable, with a format taken from the input.
//
// Input: three header bytes, then the file.
//   byte 0  bits 0-4: the delimiters, each bit one of " \t,;|" (none: the caller's mistake,
//           kInvalidArgument); bit 5: allow_non_finite; bit 6: ignored, so that the letters
//           '@'-'_' and '`'-DEL cover every set ('C' is " \t", 'D' is ",", 'E' is " ,");
//           bit 7: the callback also reads field 1 as a whole number that must not decrease
//   byte 1  the comment character
//   byte 2  min_fields = 1 + bits 0-2, max_fields = min_fields + bits 3-5
//           ('0' is 1 to 7 fields, 'A' exactly 2, 'H' 1 to 2)

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include <sylva/datasets/numeric_table.hpp>

#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva_fuzz;
  static const Scratch dir("numeric_table");
  if (size < 3) return 0;
  const std::uint8_t flags = data[0];
  sylva::datasets::NumericTableFormat format;
  format.delimiters.clear();
  for (int bit = 0; bit < 5; ++bit)
    if (flags & (1u << bit)) format.delimiters += " \t,;|"[bit];
  format.allow_non_finite = (flags & 0x20) != 0;
  const bool whole_numbers = (flags & 0x80) != 0;
  format.comment = static_cast<char>(data[1]);
  format.min_fields = 1 + (data[2] & 7);
  format.max_fields = format.min_fields + ((data[2] >> 3) & 7);
  const std::string path = dir.write("table.txt", asText(data + 3, size - 3));

  return run([&] {
    long last_line = 0;
    double previous = -HUGE_VAL;
    sylva::datasets::readNumericTable(path, format, [&](const sylva::datasets::NumericRow& row) {
      require(row.file() == path, "the row names another file");
      require(row.line() > last_line, "line numbers do not increase");
      last_line = row.line();
      require(row.size() >= format.min_fields && row.size() <= format.max_fields, "a row has a field count outside the format");
      for (int i = 0; i < row.size(); ++i) {
        require(format.allow_non_finite || std::isfinite(row[i]), "a non-finite value was accepted");
        const std::string& text = row.text(i);
        require(!text.empty(), "an empty field was accepted");
        require(text.find_first_of(format.delimiters) == std::string::npos, "a field holds a delimiter");
        require(text.find_first_of("\r\n") == std::string::npos, "a field holds a line break");
      }
      if (whole_numbers) {
        const long v = row.integer(0, "field 1");
        require(static_cast<double>(v) == row[0], "integer() changed the value");
        sylva::datasets::requireNonDecreasing(row, previous, row[0], "field 1");
        previous = row[0];
      }
    });
  });
}
