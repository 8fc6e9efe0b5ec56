// The files a run reads, from what it parsed (run_inputs.hpp).
#include "run_inputs.hpp"

#include <stdexcept>

#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/sequence_pattern.hpp"
#include "nimbus/render/sky/sky_keyframes.hpp"

namespace nimbus::cli {

RunInputs& RunInputs::file(const std::string& what, const std::string& path) {
  if (!path.empty()) paths_.push_back({what, path});
  return *this;
}

RunInputs& RunInputs::cloud(const volume::CloudParams& params, const std::string& what) {
  return file(what + ".coverage_map", params.coverage_map);
}

RunInputs& RunInputs::sky(const volume::Sky& sky, const std::string& what) {
  for (std::size_t i = 0; i < sky.clouds.size(); ++i) {
    const volume::SkyCloud& c = sky.clouds[i];
    const std::string at = what + " clouds[" + std::to_string(i) + "].";
    if (!c.file.empty()) {
      const SequencePattern pattern = SequencePattern::parse(c.file, at + "file");
      if (!pattern.has_field) {
        file(at + "file", c.file);
        continue;
      }
      try {
        for (const int frame : render::existing_sequence_frames(c.file)) file(at + "file", pattern.path(frame));
      } catch (const std::runtime_error&) {
        // No frame exists: nothing of it to overwrite (the sky's own checks refuse it).
      }
    }
    const auto map = c.overrides.find("coverage_map");
    if (map != c.overrides.end() && map->is_string()) file(at + "overrides.coverage_map", map->get<std::string>());
  }
  return *this;
}

}  // namespace nimbus::cli
