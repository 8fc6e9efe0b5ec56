// The shared body of the harnesses for JSON documents that nimbus reads whole and writes back
// (fuzz_sky.cpp, fuzz_view_state.cpp): the input bytes are written to a file and loaded; every
// refusal must be a std::invalid_argument or std::runtime_error whose message is one line (at
// most 64 KB) and starts with "<what> '<path>'" (main.cpp prints it as the one stderr line, exit
// 2 or 1); anything else would reach the user without naming the file. An accepted document must
// pass validate(), read back from its own JSON, and write the same JSON again.
#pragma once
#include <cstdint>
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fuzz_common.hpp"

namespace nimbus::fuzz {

// How one kind of document is loaded, checked and written: `load(path)`, `validate(doc)`,
// `to_json(doc)` and `from_json(json, where)`, named `what` ("sky file", "view state").
template <typename Doc, typename Load, typename Validate, typename ToJson, typename FromJson>
struct JsonDocument {
  std::string what, load_name;
  Load load;
  Validate validate;
  ToJson to_json;
  FromJson from_json;

  static constexpr size_t kMessageLimit = 64 << 10;  // a one-line message a person can read

  void expect_named(const std::exception& e, const std::string& prefix) const {
    const std::string_view m = e.what();
    if (m.size() > kMessageLimit)
      contract_failure(load_name + ": a message of " + std::to_string(m.size()) + " bytes: " + std::string(m.substr(0, 200)) + "...");
    if (!one_line(m)) contract_failure(load_name + ": the message is not one line: " + std::string(m));
    if (m.substr(0, prefix.size()) != prefix)
      contract_failure(load_name + ": the message does not start with \"" + prefix + "\": " + std::string(m));
  }

  // The JSON text of a document; dump() throws on a string that is not UTF-8, which a saved one may not hold.
  std::string text_of(const Doc& doc, const std::string& step) const {
    try {
      return to_json(doc).dump();
    } catch (const std::exception& e) {
      contract_failure(step + ": the " + what + "'s JSON .dump() threw " + type_name(e) + ": " + e.what());
    }
  }

  void expect_round_trip(const Doc& doc) const {
    try {
      validate(doc);
    } catch (const std::exception& e) {
      contract_failure("an accepted " + what + " fails validate(): " + e.what());
    }
    const std::string first = text_of(doc, "the accepted " + what);
    Doc again;
    try {
      again = from_json(to_json(doc), "roundtrip");
    } catch (const std::exception& e) {
      contract_failure("an accepted " + what + " does not read back from its JSON: " + type_name(e) + ": " + e.what() +
                       " (JSON: " + first.substr(0, 2000) + ")");
    }
    const std::string second = text_of(again, "the " + what + " read back");
    if (second != first)
      contract_failure("the " + what + "'s JSON differs after a round trip:\n  " + first.substr(0, 2000) + "\n  " +
                       second.substr(0, 2000));
  }

  int run(const uint8_t* data, size_t size) const {
    static const ScratchFile file(".json");
    file.write(std::string_view(reinterpret_cast<const char*>(data), size));
    const std::string prefix = what + " '" + file.path() + "'";
    Doc doc;
    try {
      doc = load(file.path());
    } catch (const std::invalid_argument& e) {
      expect_named(e, prefix);
      return 0;
    } catch (const std::runtime_error& e) {
      expect_named(e, prefix);
      return 0;
    } catch (const std::exception& e) {
      contract_failure(load_name + " threw " + type_name(e) + ", not std::invalid_argument or std::runtime_error: " + e.what());
    }
    expect_round_trip(doc);
    return 0;
  }
};

template <typename Doc, typename Load, typename Validate, typename ToJson, typename FromJson>
JsonDocument<Doc, Load, Validate, ToJson, FromJson> json_document(std::string what, std::string load_name, Load load,
                                                                  Validate validate, ToJson to_json, FromJson from_json) {
  return {std::move(what), std::move(load_name), load, validate, to_json, from_json};
}

}  // namespace nimbus::fuzz
