// The noise module: everything a caller needs.
#pragma once
#include "nimbus/noise/batch.hpp"
#include "nimbus/noise/field.hpp"
#include "nimbus/noise/footprint.hpp"
#include "nimbus/noise/gradient_bound.hpp"
#include "nimbus/base/memory.hpp"
#include "nimbus/noise/params.hpp"
#include "nimbus/noise/wavelet_tile.hpp"
