// nimbus.render: `nimbus render`'s clouds (render_to_image.hpp), the image as a NumPy array.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <tuple>

#include "calls.hpp"
#include "nimbus/render/core/cloud_source.hpp"
#include "py_volume.hpp"
#include "nimbus/render/core/render_settings.hpp"
#include "render_to_image.hpp"

namespace nimbus::python {
namespace {

namespace py = pybind11;

// A Volume as the cloud its file would be (written in float, read back as `nimbus render` reads
// it), without the file: its grid, turned y-up from its own up axis, negative values read as 0.
cli::MemoryCloud memory_cloud(const Volume& v, const std::string& name, std::size_t position,
                              std::vector<std::string>& warnings) {
  cli::MemoryCloud m;
  m.name = name;
  m.position = position;
  try {
    check_density(v.box, v.grid, true);  // a NaN would become empty space in the grid
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(name + ": " + e.what());
  }
  const openvdb::FloatGrid::Ptr grid = volume::grid_from_dense_box(v.box, *v.transform);
  render::CloudFileOptions options;
  options.warn = [&](const std::string& text) { warnings.push_back(text); };
  m.grid = render::cloud_grid_in_memory(*grid, v.metadata, v.up_axis == 'z' ? render::UpAxis::Z : render::UpAxis::Y,
                                        name, options, &m.period_m);
  return m;
}

// The image, and the warnings of its in-memory clouds (negative values read as 0).
using VolumeArg = std::tuple<std::size_t, py::object, std::string>;  // its place among the paths, it, its name

py::tuple render(const std::vector<std::string>& args, const std::vector<VolumeArg>& volumes) {
  std::vector<std::pair<const Volume*, std::pair<std::size_t, std::string>>> held;
  for (const auto& [position, object, name] : volumes) held.push_back({&volume_of(object), {position, name}});
  auto image = std::make_unique<render::Image>();
  std::vector<std::string> warnings;
  run_interruptible([&] {
    std::vector<cli::MemoryCloud> memory;
    for (const auto& [v, where] : held) memory.push_back(memory_cloud(*v, where.second, where.first, warnings));
    *image = cli::render_clouds_image(args, std::move(memory));
  });
  // The image's own buffer, handed to NumPy: (height, width, RGBA), row 0 at the top.
  auto* pixels = new std::vector<float>(std::move(image->rgba));
  py::capsule owner(pixels, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  py::array out = py::array_t<float>({py::ssize_t(image->height), py::ssize_t(image->width), py::ssize_t(4)},
                                     pixels->data(), owner);
  return py::make_tuple(out, warnings);
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
