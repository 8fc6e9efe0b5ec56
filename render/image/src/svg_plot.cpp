// SVG plot writer: axis ranges and ticks, series as polylines with markers, legend.
#include "nimbus/render/image/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "nimbus/base/atomic_file.hpp"

namespace nimbus::render {
namespace {

constexpr std::array<const char*, 7> kColours{"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                              "#E69F00", "#56B4E9", "#000000"};
constexpr int kMarkers = 7;
constexpr double kLeft = 80, kRight = 210, kTop = 48, kBottom = 62;  // margins, pixels

std::string escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

struct Tick {
  double value;
  bool major;
  std::string text;  // empty: no label
};

// Maps data values to [0, 1] along the axis and lists its ticks.
struct AxisScale {
  bool log = true;
  double lo = 0, hi = 1;  // in log10 units for a log axis
  std::vector<Tick> ticks;

  double unit(double v) const { return ((log ? std::log10(v) : v) - lo) / (hi - lo); }
};

AxisScale make_axis(double vmin, double vmax, Plot::Axis kind) {
  AxisScale a;
  a.log = kind == Plot::Axis::Log;
  if (a.log) {
    a.lo = std::floor(std::log10(vmin));
    a.hi = std::max(std::ceil(std::log10(vmax)), a.lo + 1);
    const int decades = static_cast<int>(a.hi - a.lo);
    const int stride = (decades + 7) / 8;  // at most about 8 labels
    for (int k = static_cast<int>(a.lo); k <= static_cast<int>(a.hi); ++k) {
      const double v = std::pow(10.0, k);
      const bool labelled = (k - static_cast<int>(a.lo)) % stride == 0;
      a.ticks.push_back({v, true, labelled ? (k >= -4 && k <= 5 ? label(v) : "1e" + std::to_string(k)) : ""});
      if (k == static_cast<int>(a.hi)) break;
      for (int m = 2; m <= 9; ++m) a.ticks.push_back({m * v, false, ""});
    }
    return a;
  }
  if (vmax - vmin <= 0) {
    const double pad = vmin != 0 ? std::abs(vmin) * 0.1 : 1.0;
    vmin -= pad;
    vmax += pad;
  }
  const double raw = (vmax - vmin) / 5.0;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw <= p ? p : raw <= 2 * p ? 2 * p : raw <= 5 * p ? 5 * p : 10 * p;
  a.lo = std::floor(vmin / step) * step;
  a.hi = std::ceil(vmax / step) * step;
  for (double v = a.lo; v <= a.hi + 0.5 * step; v += step) {
    const double t = std::abs(v) < 1e-9 * step ? 0.0 : v;
    a.ticks.push_back({t, true, label(t)});
  }
  return a;
}

void check(const Plot& plot) {
  if (plot.width < 320) throw std::invalid_argument("plot width must be >= 320, got " + std::to_string(plot.width));
  if (plot.height < 240) throw std::invalid_argument("plot height must be >= 240, got " + std::to_string(plot.height));
  if (plot.series.empty()) throw std::invalid_argument("plot '" + plot.title + "' has no series");
  for (const PlotSeries& s : plot.series) {
    if (s.x.size() != s.y.size()) {
      throw std::invalid_argument("plot series '" + s.name + "': " + std::to_string(s.x.size()) + " x values but " +
                                  std::to_string(s.y.size()) + " y values");
    }
    if (s.x.empty()) throw std::invalid_argument("plot series '" + s.name + "' has no points");
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      for (const auto& [v, axis, kind] : {std::tuple{s.x[i], "x", plot.x_axis}, std::tuple{s.y[i], "y", plot.y_axis}}) {
        if (!std::isfinite(v) || (kind == Plot::Axis::Log && v <= 0)) {
          throw std::invalid_argument("plot series '" + s.name + "' point " + std::to_string(i) + ": " + axis +
                                      " = " + label(v) + (std::isfinite(v) ? " on a log axis" : ""));
        }
      }
    }
  }
}

// A marker of kind k centred at (x, y), radius about 4 pixels.
std::string marker(int k, double x, double y, const char* colour) {
  const std::string fill = std::string(" fill=\"") + colour + "\" stroke=\"" + colour + "\"";
  const double r = 4;
  auto poly = [&](std::initializer_list<std::pair<double, double>> pts) {
    std::string s = "<polygon points=\"";
    for (const auto& [dx, dy] : pts) s += num(x + dx) + "," + num(y + dy) + " ";
    return s + "\"" + fill + "/>";
  };
  switch (k % kMarkers) {
    case 0: return "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"" + num(r) + "\"" + fill + "/>";
    case 1: return poly({{-r, -r}, {r, -r}, {r, r}, {-r, r}});
    case 2: return poly({{0, -1.2 * r}, {1.1 * r, 0.8 * r}, {-1.1 * r, 0.8 * r}});
    case 3: return poly({{0, -1.3 * r}, {1.3 * r, 0}, {0, 1.3 * r}, {-1.3 * r, 0}});
    case 4: return poly({{0, 1.2 * r}, {1.1 * r, -0.8 * r}, {-1.1 * r, -0.8 * r}});
    case 5:
      return "<path d=\"M" + num(x - r) + " " + num(y) + "H" + num(x + r) + "M" + num(x) + " " + num(y - r) + "V" +
             num(y + r) + "\" stroke=\"" + colour + "\" stroke-width=\"2\" fill=\"none\"/>";
    default:
      return "<path d=\"M" + num(x - r) + " " + num(y - r) + "L" + num(x + r) + " " + num(y + r) + "M" + num(x - r) +
             " " + num(y + r) + "L" + num(x + r) + " " + num(y - r) + "\" stroke=\"" + colour +
             "\" stroke-width=\"2\" fill=\"none\"/>";
  }
}

}  // namespace

std::string svg_plot(const Plot& plot) {
  check(plot);
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
  for (const PlotSeries& s : plot.series) {
    xmin = std::min(xmin, *std::min_element(s.x.begin(), s.x.end()));
    xmax = std::max(xmax, *std::max_element(s.x.begin(), s.x.end()));
    ymin = std::min(ymin, *std::min_element(s.y.begin(), s.y.end()));
    ymax = std::max(ymax, *std::max_element(s.y.begin(), s.y.end()));
  }
  const AxisScale ax = make_axis(xmin, xmax, plot.x_axis);
  const AxisScale ay = make_axis(ymin, ymax, plot.y_axis);
  // The legend's column is as wide as its longest name (about 7 px a character at 12 px
  // sans-serif), so no name is cut at the right edge; the picture widens rather than the plot
  // area shrinking.
  std::size_t longest = 0;
  for (const PlotSeries& s : plot.series) longest = std::max(longest, s.name.size());
  const double right = std::max(kRight, 16.0 + 36.0 + 7.0 * static_cast<double>(longest) + 12.0);
  const double w = plot.width + (right - kRight), h = plot.height;
  const double x0 = kLeft, x1 = w - right, y0 = h - kBottom, y1 = kTop;  // plot area
  auto px = [&](double v) { return x0 + ax.unit(v) * (x1 - x0); };
  auto py = [&](double v) { return y0 + ay.unit(v) * (y1 - y0); };

  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(w) << "\" height=\"" << plot.height
    << "\" viewBox=\"0 0 " << num(w) << " " << plot.height
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << num((x0 + x1) / 2) << "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">"
    << escape(plot.title) << "</text>\n";
  // Grid, ticks and tick labels.
  o << "<g class=\"axes\" stroke-width=\"1\">\n";
  for (const Tick& t : ax.ticks) {
    const double x = px(t.value);
    if (t.major) o << "<line x1=\"" << num(x) << "\" y1=\"" << num(y0) << "\" x2=\"" << num(x) << "\" y2=\"" << num(y1) << "\" stroke=\"#e4e4e4\"/>\n";
    o << "<line x1=\"" << num(x) << "\" y1=\"" << num(y0) << "\" x2=\"" << num(x) << "\" y2=\"" << num(y0 + (t.major ? 7 : 4)) << "\" stroke=\"black\"/>\n";
    if (!t.text.empty()) o << "<text x=\"" << num(x) << "\" y=\"" << num(y0 + 21) << "\" text-anchor=\"middle\">" << escape(t.text) << "</text>\n";
  }
  for (const Tick& t : ay.ticks) {
    const double y = py(t.value);
    if (t.major) o << "<line x1=\"" << num(x0) << "\" y1=\"" << num(y) << "\" x2=\"" << num(x1) << "\" y2=\"" << num(y) << "\" stroke=\"#e4e4e4\"/>\n";
    o << "<line x1=\"" << num(x0 - (t.major ? 7 : 4)) << "\" y1=\"" << num(y) << "\" x2=\"" << num(x0) << "\" y2=\"" << num(y) << "\" stroke=\"black\"/>\n";
    if (!t.text.empty()) o << "<text x=\"" << num(x0 - 10) << "\" y=\"" << num(y + 4) << "\" text-anchor=\"end\">" << escape(t.text) << "</text>\n";
  }
  o << "<rect x=\"" << num(x0) << "\" y=\"" << num(y1) << "\" width=\"" << num(x1 - x0) << "\" height=\"" << num(y0 - y1)
    << "\" fill=\"none\" stroke=\"black\"/>\n</g>\n";
  // Axis titles.
  o << "<text x=\"" << num((x0 + x1) / 2) << "\" y=\"" << num(h - 18) << "\" text-anchor=\"middle\">"
    << escape(plot.x_title) << "</text>\n"
    << "<text transform=\"translate(20 " << num((y0 + y1) / 2) << ") rotate(-90)\" text-anchor=\"middle\">"
    << escape(plot.y_title) << "</text>\n";
  // Series, then the legend.
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& s = plot.series[i];
    const char* colour = kColours[i % kColours.size()];
    const int mk = static_cast<int>(i + i / kColours.size());
    o << "<g class=\"series\"><title>" << escape(s.name) << "</title>\n<polyline fill=\"none\" stroke=\"" << colour
      << "\" stroke-width=\"1.5\" points=\"";
    for (std::size_t j = 0; j < s.x.size(); ++j) o << num(px(s.x[j])) << "," << num(py(s.y[j])) << " ";
    o << "\"/>\n";
    for (std::size_t j = 0; j < s.x.size(); ++j) o << marker(mk, px(s.x[j]), py(s.y[j]), colour) << "\n";
    o << "</g>\n";
  }
  o << "<g class=\"legend\">\n";
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const char* colour = kColours[i % kColours.size()];
    const int mk = static_cast<int>(i + i / kColours.size());
    const double y = y1 + 10 + 20.0 * static_cast<double>(i);
    const double lx = x1 + 16;
    o << "<line x1=\"" << num(lx) << "\" y1=\"" << num(y) << "\" x2=\"" << num(lx + 28) << "\" y2=\"" << num(y)
      << "\" stroke=\"" << colour << "\" stroke-width=\"1.5\"/>" << marker(mk, lx + 14, y, colour)
      << "<text x=\"" << num(lx + 36) << "\" y=\"" << num(y + 4) << "\">" << escape(plot.series[i].name) << "</text>\n";
  }
  o << "</g>\n</svg>\n";
  return o.str();
}

void write_svg_plot(const std::filesystem::path& path, const Plot& plot) {
  const std::string svg = svg_plot(plot);
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << svg;
    out.close();
    if (!out) throw std::runtime_error("cannot write plot " + path.string());
  });
}

}  // namespace nimbus::render
