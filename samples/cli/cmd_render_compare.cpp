// `nimbus compare TEST.exr REFERENCE.exr`: image error over the reference's lit pixels
// (relative RMSE, maximum relative error, mean bias), as `nimbus bench shafts` reports it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "cli.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "nimbus/render/image/image_metrics.hpp"

namespace nimbus::cli {

void add_compare_command(CLI::App& app, Action& action) {
  struct Args {
    std::string test, reference;
    int worst = 0;
  };
  auto files = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("compare", "Error of an EXR image against a reference EXR over its lit pixels");
  cmd->add_option("test", files->test, "Image to measure (.exr)")->required();
  cmd->add_option("reference", files->reference, "Reference image (.exr)")->required();
  cmd->add_option("--worst", files->worst, "Also list the N lit pixels with the largest relative error");
  cmd->callback([&action, files] {
    action = [files] {
      refuse_special_file(files->test, "TEST");
      refuse_special_file(files->reference, "REFERENCE");
      const render::Image test = render::read_exr(files->test);
      const render::Image ref = render::read_exr(files->reference);
      if (test.width != ref.width || test.height != ref.height)
        throw UsageError("compare: " + files->test + " is " + std::to_string(test.width) + "x" +
                         std::to_string(test.height) + " but " + files->reference + " is " + std::to_string(ref.width) +
                         "x" + std::to_string(ref.height));
      const render::ImageError e = render::compare_images(test, ref);
      std::printf("rel_rmse %.6g median_rel %.6g max_rel %.6g mean_bias %+.6g lit_pixels %zu\n", e.rel_rmse,
                  e.median_rel, e.max_rel, e.mean_bias, e.pixels);
      if (files->worst > 0) {
        const std::vector<std::uint8_t> lit = render::lit_pixels(ref);
        std::vector<std::pair<double, std::size_t>> errs;
        for (std::size_t i = 0; i < lit.size(); ++i) {
          if (!lit[i]) continue;
          double num = 0, den = 0;
          for (int c = 0; c < 3; ++c) {
            num = std::max(num, std::abs(double(test.rgba[i * 4 + c]) - ref.rgba[i * 4 + c]));
            den = std::max(den, std::abs(double(ref.rgba[i * 4 + c])));
          }
          errs.emplace_back(num / std::max(den, 1e-30), i);
        }
        const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(files->worst), errs.size());
        std::partial_sort(errs.begin(), errs.begin() + static_cast<std::ptrdiff_t>(n), errs.end(), std::greater<>());
        for (std::size_t k = 0; k < n; ++k) {
          const std::size_t i = errs[k].second;
          std::printf("pixel %zu,%zu rel %.4g test %.6g reference %.6g\n", i % static_cast<std::size_t>(ref.width),
                      i / static_cast<std::size_t>(ref.width), errs[k].first, test.rgba[i * 4], ref.rgba[i * 4]);
        }
      }
      return 0;
    };
  });
}

}  // namespace nimbus::cli
