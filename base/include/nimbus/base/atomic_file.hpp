// Writing files atomically: a temporary file beside the target, renamed over it only once
// complete, so a failed or interrupted write never leaves a partial file or replaces a good one.
#pragma once
#include <filesystem>
#include <functional>
#include <string>

namespace nimbus {

// A name for a temporary file beside `path`, in its folder: "." + its name + `tag` + "<pid>.<thread>.
// <counter>.<random>", which no other call, thread or process draws (the pid and thread set
// apart what runs at once here, the counter the calls of one thread, and 64 random bits the
// processes of other hosts or pid namespaces that share the folder). write_atomically's and
// StagedFiles' temporaries and check_output_path's probe are named so.
std::filesystem::path unique_name_beside(const std::filesystem::path& path, const std::string& tag = ".tmp");

// A new, empty file named by unique_name_beside, created with O_EXCL (mode 0666 less the umask):
// should the name exist, another is drawn, so a leftover file of any name never matters.
// std::system_error (the errno, and the folder) when the folder does not take it.
std::filesystem::path create_file_beside(const std::filesystem::path& path, const std::string& tag = ".tmp");

// Calls write(tmp_path) to produce the file, flushes it to disk (fsync), then renames tmp_path
// to `path` and flushes the directory, so a crash leaves either the old file or the complete
// new one. Creates missing parent directories. Replaces only a regular file: an existing
// `path` that is a directory, symbolic link, FIFO, device or socket is std::runtime_error. On any exception the temporary file is removed
// and the exception propagates; `path` is untouched.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& write);

}  // namespace nimbus
