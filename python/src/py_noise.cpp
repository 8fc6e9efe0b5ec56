// nimbus.noise: `nimbus noise`'s field sampled on a grid, as a NumPy array indexed [x, y, z].
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <memory>
#include <span>

#include "calls.hpp"
#include "nimbus/app/usage_error.hpp"
#include "nimbus/base/memory.hpp"
#include "noise_request.hpp"

namespace nimbus::python {
namespace {

namespace py = pybind11;

// Samples at (i, j, k) * spacing, i < shape[0]...: x fastest, so NumPy sees [x, y, z] in Fortran order.
py::array sample(const cli::NoiseOptions& o, const std::array<int64_t, 3>& shape, double spacing) {
  for (int a = 0; a < 3; ++a)
    if (shape[a] < 1 || shape[a] > 4096)
      throw app::UsageError("shape: every size must be in [1, 4096], got " + std::to_string(shape[a]));
  if (!(std::isfinite(spacing) && spacing > 0.0)) throw app::UsageError("spacing: must be finite and > 0");
  const noise::NoiseParams p = cli::plan_noise(o);
  const uint64_t count = uint64_t(shape[0]) * uint64_t(shape[1]) * uint64_t(shape[2]);
  ensure_fits_in_memory(count, sizeof(float), "a noise grid of " + std::to_string(count) + " samples");
  std::unique_ptr<float[]> values;
  run_interruptible([&] {
    values.reset(new float[count]);  // not zero-filled first (half a second at 512^3): every sample is written
    const noise::NoiseField field(p);
    noise::GridSpec grid;
    grid.spacing = spacing;
    grid.res = {shape[0], shape[1], shape[2]};
    noise::evaluate_grid(field, grid, std::span<float>(values.get(), count), {});
  });
  float* data = values.release();
  py::capsule owner(data, [](void* v) { delete[] static_cast<float*>(v); });
  const py::ssize_t f = sizeof(float);
  return py::array_t<float>({py::ssize_t(shape[0]), py::ssize_t(shape[1]), py::ssize_t(shape[2])},
                            {f, f * shape[0], f * shape[0] * shape[1]}, data, owner);
}

}  // namespace

void bind_noise(py::module_& m) {
  m.def("_noise", [](const std::string& kind, const std::array<int64_t, 3>& shape, double frequency, const std::string& fractal,
                     int octaves, uint32_t seed, std::optional<double> time, double lacunarity, double gain, int32_t period,
                     bool projected, double spacing) {
    cli::NoiseOptions o;
    o.kind = kind;
    o.fractal = fractal;
    o.octaves = octaves;
    o.frequency = frequency;
    o.seed = seed;
    o.time = time;
    o.lacunarity = lacunarity;
    o.gain = gain;
    o.period = period;
    o.projected = projected;
    return sample(o, shape, spacing);
  });
}

}  // namespace nimbus::python
