// Fuzz target: reading view states (render/core/src/view_state.cpp), as `nimbus view --state
// FILE` and `nimbus render --view-state FILE` do: the input bytes are written to a file and
// load_view_state reads it (read_json_file's size, kind and depth limits, then
// view_state_from_json: the sky inside, the scene, camera, clocks, optics and renderer). The
// contract (fuzz_json_document.hpp): refusals start with "view state '<path>'" on one line; an
// accepted state survives the trip through JSON that Ctrl+S / Ctrl+O and screenshots make.
#include "fuzz_json_document.hpp"
#include "nimbus/render/sky/view_state.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace render = nimbus::render;
  static const auto target = nimbus::fuzz::json_document<render::ViewState>(
      "view state", "load_view_state", [](const std::string& p) { return render::load_view_state(p); },
      [](const render::ViewState& s) { render::validate(s); },
      [](const render::ViewState& s) { return render::view_state_to_json(s); },
      [](const nlohmann::json& j, const std::string& where) { return render::view_state_from_json(j, where); });
  return target.run(data, size);
}
