// Several files written as one result, all or nothing: a render's EXR and its PNG preview. Each
// is written to a temporary beside its target; only when every one is complete are they renamed
// into place, and a failure on the way puts back what was there before.
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace nimbus {

class StagedFiles {
 public:
  StagedFiles() = default;
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;
  // Removes the temporaries of a result that was not committed.
  ~StagedFiles();

  // Calls write(tmp) to produce `target`'s content in a temporary file beside it (its directory
  // is created). An exception from write propagates with `target` named in place of the
  // temporary; nothing is left of this file, and commit() is no longer allowed.
  void write(const std::filesystem::path& target, const std::function<void(const std::filesystem::path&)>& write);

  // Renames every temporary over its target. Should one rename fail, the targets renamed before
  // it get their old content back (or are removed, where there was none) and std::runtime_error
  // names the file that failed.
  void commit();

 private:
  struct Entry {
    std::filesystem::path target, tmp, backup;  // backup: a hard link to the old target, if any
  };
  std::vector<Entry> entries_;
  bool failed_ = false;
};

}  // namespace nimbus
