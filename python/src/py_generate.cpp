// nimbus.presets, preset, plan and generate: `nimbus generate`'s request and model, in memory.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <optional>

#include "calls.hpp"
#include "generate_plan.hpp"
#include "nimbus/app/usage_error.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/volume/coverage_map.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"
#include "py_volume.hpp"

namespace nimbus::python {
namespace {

namespace py = pybind11;

void check_time(double time_s) {
  if (!std::isfinite(time_s)) throw app::UsageError("time: must be a finite number of seconds");
}

// coverage_map: a PNG path (str), or (float32 bytes, width, height) from a NumPy array, or None.
void set_coverage_map(cli::GenerateRequest& r, const py::object& map) {
  if (map.is_none()) return;
  if (py::isinstance<py::str>(map)) {
    r.coverage_map = map.cast<std::string>();
    return;
  }
  const auto t = map.cast<py::tuple>();
  const std::string bytes = t[0].cast<std::string>();
  const int w = t[1].cast<int>(), h = t[2].cast<int>();
  std::vector<float> values(bytes.size() / sizeof(float));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(float));
  try {
    r.coverage_image = volume::coverage_from_values(std::move(values), w, h, "coverage_map (array)");
  } catch (const std::invalid_argument& e) {
    throw app::UsageError(e.what());
  }
}

// The plan as generate_plan.hpp's JSON text (the package makes it a dict).
std::string plan(const std::string& preset, std::optional<uint32_t> seed, std::optional<double> voxel_size,
                 std::optional<int> res, double time_s, std::vector<std::string> sets, double size,
                 const std::string& params_file, const py::object& coverage_map) {
  check_time(time_s);
  cli::GenerateRequest request{preset, seed, voxel_size, res, std::move(sets), size, params_file, "", nullptr};
  set_coverage_map(request, coverage_map);
  const cli::GeneratePlan p = cli::plan_generate(request);
  return cli::plan_json(p, time_s).dump();  // refuses as generate does, before any voxel
}

Volume generate(const std::string& preset, std::optional<uint32_t> seed, std::optional<double> voxel_size,
                std::optional<int> res, double time_s, std::vector<std::string> sets, double size,
                const std::string& params_file, const py::object& coverage_map, const py::object& progress) {
  check_time(time_s);
  cli::GenerateRequest request{preset, seed, voxel_size, res, std::move(sets), size, params_file, "", nullptr};
  set_coverage_map(request, coverage_map);
  Volume v;
  std::atomic<double> fraction{0.0};
  run_interruptible(
      [&] {
        const cli::GeneratePlan p = cli::plan_generate(request);
        cli::check_generate_time(p, time_s);
        volume::GenerateOptions opt;
        opt.voxel_size = p.voxel_size_m;
        opt.time = time_s;
        opt.progress = [&](double f) { fraction.store(f); };
        volume::GenerateStats stats;
        const openvdb::FloatGrid::Ptr density = volume::generate_density(p.params, opt, &stats);
        if (stats.active_voxels == 0)  // as nimbus generate says it
          throw std::runtime_error("the cloud has no voxel of density >= 1e-6 at voxel size " + number_text(opt.voxel_size) +
                                   " m (shapes smaller than a voxel, or coverage, weight or density leave nothing)");
        volume::ExportInfo info;
        info.preset = preset;
        info.seed = p.params.seed;
        info.time = time_s;
        info.up_axis = 'z';
        cli::add_period_metadata(p.params, info);  // as nimbus generate writes it
        v = volume_from_grid(*density, 'z', volume::export_metadata(info));
        if (auto temperature = volume::generate_temperature(p.params, *density)) v.extra.push_back(temperature);
      },
      progress, &fraction);
  return v;
}

}  // namespace

void bind_generate(py::module_& m) {
  m.def("_presets", [] {
    py::list out;
    for (const volume::PresetInfo& p : volume::list_presets()) out.append(py::make_tuple(p.name, p.genus, p.description));
    return out;
  });
  m.def("_preset_json", [](const std::string& name) {
    try {
      return volume::load_preset(name).dump();
    } catch (const std::invalid_argument& e) {
      throw app::UsageError(e.what());
    }
  });
  m.def("_plan", &plan);
  m.def("_generate", &generate);
}

}  // namespace nimbus::python
