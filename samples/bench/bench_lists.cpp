// The benchmarks' list flags (bench_lists.hpp).
#include "bench_lists.hpp"

#include <optional>
#include <sstream>

#include "cli/cli.hpp"
#include "nimbus/base/validate.hpp"

namespace nimbus::cli {

std::vector<int> parse_ints(const std::string& flag, const std::string& text, int hi, int lo) {
  std::vector<int> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) v.push_back(nimbus::parse_int_in(item, lo, hi, flag));
  if (v.empty()) throw UsageError(flag + ": give at least one number");
  return v;
}

std::vector<double> parse_doubles(const std::string& flag, const std::string& text, double lo, double hi) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const std::optional<double> x = nimbus::parse_double(item);
    if (!x || !(*x >= lo && *x <= hi))
      throw UsageError(flag + ": '" + item + "' is not a number in [" + number_text(lo) + ", " + number_text(hi) + "]");
    v.push_back(*x);
  }
  if (v.empty()) throw UsageError(flag + ": give at least one number");
  return v;
}

std::string slug(const std::string& name) {
  std::string s;
  for (char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.';
    const char out = keep ? c : (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : '-';
    if (out != '-' || (!s.empty() && s.back() != '-')) s += out;
  }
  while (!s.empty() && s.back() == '-') s.pop_back();
  return s;
}

void check_case_list(const std::string& flag, const std::string& list, const std::vector<std::string>& names) {
  std::stringstream ss(list);
  std::string item;
  int items = 0;
  while (std::getline(ss, item, ',')) {
    bool found = false;
    for (const std::string& n : names) found = found || (!item.empty() && n.rfind(item, 0) == 0);
    if (!found) throw UsageError(flag + ": '" + item + "' names none of its cases");
    ++items;
  }
  if (items == 0) throw UsageError(flag + ": give at least one case");
}

bool chosen(const std::string& list, const std::string& name) {
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty() && name.rfind(item, 0) == 0) return true;
  return false;
}

}  // namespace nimbus::cli
