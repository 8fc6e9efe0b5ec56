// Entry points of one instruction-set level (defined by batch_level.inl per level).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "nimbus/noise/batch.hpp"

namespace nimbus::noise::level {

using RowsFn = void (*)(const detail::FieldData&, const GridSpec&, int64_t row_begin,
                        int64_t row_end, float* out);
using PointsFn = void (*)(const detail::FieldData&, const std::array<double, 3>* points,
                          size_t count, float* out);

// Several fields on one lattice (shares_lattice) at the same points: out[f] gets field f's
// values, split once for all of them.
using SharedPointsFn = void (*)(const detail::FieldData* const* fields, size_t field_count,
                                const std::array<double, 3>* points, size_t count, float* const* out);

struct Kernels {
  RowsFn rows;
  PointsFn points;
  SharedPointsFn shared_points;
};

Kernels scalar();
Kernels sse41();
Kernels avx2();
Kernels avx512();

}  // namespace nimbus::noise::level
