// A small SVG line/scatter plot writer for the benchmarks (e.g. time per frame against image
// error): log or linear axes with ticks and labels, named series, axis titles, legend, title.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace nimbus::render {

struct PlotSeries {
  std::string name;       // shown in the legend
  std::vector<double> x;  // points, joined by lines in this order
  std::vector<double> y;  // same length as x
};

struct Plot {
  enum class Axis { Log, Linear };
  std::string title;
  std::string x_title;  // with units, e.g. "time per frame (ms)"
  std::string y_title;
  std::vector<PlotSeries> series;
  Axis x_axis = Axis::Log;
  Axis y_axis = Axis::Log;
  int width = 760;   // pixels, >= 320; widened when the legend's longest name needs more room
  int height = 480;  // pixels, >= 240
};

// The SVG document. Log axes span whole decades around the data (major ticks labelled at
// decades, minor ticks at 2..9), linear axes "nice" steps of 1, 2 or 5 x 10^k. Series get
// distinct colours (Okabe-Ito palette) and markers (circle, square, triangles, diamond, plus,
// cross). Throws std::invalid_argument naming the series and point for NaN/Inf, or <= 0 on a
// log axis; for x/y of different lengths, an empty series or no series; and for a size below
// the minimum (naming width or height).
std::string svg_plot(const Plot& plot);

// Writes svg_plot(plot) atomically; an unwritable path throws std::runtime_error naming it.
void write_svg_plot(const std::filesystem::path& path, const Plot& plot);

}  // namespace nimbus::render
