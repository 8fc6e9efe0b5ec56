// How clouds are rendered, as named on the command line: the half-angle slicer on the GPU, or
// the exact CPU reference (clouds alone). The frame pipeline (frame/frame_renderer.hpp) takes it.
#pragma once
#include <string>

namespace nimbus::render {

enum class CloudMethod { Slices, Reference };

// "slices", "reference"; std::invalid_argument naming the text otherwise.
CloudMethod parse_cloud_method(const std::string& text);
std::string to_string(CloudMethod method);

}  // namespace nimbus::render
