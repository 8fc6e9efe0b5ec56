// Fuzz target: reading EXR files (render/image/src/image_exr.cpp), as `nimbus render compare`,
// `nimbus farm check` and nimbus.read_image do: the input bytes are written to a file and
// read_exr reads it (the header check of exr_header_check.cpp, then OpenEXR).
//
// The contract checked (image_io.hpp): every failure is a std::runtime_error whose message is one
// line of at most 64 KB that names the file; an image that was read has a size of 1 to 2^28
// pixels and width * height * 4 values. Anything else, and any crash, hang or runaway allocation
// (a header may not make the reader allocate more than the file can hold), is a finding.
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>

#include "fuzz_common.hpp"
#include "nimbus/render/image/image_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using nimbus::fuzz::contract_failure;
  static const nimbus::fuzz::ScratchFile file(".exr");
  file.write(std::string_view(reinterpret_cast<const char*>(data), size));
  const std::string& path = file.path();
  try {
    const nimbus::render::Image image = nimbus::render::read_exr(path);
    if (image.width < 1 || image.height < 1 || int64_t(image.width) * image.height > (int64_t(1) << 28))
      contract_failure("read_exr returned a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                       " image");
    if (image.rgba.size() != size_t(image.width) * size_t(image.height) * 4)
      contract_failure("read_exr returned an image whose values do not match its size");
  } catch (const std::runtime_error& e) {
    const std::string_view what = e.what();
    if (what.size() > (64 << 10)) contract_failure("a message of " + std::to_string(what.size()) + " bytes");
    if (!nimbus::fuzz::one_line(what)) contract_failure("the message is not one line: " + std::string(what));
    if (what.find(path) == std::string_view::npos)
      contract_failure("the message does not name the file: " + std::string(what));
  } catch (const std::exception& e) {
    contract_failure("read_exr threw " + nimbus::fuzz::type_name(e) + ", not std::runtime_error: " + e.what());
  }
  return 0;
}
