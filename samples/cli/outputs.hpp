// A command's output files, checked before any work and written all or nothing.
#pragma once
#include <string>
#include <vector>

#include "cli.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/image/image_io.hpp"
#include "run_inputs.hpp"

namespace nimbus::cli {

// Before any work: UsageError when an output is also an input (any file the run reads, gathered
// by RunInputs from what it parsed) or another output (compared as files: links and other
// spellings of one file are the same); std::runtime_error naming the flag and path when an output
// could not be written (check_output_path: not a regular file, no writable directory). Outputs
// with an empty path (a flag not given) are skipped.
void check_outputs(const std::vector<PathArg>& outputs, const RunInputs& inputs = {});

// The render's EXR and, when `preview` is not empty, its PNG preview: both or neither. Each is
// written to a temporary, and only when both are complete are they renamed into place.
void write_image_files(const std::string& exr, const std::string& preview, const render::Image& image,
                       const render::PreviewOptions& preview_options);

// The largest value the EXR's half floats hold; brighter radiances are clipped to it.
inline constexpr double kExrHalfMax = 65504.0;

// The EXR stores half floats, whose largest value is 65504: brighter radiances are clipped. Prints
// one warning line on stderr naming `output`, how many values were clipped, the brightest, and
// `sources` (the flags or keys that set the light, e.g. "--lamp-intensity"), when any are.
void warn_half_float_clipping(const render::Image& image, const std::string& output, const std::string& sources);

}  // namespace nimbus::cli
