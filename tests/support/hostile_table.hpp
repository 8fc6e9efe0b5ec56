// Tables of hostile command lines (tests/cpu/test_hostile_*.cpp): each case runs the nimbus
// program and must exit with its code, print exactly one stderr line holding the expected words,
// print nothing on stdout, and leave the case's directory exactly as it was.
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace nimbus::test {

struct HostileCase {
  std::vector<std::string> args;  // "{d}" stands for the fixture directory
  int code;                       // 2: usage error, 1: runtime error
  std::string mentions;           // words the single stderr line must hold ("{d}" as in args)
  std::string stdin_path = "/dev/null";
};

// The directory as its entries stand: kind, size, inode and modification time of each, so a
// file written, replaced (a new inode) or created shows up, without reading FIFOs or big files.
std::map<std::string, std::string> snapshot(const std::filesystem::path& dir);

// `text` with every "{d}" replaced by `dir`.
std::string in_dir(std::string text, const std::filesystem::path& dir);

// Runs every case with "{d}" = `dir` and checks it (gtest EXPECTs, each traced with its command).
void expect_refused(const std::filesystem::path& dir, const std::vector<HostileCase>& cases);

}  // namespace nimbus::test
