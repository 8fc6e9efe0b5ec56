// nimbus.render: `nimbus render`'s clouds (render_to_image.hpp), the image as a NumPy array.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>

#include "calls.hpp"
#include "render_to_image.hpp"

namespace nimbus::python {
namespace {

namespace py = pybind11;

py::array render(const std::vector<std::string>& args) {
  auto image = std::make_unique<render::Image>();
  run_interruptible([&] { *image = cli::render_clouds_image(args); });
  // The image's own buffer, handed to NumPy: (height, width, RGBA), row 0 at the top.
  auto* pixels = new std::vector<float>(std::move(image->rgba));
  py::capsule owner(pixels, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array_t<float>({py::ssize_t(image->height), py::ssize_t(image->width), py::ssize_t(4)}, pixels->data(), owner);
}

}  // namespace

void bind_render(py::module_& m) {
  m.def("_render", &render);
  m.def("_render_flags", [] {
    py::list out;  // (flag, takes a value)
    for (const cli::ImageFlag& f : cli::render_image_flags()) out.append(py::make_tuple(f.name, f.takes_value));
    return out;
  });
}

}  // namespace nimbus::python
