// Hostile command-line tables (hostile_table.hpp).
#include "support/hostile_table.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>

#include "support/run_split.hpp"

namespace nimbus::test {

std::map<std::string, std::string> snapshot(const std::filesystem::path& dir) {
  std::map<std::string, std::string> entries;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    struct stat st {};
    ::lstat(e.path().c_str(), &st);
    entries[e.path().string()] = std::to_string(st.st_mode) + " " + std::to_string(st.st_size) + " " +
                                 std::to_string(st.st_ino) + " " + std::to_string(st.st_mtim.tv_sec) + "." +
                                 std::to_string(st.st_mtim.tv_nsec);
  }
  return entries;
}

std::string in_dir(std::string text, const std::filesystem::path& dir) {
  for (std::size_t at; (at = text.find("{d}")) != std::string::npos;) text.replace(at, 3, dir.string());
  return text;
}

void expect_refused(const std::filesystem::path& dir, const std::vector<HostileCase>& cases) {
  for (const HostileCase& c : cases) {
    std::vector<std::string> args;
    std::string shown;
    for (const std::string& arg : c.args) {
      const std::string a = in_dir(arg, dir);
      shown += (shown.empty() ? "" : " ") + (a.empty() ? std::string("''") : a);
      args.push_back(a);
    }
    const std::string in = in_dir(c.stdin_path, dir), mentions = in_dir(c.mentions, dir);
    const auto before = snapshot(dir);
    const SplitResult r = run_nimbus_split(args, in);
    SCOPED_TRACE("nimbus " + shown + (in == "/dev/null" ? "" : " < " + in));
    EXPECT_EQ(r.code, c.code) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.empty() ? '\n' : r.err.back(), '\n') << r.err;
    EXPECT_NE(r.err.find(mentions), std::string::npos) << "wanted: " << mentions << "\n" << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(snapshot(dir), before) << "the run changed its directory";
  }
}

}  // namespace nimbus::test
