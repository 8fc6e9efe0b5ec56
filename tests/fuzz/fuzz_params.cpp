// Fuzz target: the JSON parameter path of `nimbus generate --preset NAME --params FILE --set K=V`
// (samples/cli/cmd_generate.cpp): load_preset, merge_params_file, set_key on "cloud",
// cloud_from_json(doc.at("cloud")), preset_voxel_size(doc, preset); and, for parameters that
// were accepted, cloud_to_json read back by cloud_from_json.
//
// Input layout (every byte sequence is valid):
//   [preset:NAME\n]   optional first line choosing the preset (default cumulus-congestus)
//   PARAMS            the --params file's bytes, up to the first NUL
//   \0SET\0SET...     optional --set arguments, NUL-separated
//
// The contract checked (preset.hpp; main.cpp turns std::invalid_argument into exit 2 with the
// message on one stderr line): every refusal is a std::invalid_argument whose message is one
// line and names the input: "--params FILE...", "--set ..." or the preset name (the "where"
// of cloud_from_json; a --set argument that itself holds a line break may be echoed). Any other exception would reach the user as "nimbus: error: ..." with
// exit 1 and, for nlohmann's exceptions, without naming the file; it is reported as a finding.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "fuzz_common.hpp"
#include "nimbus/volume/preset.hpp"

namespace {

using nimbus::fuzz::contract_failure;
using nimbus::fuzz::one_line;

void expect_named(const std::invalid_argument& e, const std::string& step, std::string_view prefix) {
  const std::string_view what = e.what();
  if (!one_line(what)) contract_failure(step + ": the message is not one line: " + std::string(what));
  // "--params FILE" or "--params 'FILE'": the file named, quoted or not.
  std::string quoted(prefix);
  if (const size_t space = quoted.find(' '); space != std::string::npos && quoted.rfind("--", 0) == 0)
    quoted = quoted.substr(0, space + 1) + "'" + quoted.substr(space + 1) + "'";
  if (what.substr(0, prefix.size()) != prefix && what.substr(0, quoted.size()) != quoted)
    contract_failure(step + ": the message does not start with '" + std::string(prefix) + "': " + std::string(what));
}

[[noreturn]] void wrong_type(const std::string& step, const std::exception& e) {
  contract_failure(step + " threw " + nimbus::fuzz::type_name(e) + ", not std::invalid_argument: " + e.what());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace volume = nimbus::volume;
  static const nimbus::fuzz::ScratchFile params_file(".json");

  std::string_view in(reinterpret_cast<const char*>(data), size);
  std::string preset = "cumulus-congestus";
  if (in.substr(0, 7) == "preset:") {
    const size_t nl = in.find('\n');
    preset = std::string(in.substr(7, nl == std::string_view::npos ? std::string_view::npos : nl - 7));
    in.remove_prefix(nl == std::string_view::npos ? in.size() : nl + 1);
  }
  const size_t nul = in.find('\0');
  params_file.write(in.substr(0, nul));
  std::vector<std::string> sets;
  for (size_t at = nul; at != std::string_view::npos;) {
    const size_t next = in.find('\0', at + 1);
    sets.emplace_back(in.substr(at + 1, next == std::string_view::npos ? std::string_view::npos : next - at - 1));
    at = next;
  }

  nlohmann::json doc;
  try {
    doc = volume::load_preset(preset);
  } catch (const std::invalid_argument& e) {
    expect_named(e, "load_preset", "unknown preset '");
    return 0;
  } catch (const std::exception& e) {
    wrong_type("load_preset", e);
  }

  const std::string& path = params_file.path();
  try {
    volume::merge_params_file(doc, path);
  } catch (const std::invalid_argument& e) {
    expect_named(e, "merge_params_file", "--params " + path);
    return 0;
  } catch (const std::exception& e) {
    wrong_type("merge_params_file", e);
  }
  for (const std::string& s : sets) {
    try {
      volume::set_key(doc["cloud"], s);
    } catch (const std::invalid_argument& e) {
      // A line break the user typed into their own --set argument may come back in the
      // message; one read from a file may not (merge_params_file, cloud_from_json).
      if (s.find('\n') == std::string::npos) expect_named(e, "set_key", "--set");
      return 0;
    } catch (const std::exception& e) {
      wrong_type("set_key '" + s + "'", e);
    }
  }

  volume::CloudParams params;
  try {
    params = volume::cloud_from_json(doc.at("cloud"), preset);
    const double voxel_size = volume::preset_voxel_size(doc, preset);  // as cmd_generate reads it
    (void)voxel_size;
  } catch (const std::invalid_argument& e) {
    expect_named(e, "cloud_from_json", preset);
    return 0;
  } catch (const std::exception& e) {
    wrong_type("cloud_from_json(doc.at(\"cloud\")) or preset_voxel_size", e);
  }

  // Accepted parameters written back as JSON (nimbus presets NAME, view states) read back.
  try {
    (void)volume::cloud_from_json(volume::cloud_to_json(params), "roundtrip");
  } catch (const std::exception& e) {
    contract_failure(std::string("accepted parameters do not read back from cloud_to_json: ") + e.what());
  }
  return 0;
}
