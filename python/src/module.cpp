// The compiled part of the Python package nimbus (python/nimbus/__init__.py is its face).
#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>

#include "calls.hpp"
#include "nimbus/volume/vdb_read.hpp"
#include "py_volume.hpp"

namespace nimbus::python {
void bind_generate(pybind11::module_& m);
void bind_render(pybind11::module_& m);
void bind_noise(pybind11::module_& m);
void bind_image(pybind11::module_& m);
}  // namespace nimbus::python

PYBIND11_MODULE(_nimbus, m) {
  m.doc() = "nimbus's compiled core; use the package nimbus, not this module";
  openvdb::initialize();
  nimbus::python::register_errors(m);
  nimbus::python::register_exit_handler();
  nimbus::python::bind_volume(m);
  nimbus::python::bind_generate(m);
  nimbus::python::bind_render(m);
  nimbus::python::bind_noise(m);
  nimbus::python::bind_image(m);
  m.def("_set_reader_program", [](const std::filesystem::path& p) { nimbus::volume::set_vdb_reader_program(p); });
  m.attr("__version__") = NIMBUS_VERSION;
}
