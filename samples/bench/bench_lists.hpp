// The benchmarks' list flags: comma-separated numbers (`--ms-grid 32,48`) and names of cases
// (`--phases hg,dual`: each item a prefix of a case's name), and file-name parts from case names.
#pragma once
#include <string>
#include <vector>

namespace nimbus::cli {

// Each item an integer in [lo, hi]; UsageError naming `flag` for a bad one or an empty list.
std::vector<int> parse_ints(const std::string& flag, const std::string& text, int hi = 1 << 20, int lo = 1);
// Each item a number in [lo, hi]; UsageError naming `flag` and the range otherwise.
std::vector<double> parse_doubles(const std::string& flag, const std::string& text, double lo, double hi);

// A file-name part from a case or method name: lower-case letters, digits and '.', the rest '-'.
std::string slug(const std::string& name);

// UsageError naming `flag` unless every item of `list` names a case (a prefix of its name).
void check_case_list(const std::string& flag, const std::string& list, const std::vector<std::string>& names);
// Whether a case's name starts with an item of the list.
bool chosen(const std::string& list, const std::string& name);

}  // namespace nimbus::cli
