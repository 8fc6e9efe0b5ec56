// Output checks and all-or-nothing image files (outputs.hpp).
#include "outputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "nimbus/base/input_limits.hpp"
#include "nimbus/base/output_path.hpp"
#include "nimbus/base/validate.hpp"
#include "nimbus/base/staged_files.hpp"

namespace nimbus::cli {

void check_outputs(const std::vector<PathArg>& outputs, const RunInputs& inputs) {
  std::map<std::string, const PathArg*> seen;  // file identity -> the argument that names it
  for (const PathArg& in : inputs.paths()) seen.emplace(file_identity(in.path), &in);
  for (const PathArg& out : outputs) {
    if (out.path.empty()) continue;  // not asked for (an empty flag value is refused earlier)
    const auto [at, fresh] = seen.emplace(file_identity(out.path), &out);
    if (!fresh) {
      const PathArg& other = *at->second;
      throw UsageError(out.flag + " '" + echo(out.path, 200) + "': is also " + other.flag +
                       (other.path == out.path ? "" : " '" + echo(other.path, 200) + "'") + "; write the result to another file");
    }
  }
  for (const PathArg& out : outputs)
    if (!out.path.empty()) check_output_path(out.path, out.flag);
}

void warn_half_float_clipping(const render::Image& image, const std::string& output, const std::string& sources) {
  constexpr auto kHalfMax = static_cast<float>(kExrHalfMax);
  std::size_t clipped = 0;
  float brightest = 0.0f;
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    if (i % 4 == 3) continue;  // alpha is coverage, in [0, 1]
    const float v = std::abs(image.rgba[i]);
    if (v > kHalfMax) ++clipped;
    brightest = std::max(brightest, v);
  }
  if (clipped == 0) return;
  std::fprintf(stderr, "nimbus: warning: %s: %zu colour value(s) above 65504 (the EXR's half floats' largest; the brightest "
                       "%s) are clipped there; lower %s\n",
               echo(output, 200).c_str(), clipped, number_text(brightest).c_str(), sources.c_str());
}

void write_image_files(const std::string& exr, const std::string& preview, const render::Image& image,
                       const render::PreviewOptions& preview_options) {
  StagedFiles files;
  files.write(exr, [&](const std::filesystem::path& tmp) { render::write_exr(tmp, image); });
  if (!preview.empty())
    files.write(preview, [&](const std::filesystem::path& tmp) { render::write_png_preview(tmp, image, preview_options); });
  files.commit();
}

}  // namespace nimbus::cli
