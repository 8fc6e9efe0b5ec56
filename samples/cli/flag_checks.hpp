// Checks of the parsed command line that hold for every command: no empty values, and each
// given flag applies to what was asked (a table of the modes each flag belongs to).
#pragma once
#include <string>
#include <vector>

#include "cli.hpp"

namespace nimbus::cli {

// UsageError "<flag>: the value is empty" for any option of the parsed subcommands given as ''
// (an empty value would silently mean the default).
void refuse_empty_values(const CLI::App& app);

// One flag of a command with modes: the modes (bits) it applies to.
struct FlagModes {
  std::string flag;  // as CLI11 names it: "--slices", "--output", or a positional's name
  unsigned modes;
};

// UsageError "<flag>: applies to <its modes>, not to <mode>" for the first flag given on `cmd`
// whose modes exclude `mode` (one bit). mode_names[i] describes bit i. A given flag missing from
// the table is a std::logic_error: a new flag must say where it belongs.
void check_flags_apply(const CLI::App& cmd, const std::vector<FlagModes>& table, unsigned mode,
                       const std::vector<std::string>& mode_names);

}  // namespace nimbus::cli
