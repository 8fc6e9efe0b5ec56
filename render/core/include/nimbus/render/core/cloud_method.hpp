// How clouds are rendered, as named on the command line: the half-angle slicer on the GPU, the
// exact single-scattering CPU reference, or the CPU path tracer with multiple scattering (both
// CPU methods: clouds alone). The frame pipeline (frame/frame_renderer.hpp) takes it.
#pragma once
#include <string>

namespace nimbus::render {

enum class CloudMethod { Slices, Reference, PathTrace };

// "slices", "reference", "pathtrace"; std::invalid_argument naming the text otherwise.
CloudMethod parse_cloud_method(const std::string& text);
std::string to_string(CloudMethod method);
// The CPU methods, which render the clouds alone.
inline bool is_cpu_method(CloudMethod m) { return m != CloudMethod::Slices; }

}  // namespace nimbus::render
