// Argument checks and strict number parsing shared by every module: one place for "is this text
// a number", "is this value finite", and the std::invalid_argument that names what is wrong.
#pragma once
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

namespace nimbus {

// Throws std::invalid_argument(message) unless `ok`.
void require(bool ok, const std::string& message);

// `v` as a message shows it: at most 6 significant digits ("1e+300", "0.04", "nan"), never the
// hundreds of digits std::to_string gives a huge double.
std::string number_text(double v);

// True when every value is finite (no NaN, no infinity).
bool all_finite(std::initializer_list<double> values);

// The whole of `text` as a number, as std::from_chars reads it (no leading spaces or '+', no
// trailing characters; "inf" and "nan" are numbers here, so check finiteness separately);
// nullopt when it is not one.
std::optional<double> parse_double(std::string_view text);
// The whole of `text` as a decimal integer in [lo, hi]; nullopt when it is not one or is outside.
std::optional<int> parse_int_in(std::string_view text, int lo, int hi);
// The same, or std::invalid_argument(what + " must be an integer in [lo, hi]").
int parse_int_in(std::string_view text, int lo, int hi, const std::string& what);

}  // namespace nimbus
