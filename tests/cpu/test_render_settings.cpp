// The one table of render settings (render_settings.hpp) and the front ends that read it: the
// library's validators, the view state and `nimbus render` agree with it on every default and
// range (Python's side: python/tests/test_settings.py).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "nimbus/base/validate.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_slice_settings.hpp"
#include "nimbus/render/core/render_settings.hpp"
#include "nimbus/render/sky/view_state.hpp"
#include "support/run_nimbus.hpp"

namespace nimbus::render {
namespace {

using json = nlohmann::json;

// Just outside the range at each end (the bound itself where it is open), and just inside.
std::vector<double> outside(const RenderSetting& s) {
  const double step = s.integer ? 1.0 : std::max(1e-6, 1e-6 * (s.max - s.min));
  return {s.min_open ? s.min : s.min - step, s.max_open ? s.max : s.max + step};
}
std::vector<double> inside(const RenderSetting& s) {
  const double step = s.integer ? 1.0 : std::max(1e-6, 1e-6 * (s.max - s.min));
  return {s.min_open ? s.min + step : s.min, s.max_open ? s.max - step : s.max};
}

// The JSON value at "renderer.slices".
json& at_key(json& doc, std::string_view key) {
  const std::size_t dot = key.find('.');
  return doc[std::string(key.substr(0, dot))][std::string(key.substr(dot + 1))];
}

json number(const RenderSetting& s, double v) { return s.integer ? json(std::int64_t(v)) : json(v); }

std::string view_error(const json& doc) {
  try {
    view_state_from_json(doc, "state");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(RenderSettings, RangesAreWellFormedAndPrinted) {
  for (const RenderSetting& s : kRenderSettings) {
    SCOPED_TRACE(std::string(s.flag.empty() ? s.view_key : s.flag));
    EXPECT_LT(s.min, s.max);
    EXPECT_FALSE(s.help.empty());
    EXPECT_FALSE(s.flag.empty() && s.view_key.empty()) << "a setting no front end takes";
    EXPECT_EQ(s.view_default != s.still_default && s.default_text.empty(), !s.view_reason.empty() && s.default_text.empty())
        << "a viewer default that differs says why, and only then";
    for (double v : outside(s)) EXPECT_FALSE(in_range(s, v)) << v;
    for (double v : inside(s)) EXPECT_TRUE(in_range(s, v)) << v;
    EXPECT_FALSE(in_range(s, std::nan("")));
    if (s.integer) EXPECT_FALSE(in_range(s, s.min + 0.5));
    const std::string range = range_text(s);
    EXPECT_EQ(range.front(), s.min_open ? '(' : '[');
    EXPECT_NE(range.find(s.max_open ? ')' : ']'), std::string::npos);
    try {
      check_setting(s.id, outside(s)[1], "NAME");
      ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("NAME: must be in " + range + ", got ", 0), 0u) << e.what();
    }
  }
}

// The library's structs start at the table's still defaults, and their validators refuse what the
// table refuses.
TEST(RenderSettings, LibraryDefaultsAndValidatorsAreTheTables) {
  const CloudSliceSettings slices;
  EXPECT_EQ(slices.slices, setting(Setting::Slices).still_default);
  EXPECT_EQ(slices.light_res, setting(Setting::LightRes).still_default);
  EXPECT_EQ(slices.max_lights, setting(Setting::MaxLights).still_default);
  const MultipleScattering ms;
  EXPECT_EQ(ms.light_volume.resolution, setting(Setting::MsGrid).still_default);
  EXPECT_EQ(double(ms.light_volume.photons), setting(Setting::MsPhotons).still_default);
  EXPECT_EQ(ms.light_volume.lobe_orders, setting(Setting::MsLobes).still_default);
  EXPECT_EQ(ms.occlusion, setting(Setting::MsOcclusion).still_default);
  EXPECT_EQ(CloudOptics{}.extinction_per_m, setting(Setting::CloudExtinction).still_default);
  for (double v : outside(setting(Setting::Slices))) {
    CloudSliceSettings s;
    s.slices = int(v);
    EXPECT_THROW(validate(s), std::invalid_argument) << v;
  }
  for (double v : outside(setting(Setting::MsPhotons))) {
    LightVolumeSettings s;
    s.photons = std::int64_t(v);
    EXPECT_THROW(validate(s), std::invalid_argument) << v;
  }
  LightVolumeSettings most;
  most.photons = std::int64_t(setting(Setting::MsPhotons).max);
  EXPECT_NO_THROW(validate(most));
}

// A view state holds each setting with a view key at the table's view default, reads the ends of
// its range, and refuses just beyond them naming the key and the range.
TEST(RenderSettings, ViewStateDefaultsAndRangesAreTheTables) {
  const json good = view_state_to_json(default_view_state());
  for (const RenderSetting& s : kRenderSettings) {
    if (s.view_key.empty()) continue;
    SCOPED_TRACE(std::string(s.view_key));
    json doc = good;
    EXPECT_EQ(at_key(doc, s.view_key).get<double>(), s.view_default);
    for (double v : inside(s)) {
      at_key(doc, s.view_key) = number(s, v);
      EXPECT_EQ(view_error(doc), "(no error)") << v;
    }
    for (double v : outside(s)) {
      at_key(doc, s.view_key) = number(s, v);
      const std::string error = view_error(doc);
      EXPECT_NE(error.find(std::string(s.view_key) + ": must be in " + range_text(s)), std::string::npos) << error;
    }
  }
}

// `nimbus render`: every setting with a flag shows the table's help, range and default in --help,
// and a value just beyond its range is a usage error naming the flag and the range.
TEST(RenderSettings, CliFlagsShowAndCheckTheTable) {
  const test::RunResult help = test::run_nimbus("render --help");
  ASSERT_EQ(help.code, 0) << help.output;
  std::string text;  // --help folds long lines; compare with the spaces squeezed
  for (char c : help.output)
    if (!(std::isspace(static_cast<unsigned char>(c)) && !text.empty() && text.back() == ' '))
      text += std::isspace(static_cast<unsigned char>(c)) ? ' ' : c;
  for (const RenderSetting& s : kRenderSettings) {
    if (s.flag.empty()) continue;
    SCOPED_TRACE(std::string(s.flag));
    const std::string flag = flag_name(s);
    EXPECT_NE(text.find(flag), std::string::npos);
    EXPECT_NE(text.find(range_text(s)), std::string::npos);
    if (s.default_text.empty()) {
      const std::string number = s.integer ? std::to_string(std::int64_t(s.still_default)) : number_text(s.still_default);
      EXPECT_NE(text.find(flag + " " + (s.integer ? "INT" : "FLOAT") + "=" + number + " "), std::string::npos)
          << "--help does not show the default " << number;
    } else {
      EXPECT_NE(text.find("default: " + std::string(s.default_text)), std::string::npos);
    }
    // The octaves' scales apply only to the octaves; the light volume's flags need a sun (the default).
    const std::string mode = s.flag == "ms-occlusion" || s.flag == "ms-contribution" || s.flag == "ms-eccentricity"
                                 ? " --ms-method octaves --multiple 2"
                                 : "";
    for (double v : outside(s)) {
      char value[64];
      std::snprintf(value, sizeof value, s.integer ? "%.0f" : "%.9g", v);
      const test::RunResult r =
          test::run_nimbus("--check-only render --preset cumulus-humilis -o /tmp/never.exr" + mode + " " + flag + "=" + value);
      EXPECT_EQ(r.code, 2) << r.output;
      EXPECT_NE(r.output.find(flag + ": "), std::string::npos) << r.output;
      EXPECT_NE(r.output.find(" in " + range_text(s)), std::string::npos) << r.output;
    }
  }
}

}  // namespace
}  // namespace nimbus::render

namespace nimbus::render {
namespace {

// A number of the table as docs/cli.md writes it.
std::string doc_number(const RenderSetting& s, double v) {
  return s.integer ? std::to_string(std::int64_t(v)) : number_text(v);
}

// docs/cli.md's table of the render settings is the table's, row for row.
TEST(RenderSettings, DocsTableIsTheTables) {
  std::ifstream in(std::string(NIMBUS_SOURCE_DIR) + "/docs/cli.md");
  ASSERT_TRUE(in) << "docs/cli.md";
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const RenderSetting& s : kRenderSettings) {
    const std::string flag = s.flag.empty() ? "-" : "`" + flag_name(s) + "`";
    const std::string key = s.view_key.empty() ? "-" : "`" + std::string(s.view_key) + "`";
    const std::string still = s.default_text.empty() ? doc_number(s, s.still_default) : std::string(s.default_text);
    const std::string view = s.view_key.empty() ? "-"
                             : s.view_reason.empty() ? doc_number(s, s.view_default)
                                                     : doc_number(s, s.view_default) + ": " + std::string(s.view_reason);
    const std::string row = "| " + flag + " | " + key + " | " + range_text(s) + " | " + still + " | " + view + " | " +
                            std::string(s.help) + " |";
    EXPECT_NE(doc.find(row + "\n"), std::string::npos) << "docs/cli.md lacks the row\n" << row;
  }
}

}  // namespace
}  // namespace nimbus::render
