// Fuzz target: reading sky files (volume/src/sky.cpp), as `nimbus view --sky FILE` does: the
// input bytes are written to a file and load_sky_file reads it (read_json_file's size, kind and
// depth limits, then sky_from_json, which validates every cloud's preset and overrides).
//
// The contract checked (sky.hpp; main.cpp turns std::invalid_argument into exit 2 and
// std::runtime_error into exit 1, each with the message on one stderr line): every refusal is a
// std::invalid_argument or a std::runtime_error whose message is one line (at most 64 KB) and
// starts with "sky file '<path>'". Anything else (nlohmann's exceptions, std::out_of_range from a
// conversion, std::logic_error...) would reach the user without naming the file; it is reported
// as a finding. A sky that was accepted must pass validate() and survive the trip through JSON
// that "Save sky" and view states make: sky_from_json(sky_to_json(s)) succeeds and writes the
// same JSON again.
#include <cstdint>
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "fuzz_common.hpp"
#include "nimbus/volume/sky.hpp"

namespace {

using nimbus::fuzz::contract_failure;
using nimbus::fuzz::one_line;

constexpr size_t kMessageLimit = 64 << 10;  // a one-line message a person can read

void expect_named(const std::exception& e, const std::string& prefix) {
  const std::string_view what = e.what();
  if (what.size() > kMessageLimit)
    contract_failure("load_sky_file: a message of " + std::to_string(what.size()) + " bytes: " +
                     std::string(what.substr(0, 200)) + "...");
  if (!one_line(what)) contract_failure("load_sky_file: the message is not one line: " + std::string(what));
  if (what.substr(0, prefix.size()) != prefix)
    contract_failure("load_sky_file: the message does not start with \"" + prefix + "\": " + std::string(what));
}

// The JSON text of a sky; dump() throws on a string that is not UTF-8, which a saved sky may not hold.
std::string text_of(const nimbus::volume::Sky& sky, const std::string& step) {
  try {
    return nimbus::volume::sky_to_json(sky).dump();
  } catch (const std::exception& e) {
    contract_failure(step + ": sky_to_json(...).dump() threw " + nimbus::fuzz::type_name(e) + ": " + e.what());
  }
}

void expect_round_trip(const nimbus::volume::Sky& sky) {
  namespace volume = nimbus::volume;
  try {
    volume::validate(sky);
  } catch (const std::exception& e) {
    contract_failure(std::string("an accepted sky fails validate(): ") + e.what());
  }
  const std::string first = text_of(sky, "the accepted sky");
  volume::Sky again;
  try {
    again = volume::sky_from_json(volume::sky_to_json(sky), "roundtrip");
  } catch (const std::exception& e) {
    contract_failure("an accepted sky does not read back from sky_to_json: " + nimbus::fuzz::type_name(e) + ": " +
                     e.what() + " (JSON: " + first.substr(0, 2000) + ")");
  }
  const std::string second = text_of(again, "the sky read back");
  if (second != first)
    contract_failure("sky_to_json differs after a round trip:\n  " + first.substr(0, 2000) + "\n  " +
                     second.substr(0, 2000));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace volume = nimbus::volume;
  static const nimbus::fuzz::ScratchFile file(".json");
  file.write(std::string_view(reinterpret_cast<const char*>(data), size));
  const std::string prefix = "sky file '" + file.path() + "'";

  volume::Sky sky;
  try {
    sky = volume::load_sky_file(file.path());
  } catch (const std::invalid_argument& e) {
    expect_named(e, prefix);
    return 0;
  } catch (const std::runtime_error& e) {
    expect_named(e, prefix);
    return 0;
  } catch (const std::exception& e) {
    contract_failure("load_sky_file threw " + nimbus::fuzz::type_name(e) +
                     ", not std::invalid_argument or std::runtime_error: " + e.what());
  }
  expect_round_trip(sky);
  return 0;
}
