// nimbus.render: `nimbus render`'s clouds (render_to_image.hpp), the image as a NumPy array.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>

#include "calls.hpp"
#include "nimbus/render/core/render_settings.hpp"
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
    py::list out;  // (flag, takes a value, its default as --help shows it, its help)
    for (const cli::ImageFlag& f : cli::render_image_flags())
      out.append(py::make_tuple(f.name, f.takes_value, f.default_text, f.help));
    return out;
  });
  m.def("_render_settings", [] {
    py::list out;  // the one table (render_settings.hpp), a dict per setting
    for (const render::RenderSetting& s : render::kRenderSettings) {
      py::dict d;
      d["flag"] = std::string(s.flag);
      d["view_key"] = std::string(s.view_key);
      d["unit"] = std::string(s.unit);
      d["integer"] = s.integer;
      d["min"] = s.min;
      d["max"] = s.max;
      d["min_open"] = s.min_open;
      d["max_open"] = s.max_open;
      d["range"] = render::range_text(s);
      d["default"] = s.still_default;
      d["default_text"] = std::string(s.default_text);
      d["view_default"] = s.view_default;
      d["view_reason"] = std::string(s.view_reason);
      d["help"] = std::string(s.help);
      out.append(d);
    }
    return out;
  });
}

}  // namespace nimbus::python
