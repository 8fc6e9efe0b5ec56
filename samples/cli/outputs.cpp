// Output checks and all-or-nothing image files (outputs.hpp).
#include "outputs.hpp"

#include <map>

#include "nimbus/base/output_path.hpp"
#include "nimbus/base/staged_files.hpp"

namespace nimbus::cli {

void check_outputs(const std::vector<PathArg>& outputs, const std::vector<PathArg>& inputs) {
  std::map<std::string, const PathArg*> seen;  // file identity -> the argument that names it
  for (const PathArg& in : inputs)
    if (!in.path.empty()) seen.emplace(file_identity(in.path), &in);
  for (const PathArg& out : outputs) {
    if (out.path.empty()) continue;  // not asked for (an empty flag value is refused earlier)
    const auto [at, fresh] = seen.emplace(file_identity(out.path), &out);
    if (!fresh) {
      const PathArg& other = *at->second;
      throw UsageError(out.flag + " '" + out.path + "': is also " + other.flag +
                       (other.path == out.path ? "" : " '" + other.path + "'") + "; write the result to another file");
    }
  }
  for (const PathArg& out : outputs)
    if (!out.path.empty()) check_output_path(out.path, out.flag);
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
