// Cloud method names (cloud_method.hpp).
#include "nimbus/render/core/cloud_method.hpp"

#include <stdexcept>

namespace nimbus::render {

CloudMethod parse_cloud_method(const std::string& text) {
  if (text == "slices") return CloudMethod::Slices;
  if (text == "reference") return CloudMethod::Reference;
  throw std::invalid_argument("cloud method '" + text + "': expected slices or reference");
}

std::string to_string(CloudMethod method) {
  switch (method) {
    case CloudMethod::Slices: return "slices";
    case CloudMethod::Reference: return "reference";
  }
  return "?";
}

}  // namespace nimbus::render
