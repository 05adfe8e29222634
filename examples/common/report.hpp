#pragma once
// The examples' text report: one result object, printed either as JSON (--json) or as indented
// text by `printReport`. Each figure is computed once, for both outputs.
//
//   key: value               a number, string, boolean or null ("-")
//   key:                     an object: its members, indented
//   key: 1 2 3               an array of numbers or strings, wrapped at about 100 columns
//   key:                     an array of objects: a table, one row each, one column per member
//     a   b.c   d              (nested objects flattened as b.c; arrays inside a row joined
//     ...                      by spaces; the members that name a row, such as name or
//                              seed, first), or a list of items when that is too wide:
//   key:
//     - a: 1                   each object's members, the first after "- "
//       b: 2
//
// An object lists its plain values first, then its objects and tables, each group by name
// after the members that name a row (seed, name, robot, ...).
// Numbers print with 5 significant digits (integers in full); --json keeps every digit.

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace sylva_examples {

namespace report_detail {

inline std::string scalar(const nlohmann::json& v) {
  if (v.is_null()) return "-";
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
  if (v.is_number_float()) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.5g", v.get<double>());
    return buffer;
  }
  // An array inside a table cell: its scalars joined by spaces.
  std::string out;
  for (const nlohmann::json& e : v)
    out += (out.empty() ? "" : " ") + (e.is_primitive() ? scalar(e) : e.dump());
  return out;
}

// The members that name a row first, the others in their order (nlohmann::json keeps an
// object's members sorted by name).
inline void leadingFirst(std::vector<std::string>& names) {
  static const char* const leading[] = {
      "robot", "case", "scan", "step", "seed", "name", "variant", "pipeline"};
  const auto rank = [](const std::string& name) {
    return std::find(std::begin(leading), std::end(leading), name) - std::begin(leading);
  };
  std::stable_sort(names.begin(), names.end(), [&](const std::string& a, const std::string& b) {
    return rank(a) < rank(b);
  });
}

inline bool isTable(const nlohmann::json& v) {
  return v.is_array() && !v.empty() &&
         std::all_of(v.begin(), v.end(), [](const nlohmann::json& e) { return e.is_object(); });
}

// A table row's cells, nested objects flattened to dotted names.
inline void flatten(const nlohmann::json& row,
                    const std::string& prefix,
                    std::vector<std::pair<std::string, std::string>>& cells) {
  for (auto it = row.begin(); it != row.end(); ++it) {
    if (it->is_object())
      flatten(*it, prefix + it.key() + ".", cells);
    else
      cells.emplace_back(prefix + it.key(), scalar(*it));
  }
}

inline void printMembers(std::ostream& os,
                         const nlohmann::json& object,
                         const std::string& indent,
                         const std::string& first_indent);

// A table when its rows fit in kWidth columns (a wide terminal); else each row as a list item ("-
// "), its members indented below the first.
constexpr std::size_t kWidth = 160;

inline void printTable(std::ostream& os, const nlohmann::json& rows, const std::string& indent) {
  std::vector<std::string> columns;
  std::vector<std::vector<std::pair<std::string, std::string>>> cells;
  for (const nlohmann::json& row : rows) {
    cells.emplace_back();
    flatten(row, "", cells.back());
    for (const auto& [name, value] : cells.back())
      if (std::find(columns.begin(), columns.end(), name) == columns.end()) columns.push_back(name);
  }
  leadingFirst(columns);
  std::vector<std::size_t> width(columns.size());
  std::vector<std::vector<std::string>> text(cells.size(),
                                             std::vector<std::string>(columns.size(), "-"));
  for (std::size_t c = 0; c < columns.size(); ++c) width[c] = columns[c].size();
  for (std::size_t r = 0; r < cells.size(); ++r)
    for (const auto& [name, value] : cells[r]) {
      const auto c = static_cast<std::size_t>(std::find(columns.begin(), columns.end(), name) -
                                              columns.begin());
      text[r][c] = value;
      width[c] = std::max(width[c], value.size());
    }
  std::size_t total = indent.size();
  for (std::size_t c = 0; c < columns.size(); ++c) total += width[c] + (c ? 2 : 0);
  if (total > kWidth) {
    for (const nlohmann::json& row : rows) printMembers(os, row, indent + "  ", indent + "- ");
    return;
  }
  const auto line = [&](const std::vector<std::string>& row) {
    os << indent;
    for (std::size_t c = 0; c < row.size(); ++c)
      os << (c ? "  " : "") << std::string(width[c] - row[c].size(), ' ') << row[c];
    os << "\n";
  };
  line(columns);
  for (const std::vector<std::string>& row : text) line(row);
}

inline void printMembers(std::ostream& os,
                         const nlohmann::json& object,
                         const std::string& indent,
                         const std::string& first_indent) {
  std::vector<std::string> names;
  for (auto it = object.begin(); it != object.end(); ++it) names.push_back(it.key());
  // Plain values before objects and tables, so that a report opens with its headline figures.
  std::stable_partition(names.begin(), names.end(), [&](const std::string& name) {
    return !object.at(name).is_object() && !isTable(object.at(name));
  });
  leadingFirst(names);
  for (const std::string& name : names) {
    const nlohmann::json& v = object.at(name);
    os << (name == names.front() ? first_indent : indent) << name << ":";
    if (v.is_object()) {
      os << "\n";
      printMembers(os, v, indent + "  ", indent + "  ");
    } else if (isTable(v)) {
      os << "\n";
      printTable(os, v, indent + "  ");
    } else if (v.is_array() && v.empty()) {
      os << " (none)\n";
    } else if (v.is_array()) {
      std::size_t column = indent.size() + name.size() + 1;
      for (const nlohmann::json& e : v) {
        // A string with a space is quoted, so that the items stay apart.
        const bool quote = !e.is_primitive() ||
                           (e.is_string() && e.get<std::string>().find(' ') != std::string::npos);
        const std::string s = quote ? e.dump() : scalar(e);
        if (column + 1 + s.size() > 100 && column > indent.size() + 4) {
          os << "\n" << indent << "   ";
          column = indent.size() + 3;
        }
        os << " " << s;
        column += 1 + s.size();
      }
      os << "\n";
    } else {
      os << " " << scalar(v) << "\n";
    }
  }
}

}  // namespace report_detail

/// `result` as indented text under the line `title` (see the top of this file).
inline void printReport(std::ostream& os, const std::string& title, const nlohmann::json& result) {
  os << title << "\n";
  if (result.is_object())
    report_detail::printMembers(os, result, "  ", "  ");
  else
    report_detail::printMembers(os, nlohmann::json{{"result", result}}, "  ", "  ");
}

/// The one output of an example: `result` as JSON when `json`, else as text under `title`.
inline void writeResult(std::ostream& os,
                        bool json,
                        const std::string& title,
                        const nlohmann::json& result) {
  if (json)
    os << result.dump(2) << "\n";
  else
    printReport(os, title, result);
}

}  // namespace sylva_examples
