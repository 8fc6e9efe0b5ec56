// Fuzz target: reading sky files (volume/src/sky.cpp), as `nimbus view --sky FILE` does: the
// input bytes are written to a file and load_sky_file reads it (read_json_file's size, kind and
// depth limits, then sky_from_json, which validates every cloud's preset and overrides). The
// contract (fuzz_json_document.hpp): refusals start with "sky file '<path>'" on one line; an
// accepted sky survives the trip through JSON that "Save sky" and view states make.
#include "fuzz_json_document.hpp"
#include "nimbus/volume/sky.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace volume = nimbus::volume;
  static const auto target = nimbus::fuzz::json_document<volume::Sky>(
      "sky file", "load_sky_file", [](const std::string& p) { return volume::load_sky_file(p); },
      [](const volume::Sky& s) { volume::validate(s); }, [](const volume::Sky& s) { return volume::sky_to_json(s); },
      [](const nlohmann::json& j, const std::string& where) { return volume::sky_from_json(j, where); });
  return target.run(data, size);
}
