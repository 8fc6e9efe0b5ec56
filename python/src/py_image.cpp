// nimbus.write_image and read_image: a render as the program's files (linear half-float EXR and
// a filmic PNG preview, written together and atomically) and back.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>

#include "calls.hpp"
#include "nimbus/app/usage_error.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "outputs.hpp"

namespace nimbus::python {
namespace {

namespace py = pybind11;

void write_image(const std::filesystem::path& exr, const std::string& preview, const py::array& pixels,
                 std::optional<double> exposure, const std::map<std::string, std::string>& metadata) {
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(pixels);
  if (!a || a.ndim() != 3 || a.shape(2) != 4 || a.shape(0) < 1 || a.shape(1) < 1)
    throw app::UsageError("image: must be a (height, width, 4) array of RGBA numbers, as render returns");
  render::Image image(int(a.shape(1)), int(a.shape(0)));
  std::copy(a.data(), a.data() + a.size(), image.rgba.begin());
  image.metadata = metadata;
  if (exposure && !(std::abs(*exposure) <= 64.0)) throw app::UsageError("exposure: must be within [-64, 64] stops");
  run_interruptible([&] {
    render::check_image(image, "image");
    cli::check_outputs({{"path", exr.string()}, {"preview", preview}});
    render::PreviewOptions po;
    if (!preview.empty()) po.exposure_stops = exposure ? *exposure : render::auto_exposure_stops(image);
    cli::write_image_files(exr.string(), preview, image, po);
  });
}

py::tuple read_image(const std::filesystem::path& path) {
  render::Image image;
  run_interruptible([&] { image = render::read_exr(path); });
  py::array_t<float> out({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(4)});
  std::copy(image.rgba.begin(), image.rgba.end(), out.mutable_data());
  return py::make_tuple(out, image.metadata);
}

}  // namespace

void bind_image(py::module_& m) {
  m.def("_write_image", &write_image);
  m.def("_read_image", &read_image);
}

}  // namespace nimbus::python
