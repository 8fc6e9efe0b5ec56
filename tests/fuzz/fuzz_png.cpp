// Fuzz target: reading coverage maps (volume/src/coverage_png.cpp), as `nimbus generate` does for
// a cloud's "coverage_map": the input bytes are written to a file and read_coverage_png reads it
// (the file's kind and size, the IHDR against the file's size and the memory, then libpng).
//
// The contract checked (coverage_map.hpp): every failure is a std::runtime_error whose message is
// one line of at most 64 KB starting with "coverage map '<path>'"; a map that was read is within
// kMaxCoverageMapSide a side and kMaxCoverageMapPixels in all, holds width * height values, each
// in [0, 1], and names its file. Anything else, and any crash, hang or runaway allocation (a
// header may not make the reader allocate more than the file can hold), is a finding.
#include <cmath>
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>

#include "fuzz_common.hpp"
#include "nimbus/volume/coverage_map.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace volume = nimbus::volume;
  using nimbus::fuzz::contract_failure;
  static const nimbus::fuzz::ScratchFile file(".png");
  file.write(std::string_view(reinterpret_cast<const char*>(data), size));
  const std::string& path = file.path();
  try {
    const auto map = volume::read_coverage_png(path);
    if (!map) contract_failure("read_coverage_png returned no map and threw nothing");
    if (map->width < 1 || map->height < 1 || map->width > volume::kMaxCoverageMapSide ||
        map->height > volume::kMaxCoverageMapSide ||
        int64_t(map->width) * map->height > volume::kMaxCoverageMapPixels)
      contract_failure("read_coverage_png returned a " + std::to_string(map->width) + " x " +
                       std::to_string(map->height) + " map");
    if (map->value.size() != size_t(map->width) * size_t(map->height))
      contract_failure("read_coverage_png returned a map whose values do not match its size");
    for (const float v : map->value)
      if (!(v >= 0.0f && v <= 1.0f)) contract_failure("read_coverage_png returned a value outside [0, 1]");
    if (map->source != path) contract_failure("the map does not name its file");
  } catch (const std::runtime_error& e) {
    const std::string_view what = e.what();
    if (what.size() > (64 << 10)) contract_failure("a message of " + std::to_string(what.size()) + " bytes");
    if (!nimbus::fuzz::one_line(what)) contract_failure("the message is not one line: " + std::string(what));
    if (what.substr(0, 14 + path.size()) != "coverage map '" + path)
      contract_failure("the message does not start with \"coverage map '<path>'\": " + std::string(what));
  } catch (const std::exception& e) {
    contract_failure("read_coverage_png threw " + nimbus::fuzz::type_name(e) + ", not std::runtime_error: " + e.what());
  }
  return 0;
}
