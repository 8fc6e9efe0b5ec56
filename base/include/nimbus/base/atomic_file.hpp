// Writing files atomically: a temporary file beside the target, renamed over it only once
// complete, so a failed or interrupted write never leaves a partial file or replaces a good one.
#pragma once
#include <filesystem>
#include <functional>

namespace nimbus {

// Calls write(tmp_path) to produce the file, flushes it to disk (fsync), then renames tmp_path
// to `path` and flushes the directory, so a crash leaves either the old file or the complete
// new one. Creates missing parent directories. Replaces only a regular file: an existing
// `path` that is a directory, symbolic link, FIFO, device or socket is std::runtime_error. On any exception the temporary file is removed
// and the exception propagates; `path` is untouched.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& write);

}  // namespace nimbus
