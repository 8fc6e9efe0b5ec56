// A flag whose text becomes a typed field as CLI11 reads it: the command line is an adapter over
// typed request fields, so nothing downstream parses text. A parser's error (a UsageError, which
// names the flag, or a library's std::invalid_argument) becomes CLI11's ValidationError naming
// the flag: a usage error (exit 2), as every parse error is.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.hpp"

namespace nimbus::cli {

// parse(text) for flag `name`, its errors as CLI11's ValidationError naming the flag.
template <typename Parse>
auto parse_flag_text(const std::string& name, const std::string& text, const Parse& parse) {
  if (text.empty()) throw CLI::ValidationError(name + ": the value is empty (leave the flag out for its default)");
  try {
    return parse(text);
  } catch (const UsageError& e) {
    throw CLI::ValidationError(e.what());
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError(name, e.what());
  }
}

// --NAME TEXT sets `field = parse(TEXT)`; `default_text` is what --help and Python show as the
// default when the flag is left out.
template <typename T, typename Parse>
CLI::Option* add_typed_option(CLI::App* cmd, const std::string& name, T& field, Parse parse, const std::string& help,
                              const std::string& default_text = "") {
  CLI::Option* option = cmd->add_option_function<std::string>(
      name, [&field, parse, name](const std::string& text) { field = parse_flag_text(name, text, parse); }, help);
  if (!default_text.empty()) option->default_str(default_text);
  return option;
}

// A repeatable --NAME TEXT: each value parsed into `field`, in order.
template <typename T, typename Parse>
CLI::Option* add_typed_list_option(CLI::App* cmd, const std::string& name, std::vector<T>& field, Parse parse,
                                   const std::string& help) {
  return cmd->add_option_function<std::vector<std::string>>(
      name,
      [&field, parse, name](const std::vector<std::string>& texts) {
        field.clear();
        for (const std::string& text : texts) field.push_back(parse_flag_text(name, text, parse));
      },
      help);
}

}  // namespace nimbus::cli
