// All-or-nothing writes of several files (staged_files.hpp).
#include "nimbus/base/staged_files.hpp"

#include <stdexcept>

#include "nimbus/base/atomic_file.hpp"

namespace nimbus {
namespace {

namespace fs = std::filesystem;

// A name beside `target` that no other writer draws (atomic_file.hpp).
fs::path beside(const fs::path& target, const std::string& tag) { return unique_name_beside(target, tag); }

// `text` with every `from` replaced by `to`: messages name the target, not its temporary.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = 0; !from.empty() && (at = text.find(from, at)) != std::string::npos; at += to.size())
    text.replace(at, from.size(), to);
  return text;
}

}  // namespace

StagedFiles::~StagedFiles() {
  std::error_code ec;
  for (const Entry& e : entries_) fs::remove(e.tmp, ec);
}

void StagedFiles::write(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  if (failed_) throw std::logic_error("StagedFiles: a write failed before this one");
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw std::runtime_error("cannot create directory " + parent.string() + ": " + ec.message());
  Entry e{target, beside(target, ".tmp"), {}};
  try {
    write(e.tmp);
    if (!fs::is_regular_file(e.tmp)) throw std::runtime_error(target.string() + ": nothing was written");
  } catch (const std::exception& x) {
    failed_ = true;
    fs::remove(e.tmp, ec);
    throw std::runtime_error(replaced(x.what(), e.tmp.string(), target.string()));
  }
  entries_.push_back(e);
}

void StagedFiles::commit() {
  if (failed_) throw std::logic_error("StagedFiles: commit after a failed write");
  std::error_code ec;
  // Hard links keep the old targets, so that a failed rename can put them back.
  for (Entry& e : entries_) {
    if (!fs::is_regular_file(e.target, ec)) continue;
    e.backup = beside(e.target, ".old");
    fs::create_hard_link(e.target, e.backup, ec);
    if (ec) e.backup.clear();  // a file system without hard links: no way back for this one
  }
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    fs::rename(entries_[i].tmp, entries_[i].target, ec);
    if (!ec) continue;
    const std::string message = "cannot write " + entries_[i].target.string() + ": " + ec.message();
    for (std::size_t j = 0; j < i; ++j) {
      const Entry& done = entries_[j];
      if (!done.backup.empty()) fs::rename(done.backup, done.target, ec);
      else fs::remove(done.target, ec);
    }
    for (const Entry& e : entries_) {
      fs::remove(e.tmp, ec);
      if (!e.backup.empty()) fs::remove(e.backup, ec);
    }
    entries_.clear();
    throw std::runtime_error(message);
  }
  for (const Entry& e : entries_)
    if (!e.backup.empty()) fs::remove(e.backup, ec);
  entries_.clear();
}

}  // namespace nimbus
