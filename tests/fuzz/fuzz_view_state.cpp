// Fuzz target: reading view states (render/core/src/view_state.cpp), as `nimbus view --state
// FILE` and `nimbus render --view-state FILE` do: the input bytes are written to a file and
// load_view_state reads it (read_json_file's size, kind and depth limits, then
// view_state_from_json: the sky inside, the scene, camera, clocks, optics and renderer).
//
// The contract checked (view_state.hpp; main.cpp turns std::invalid_argument into exit 2 and
// std::runtime_error into exit 1, each with the message on one stderr line): every refusal is a
// std::invalid_argument or a std::runtime_error whose message is one line (at most 64 KB) and
// starts with "view state '<path>'". Anything else would reach the user without naming the file;
// it is reported as a finding. A state that was accepted must pass validate() and survive the
// trip through JSON that Ctrl+S / Ctrl+O and the screenshots' metadata make:
// view_state_from_json(view_state_to_json(s)) succeeds and writes the same JSON again.
#include <cstdint>
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "fuzz_common.hpp"
#include "nimbus/render/core/view_state.hpp"

namespace {

using nimbus::fuzz::contract_failure;
using nimbus::fuzz::one_line;

constexpr size_t kMessageLimit = 64 << 10;  // a one-line message a person can read

void expect_named(const std::exception& e, const std::string& prefix) {
  const std::string_view what = e.what();
  if (what.size() > kMessageLimit)
    contract_failure("load_view_state: a message of " + std::to_string(what.size()) + " bytes: " +
                     std::string(what.substr(0, 200)) + "...");
  if (!one_line(what)) contract_failure("load_view_state: the message is not one line: " + std::string(what));
  if (what.substr(0, prefix.size()) != prefix)
    contract_failure("load_view_state: the message does not start with \"" + prefix + "\": " + std::string(what));
}

// The JSON text of a state; dump() throws on a string that is not UTF-8, which a saved state may not hold.
std::string text_of(const nimbus::render::ViewState& state, const std::string& step) {
  try {
    return nimbus::render::view_state_to_json(state).dump();
  } catch (const std::exception& e) {
    contract_failure(step + ": view_state_to_json(...).dump() threw " + nimbus::fuzz::type_name(e) + ": " + e.what());
  }
}

void expect_round_trip(const nimbus::render::ViewState& state) {
  namespace render = nimbus::render;
  try {
    render::validate(state);
  } catch (const std::exception& e) {
    contract_failure(std::string("an accepted view state fails validate(): ") + e.what());
  }
  const std::string first = text_of(state, "the accepted state");
  render::ViewState again;
  try {
    again = render::view_state_from_json(render::view_state_to_json(state), "roundtrip");
  } catch (const std::exception& e) {
    contract_failure("an accepted view state does not read back from view_state_to_json: " +
                     nimbus::fuzz::type_name(e) + ": " + e.what() + " (JSON: " + first.substr(0, 2000) + ")");
  }
  const std::string second = text_of(again, "the state read back");
  if (second != first)
    contract_failure("view_state_to_json differs after a round trip:\n  " + first.substr(0, 2000) + "\n  " +
                     second.substr(0, 2000));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace render = nimbus::render;
  static const nimbus::fuzz::ScratchFile file(".json");
  file.write(std::string_view(reinterpret_cast<const char*>(data), size));
  const std::string prefix = "view state '" + file.path() + "'";

  render::ViewState state;
  try {
    state = render::load_view_state(file.path());
  } catch (const std::invalid_argument& e) {
    expect_named(e, prefix);
    return 0;
  } catch (const std::runtime_error& e) {
    expect_named(e, prefix);
    return 0;
  } catch (const std::exception& e) {
    contract_failure("load_view_state threw " + nimbus::fuzz::type_name(e) +
                     ", not std::invalid_argument or std::runtime_error: " + e.what());
  }
  expect_round_trip(state);
  return 0;
}
