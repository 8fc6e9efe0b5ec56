// Cloud method names (cloud_method.hpp).
#include "nimbus/render/core/cloud_method.hpp"

#include <stdexcept>

namespace nimbus::render {

CloudMethod parse_cloud_method(const std::string& text) {
  if (text == "slices") return CloudMethod::Slices;
  if (text == "reference") return CloudMethod::Reference;
  if (text == "pathtrace") return CloudMethod::PathTrace;
  throw std::invalid_argument("cloud method '" + text + "': expected slices, reference or pathtrace");
}

std::string to_string(CloudMethod method) {
  switch (method) {
    case CloudMethod::Slices: return "slices";
    case CloudMethod::Reference: return "reference";
    case CloudMethod::PathTrace: return "pathtrace";
  }
  return "?";
}

}  // namespace nimbus::render
