// JSON documents built into the binary at configure time (volume/cmake_embed_presets.cmake):
// the presets (volume/presets/*.json) and the skies (volume/skies/*.json).
#pragma once
#include <cstddef>

namespace nimbus::volume {

struct EmbeddedJson {
  const char* name;  // the file name without .json
  const char* text;
};
extern const EmbeddedJson kEmbeddedPresets[];
extern const std::size_t kEmbeddedPresetsCount;
extern const EmbeddedJson kEmbeddedSkies[];
extern const std::size_t kEmbeddedSkiesCount;

}  // namespace nimbus::volume
