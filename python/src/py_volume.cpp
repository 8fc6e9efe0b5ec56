// Volume: construction from grids and arrays, reading, writing, and its Python face (py_volume.hpp).
#include "py_volume.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <limits>

#include "calls.hpp"
#include "outputs.hpp"
#include "nimbus/volume/up_axis.hpp"
#include "nimbus/volume/voxel_size.hpp"

namespace nimbus::python {
namespace {

namespace py = pybind11;

// The keys write_volume_vdb sets itself from ExportInfo (vdb_io.hpp), and the seal it adds.
bool standard_key(const std::string& key) {
  for (const char* k : {"creator", "preset", "seed", "time", "frame", "fps", "up_axis", "units", "nimbus_version",
                        "nimbus_checksum"})
    if (key == k) return true;
  return false;
}

const volume::MetaValue* find_meta(const volume::Metadata& m, const std::string& key) {
  for (const auto& [k, v] : m)
    if (k == key) return &v;
  return nullptr;
}

double meta_number(const volume::Metadata& m, const std::string& key, double fallback) {
  const volume::MetaValue* v = find_meta(m, key);
  if (!v) return fallback;
  if (const double* d = std::get_if<double>(v)) return *d;
  if (const int64_t* i = std::get_if<int64_t>(v)) return double(*i);
  return fallback;
}

// What the file said, as ExportInfo, so that writing it again keeps it.
volume::ExportInfo export_info(const Volume& v) {
  volume::ExportInfo info;
  if (const volume::MetaValue* p = find_meta(v.metadata, "preset"))
    if (const std::string* s = std::get_if<std::string>(p)) info.preset = *s;
  info.seed = int64_t(meta_number(v.metadata, "seed", 0.0));
  info.time = meta_number(v.metadata, "time", 0.0);
  info.frame = int64_t(meta_number(v.metadata, "frame", 0.0));
  if (find_meta(v.metadata, "fps")) info.fps = meta_number(v.metadata, "fps", 24.0);
  if (const volume::MetaValue* u = find_meta(v.metadata, "units"))
    if (const std::string* s = std::get_if<std::string>(u); s && !s->empty()) info.units = *s;
  info.up_axis = v.up_axis;
  for (const auto& [k, value] : v.metadata)
    if (!standard_key(k)) info.extra.emplace_back(k, value);
  return info;
}

}  // namespace

void check_density(const volume::DenseBox& box, const std::string& grid, bool negatives_allowed) {
  for (std::size_t n = 0; n < box.values.size(); ++n) {
    const float d = box.values[n];
    if (std::isfinite(d) && (d >= 0.0f || negatives_allowed)) continue;
    const int64_t sx = box.size[0], sy = box.size[1];
    const int64_t i = int64_t(n) % sx, j = (int64_t(n) / sx) % sy, k = int64_t(n) / (sx * sy);
    const std::string what = std::isnan(d) ? "NaN" : std::isinf(d) ? "infinite" : "negative";
    const std::string where = "density[" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) + "]";
    if (negatives_allowed) throw std::invalid_argument(where + " is " + what + ": a value must be finite");
    throw std::invalid_argument(where + " is " + what + ": a density is finite and >= 0" +
                                (grid == "density" ? "" : " (this volume's grid is '" + grid +
                                 "', read from a file: clip it first, np.maximum(v.density, 0, out=v.density))"));
  }
}

namespace {

py::object meta_to_python(const volume::MetaValue& v) {
  if (const std::string* s = std::get_if<std::string>(&v)) return py::str(*s);
  if (const double* d = std::get_if<double>(&v)) return py::float_(*d);
  return py::int_(std::get<int64_t>(v));
}

py::tuple voxel_size_of(const openvdb::math::Transform& t) {
  const openvdb::Vec3d s = t.voxelSize();
  return py::make_tuple(s.x(), s.y(), s.z());
}

// Volume.from_array: a user's densities (any float array, copied once into x-fastest order).
Volume volume_from_array(const py::array& input, double voxel_size, const std::array<int64_t, 3>& origin,
                         const std::string& up_axis) {
  volume::check_voxel_size(voxel_size, "voxel_size");
  if (up_axis != "z" && up_axis != "y") throw std::invalid_argument("up_axis: '" + up_axis + "' must be 'z' or 'y'");
  if (input.ndim() != 3)
    throw std::invalid_argument("array: must have 3 dimensions [x, y, z], got " + std::to_string(input.ndim()));
  constexpr int64_t kIndexLimit = int64_t(1) << 30;
  for (int a = 0; a < 3; ++a)
    if (origin[a] < -kIndexLimit || origin[a] + int64_t(input.shape(a)) > kIndexLimit)
      throw std::invalid_argument("origin: the voxels must lie within index +-2^30 on every axis");
  // Fortran order is x fastest: the layout the box keeps.
  const auto f = py::array_t<float, py::array::f_style | py::array::forcecast>::ensure(input);
  if (!f) throw std::invalid_argument("array: cannot be read as float32 numbers");
  Volume v;
  for (int a = 0; a < 3; ++a) {
    v.box.origin[a] = int32_t(origin[a]);
    v.box.size[a] = int64_t(f.shape(a));
  }
  v.box.values.assign(f.data(), f.data() + f.size());
  if (f.size() == 0) v.box.size = {0, 0, 0};
  check_density(v.box);
  v.transform = openvdb::math::Transform::createLinearTransform(voxel_size);
  v.up_axis = up_axis[0];
  volume::ExportInfo info;
  info.up_axis = v.up_axis;
  v.metadata = volume::export_metadata(info);
  return v;
}

// The volume, its values as the file holds them: a density's, or any other grid's (a noise
// field's negative half stays negative).
Volume read_volume(const std::filesystem::path& path, const std::optional<std::string>& grid) {
  Volume v;
  run_interruptible([&] {
    volume::VdbReadOptions options;
    options.grid = grid;
    volume::VolumeFile file = volume::read_volume_vdb(path, options);
    char up = 'y';  // what nimbus render assumes of a file that does not say (cloud_source.hpp)
    if (const volume::MetaValue* u = find_meta(file.metadata, "up_axis"))
      if (const std::string* s = std::get_if<std::string>(u); s && (*s == "z" || *s == "y")) up = (*s)[0];
    v = volume_from_grid(*file.grid, up, file.metadata);
  });
  return v;
}

}  // namespace

Volume volume_from_grid(const openvdb::FloatGrid& grid, char up_axis, volume::Metadata metadata) {
  Volume v;
  v.box = volume::dense_active_box(grid);
  v.transform = grid.transform().copy();
  v.up_axis = up_axis;
  if (!grid.getName().empty()) v.grid = grid.getName();
  volume::Metadata kept;
  for (auto& [k, value] : metadata)
    if (k != "nimbus_checksum") kept.emplace_back(k, value);
  v.metadata = std::move(kept);
  return v;
}

void write_volume(const Volume& v, const std::filesystem::path& path, bool half_float) {
  check_density(v.box, v.grid);
  cli::check_outputs({{"path", path.string()}});  // as the program checks -o: a writable file in a directory that exists
  openvdb::FloatGrid::Ptr density = volume::grid_from_dense_box(v.box, *v.transform);
  std::vector<openvdb::FloatGrid::ConstPtr> grids{density};
  for (const auto& g : v.extra) grids.push_back(g);
  if (v.up_axis == 'y')  // stored y-up: back to nimbus's z-up, which the writer turns y-up again, exactly
    for (auto& g : grids) g = volume::rotate_y_up_to_z_up(*g);
  volume::ExportOptions eo;
  eo.half_float = half_float;
  volume::write_volume_vdb(path, grids, export_info(v), eo);
}

// The Volume behind a Python object. Volume.__new__ makes an object whose Volume was never
// constructed (pybind11 leaves its value null): TypeError, never a null dereference.
Volume& volume_of(const py::handle self) {
  if (!py::isinstance<Volume>(self)) throw py::type_error("expected a nimbus.Volume");
  auto* inst = reinterpret_cast<py::detail::instance*>(self.ptr());
  const py::detail::value_and_holder vh = inst->get_value_and_holder(py::detail::get_type_info(typeid(Volume)));
  Volume* v = vh ? vh.value_ptr<Volume>() : nullptr;
  if (!v || !vh.holder_constructed() || !v->transform)
    throw py::type_error("Volume: this one was never made (Volume.__new__); make one with nimbus.generate, "
                         "nimbus.read or nimbus.Volume.from_array");
  return *v;
}

void bind_volume(py::module_& m) {
  py::class_<Volume>(m, "Volume")
      .def(py::init([]() -> Volume {
        throw py::type_error("Volume: has no constructor of its own; make one with nimbus.generate, nimbus.read "
                             "or nimbus.Volume.from_array");
      }))
      .def_property_readonly(
          "density",
          [](py::object self) {
            Volume& v = volume_of(self);
            const std::vector<py::ssize_t> shape{py::ssize_t(v.box.size[0]), py::ssize_t(v.box.size[1]),
                                                 py::ssize_t(v.box.size[2])};
            const py::ssize_t f = sizeof(float);
            const std::vector<py::ssize_t> strides{f, f * shape[0], f * shape[0] * shape[1]};
            return py::array_t<float>(shape, strides, v.box.values.data(), self);  // a view: no copy
          })
      .def_property_readonly("origin",
                             [](py::object self) {
                               const Volume& v = volume_of(self);
                               return py::make_tuple(v.box.origin[0], v.box.origin[1], v.box.origin[2]);
                             })
      .def_property_readonly("voxel_size",
                             [](py::object self) -> py::object {
                               const Volume& v = volume_of(self);
                               const openvdb::Vec3d s = v.transform->voxelSize();
                               if (std::abs(s.x() - s.y()) <= 1e-9 * s.x() && std::abs(s.x() - s.z()) <= 1e-9 * s.x())
                                 return py::float_(s.x());
                               return voxel_size_of(*v.transform);  // not cubic: (x, y, z)
                             })
      .def_property_readonly("index_to_world",
                             [](py::object self) -> py::object {
                               const Volume& v = volume_of(self);
                               if (!v.transform->isLinear()) return py::none();  // a frustum: no matrix
                               const openvdb::math::Mat4d mat = v.transform->baseMap()->getAffineMap()->getMat4();
                               py::list rows;  // OpenVDB's matrices act on row vectors: transpose to columns
                               for (int r = 0; r < 4; ++r) rows.append(py::make_tuple(mat(0, r), mat(1, r), mat(2, r), mat(3, r)));
                               return rows;
                             })
      .def_property_readonly("linear", [](py::object self) { return volume_of(self).transform->isLinear(); })
      .def_property_readonly("grid", [](py::object self) { return volume_of(self).grid; })
      .def_property_readonly("up_axis", [](py::object self) { return std::string(1, volume_of(self).up_axis); })
      .def_property_readonly("metadata",
                             [](py::object self) {
                               py::dict d;
                               for (const auto& [k, value] : volume_of(self).metadata) d[py::str(k)] = meta_to_python(value);
                               return d;
                             })
      .def_property_readonly("extra_grids",
                             [](py::object self) {
                               py::list names;
                               for (const auto& g : volume_of(self).extra) names.append(g->getName());
                               return names;
                             })
      .def("_write", [](py::object self, const std::filesystem::path& path, bool half_float) {
        const Volume& v = volume_of(self);
        run_interruptible([&] { write_volume(v, path, half_float); });
      });
  m.def("_from_array", &volume_from_array);
  m.def("_voxel_size_range", [] { return py::make_tuple(volume::kMinVoxelSize_m, volume::kMaxVoxelSize_m); });
  m.def("_read", &read_volume);
}

}  // namespace nimbus::python
