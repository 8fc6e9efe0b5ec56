// The ranges of a sky's clock and sun, each defined once: sky files, view states, viewer scripts,
// the command line's flags and the Python module all check against these, and name them in
// their messages with range_text.
#pragma once
#include <string>

#include "nimbus/base/validate.hpp"

namespace nimbus::volume {

// A closed range [lo, hi]; NaN lies outside every range.
struct Range {
  double lo, hi;
  constexpr bool holds(double v) const { return v >= lo && v <= hi; }
};

// Seconds of sky time from time 0, either way (31 years): --time, every frame of a sequence,
// a view state's clocks, the Python module's time. Beyond it a cloud's drift leaves the noise's
// range, and a static file's picture is the same at any time.
inline constexpr Range kSkyTimeRangeS{-1e9, 1e9};
// The sun's elevation above the horizon, degrees: the physical sky's tables end 10 degrees below.
inline constexpr Range kSunElevationRangeDeg{-10.0, 90.0};
// The sun's compass bearing, degrees: 0 north, 90 east (360 is north again, read as 0).
inline constexpr Range kSunAzimuthRangeDeg{0.0, 360.0};

// "[-10, 90]", the numbers as messages print them.
inline std::string range_text(const Range& r) { return "[" + number_text(r.lo) + ", " + number_text(r.hi) + "]"; }

}  // namespace nimbus::volume
