// The benchmarks' SVG plot writer: well-formed XML (parsed by Python's minidom), every series
// in the legend with its own polyline, points placed at their tick labels on log and linear
// axes, and refusals.
#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "nimbus/render/image/svg_plot.hpp"
#include "support/run_nimbus.hpp"
#include "support/vdb_fixtures.hpp"

namespace {

using nimbus::render::Plot;
using nimbus::render::PlotSeries;
using nimbus::test::TempDir;

// What minidom sees: "T x y text" per <text> (x, y of its anchor), "P x,y x,y ..." per
// polyline, "M n" with the number of markers (circle, polygon, path) inside series groups.
const char* kDump = R"PY(
import sys, xml.dom.minidom
d = xml.dom.minidom.parse(sys.argv[1])
for t in d.getElementsByTagName('text'):
    s = ''.join(n.data for n in t.childNodes if n.nodeType == n.TEXT_NODE)
    print('T', t.getAttribute('x') or '-', t.getAttribute('y') or '-', s)
markers = 0
for g in d.getElementsByTagName('g'):
    if g.getAttribute('class') != 'series': continue
    for p in g.getElementsByTagName('polyline'): print('P', p.getAttribute('points').strip())
    markers += sum(len(g.getElementsByTagName(k)) for k in ('circle', 'polygon', 'path'))
print('M', markers)
)PY";

struct Parsed {
  std::map<std::string, std::pair<double, double>> texts;  // text -> anchor (x, y)
  std::vector<std::vector<std::pair<double, double>>> polylines;
  int markers = -1;
};

Parsed parse(const std::filesystem::path& svg, const TempDir& dir) {
  nimbus::test::write_bytes(dir / "dump.py", kDump);
  const auto r = nimbus::test::run_command("python3 " + (dir / "dump.py").string() + " " + svg.string());
  EXPECT_EQ(r.code, 0) << r.output;
  Parsed p;
  std::istringstream in(r.output);
  for (std::string line; std::getline(in, line);) {
    std::istringstream l(line);
    std::string kind;
    l >> kind;
    if (kind == "T") {
      std::string x, y, text;
      l >> x >> y;
      std::getline(l >> std::ws, text);
      p.texts[text] = {x == "-" ? -1 : std::stod(x), y == "-" ? -1 : std::stod(y)};
    } else if (kind == "P") {
      p.polylines.emplace_back();
      for (std::string xy; l >> xy;) {
        const auto comma = xy.find(',');
        p.polylines.back().emplace_back(std::stod(xy.substr(0, comma)), std::stod(xy.substr(comma + 1)));
      }
    } else if (kind == "M") {
      l >> p.markers;
    }
  }
  return p;
}

Plot bench_like_plot() {
  Plot plot;
  plot.title = "Light shafts: time against error <1280x720>";
  plot.x_title = "time per frame (ms)";
  plot.y_title = "relative RMSE";
  plot.series = {{"raymarch:N", {3, 10, 40, 400}, {0.3, 0.1, 0.02, 0.002}},
                 {"analytic & table:64", {2, 2.5}, {0.05, 0.04}},
                 {"shadowvolume:N", {5, 12, 60}, {0.08, 0.01, 0.003}}};
  return plot;
}

TEST(ImageSvg, WellFormedWithEverySeriesAndPointsAtTheirDecadeLabels) {
  TempDir dir;
  const Plot plot = bench_like_plot();
  nimbus::render::write_svg_plot(dir / "p.svg", plot);
  const Parsed p = parse(dir / "p.svg", dir);
  for (const PlotSeries& s : plot.series) EXPECT_TRUE(p.texts.count(s.name)) << s.name;
  for (const std::string& t : {plot.title, plot.x_title, plot.y_title}) EXPECT_TRUE(p.texts.count(t)) << t;
  ASSERT_EQ(p.polylines.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(p.polylines[i].size(), plot.series[i].x.size());
  EXPECT_EQ(p.markers, 4 + 2 + 3);
  EXPECT_EQ(nimbus::test::count_temp_files(dir.path), 0);

  // Log axes. x spans 2..400: decades 1..1000; y spans 0.002..0.3: 0.001..1.
  for (const char* label : {"1", "10", "100", "1000", "0.001", "0.01", "0.1"}) {
    EXPECT_TRUE(p.texts.count(label)) << label;
  }
  // raymarch point (10, 0.1): x under the x label "10", y beside the y label "0.1" (whose
  // baseline sits 4 px below the tick). Point (400, 0.002): 10^0.602 of the way.
  const auto pt = p.polylines[0][1];
  EXPECT_NEAR(pt.first, p.texts.at("10").first, 0.01);
  EXPECT_NEAR(pt.second, p.texts.at("0.1").second - 4, 0.01);
  const double decade_x = p.texts.at("100").first - p.texts.at("10").first;
  EXPECT_NEAR(p.polylines[0][3].first, p.texts.at("100").first + std::log10(4.0) * decade_x, 0.02);
  EXPECT_LT(p.polylines[0][3].second, p.texts.at("0.001").second);  // larger y is lower on the page
}

TEST(ImageSvg, LinearAxesUseNiceSteps) {
  TempDir dir;
  Plot plot;
  plot.title = "linear";
  plot.x_axis = Plot::Axis::Linear;
  plot.y_axis = Plot::Axis::Linear;
  plot.series = {{"a", {2.0, 7.3}, {-1.0, 0.9}}};
  nimbus::render::write_svg_plot(dir / "p.svg", plot);
  const Parsed p = parse(dir / "p.svg", dir);
  // x: 5.3 / 5 = 1.06 -> steps of 2 from 2 to 8; y: 1.9 / 5 = 0.38 -> steps of 0.5.
  for (const char* label : {"2", "4", "6", "8", "-1", "-0.5", "0", "0.5", "1"}) EXPECT_TRUE(p.texts.count(label)) << label;
  EXPECT_FALSE(p.texts.count("10"));
  EXPECT_NEAR(p.polylines[0][0].first, p.texts.at("2").first, 0.01);
  EXPECT_NEAR(p.polylines[0][0].second, p.texts.at("-1").second - 4, 0.01);
  EXPECT_NEAR(p.polylines[0][1].second, p.texts.at("1").second - 4 + 0.1 * (p.texts.at("0.5").second - p.texts.at("1").second) / 0.5, 0.01);
}

TEST(ImageSvg, BadDataIsRefusedByName) {
  auto expect_error = [](const Plot& plot, const std::string& mentions) {
    try {
      nimbus::render::svg_plot(plot);
      ADD_FAILURE() << "no exception; expected one mentioning " << mentions;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
    }
  };
  Plot plot = bench_like_plot();
  plot.series[1].y[1] = 0.0;
  expect_error(plot, "'analytic & table:64' point 1: y = 0 on a log axis");
  plot = bench_like_plot();
  plot.series[2].x[0] = std::nan("");
  expect_error(plot, "'shadowvolume:N' point 0: x = nan");
  plot = bench_like_plot();
  plot.series[0].y.pop_back();
  expect_error(plot, "'raymarch:N': 4 x values but 3 y values");
  plot.series.clear();
  expect_error(plot, "no series");
  plot = bench_like_plot();
  plot.width = 100;
  expect_error(plot, "width");
  TempDir dir;
  nimbus::test::write_bytes(dir / "file", "x");
  EXPECT_THROW(nimbus::render::write_svg_plot(dir / "file" / "p.svg", bench_like_plot()), std::runtime_error);
}

}  // namespace
