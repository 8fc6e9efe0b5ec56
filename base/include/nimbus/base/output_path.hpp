// Checks on an output path before the work that produces it: that write_atomically could put a
// file there, and that it is not one of the inputs. Rendering for minutes and then failing to
// write, or replacing /dev/null or the input itself, are what these prevent.
#pragma once
#include <filesystem>
#include <string>

namespace nimbus {

// Throws std::runtime_error "<what> '<path>': ..." unless a regular file can be written at
// `path` now: an existing `path` must be a regular file (a directory, symbolic link, FIFO,
// device or socket is refused, never replaced); an existing parent directory must accept a new
// file (a probe file, named as write_atomically names its temporary and unique to the call, is
// created with O_EXCL and removed, so concurrent checks of one path and leftover files never clash);
// a missing parent must be creatable (a probe directory is made and removed in its nearest
// existing ancestor). Leaves nothing behind.
void check_output_path(const std::filesystem::path& path, const std::string& what);

// A text that is the same for two paths exactly when they name the same file: the device and
// inode of an existing file (links and other spellings included), else the weakly canonical
// absolute path. Comparing these finds an output that is also an input in n log n.
std::string file_identity(const std::filesystem::path& path);

}  // namespace nimbus
