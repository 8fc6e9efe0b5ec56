// Every file a run reads, gathered in one place for the output checks (outputs.hpp), from what
// the run parsed rather than from its flags alone: the files the flags name, and the files named
// inside them: a sky's cloud files (every existing frame of a sequence) and coverage maps, the
// coverage map a preset, a --params file, a --set or --coverage-map resolved to, a view state's
// sky. Commands add the objects they parsed, so a file named anywhere in a run's inputs is an
// input, whichever way it was named.
#pragma once
#include <string>
#include <vector>

#include "nimbus/volume/cloud_model.hpp"
#include "nimbus/volume/sky.hpp"

namespace nimbus::cli {

// A path given to the run, and what gave it ("-o", "--preview", "FILE", "--sky 'k.json' clouds[0].file").
struct PathArg {
  std::string flag, path;
};

class RunInputs {
 public:
  // A file a flag names ("--params", p); an empty path (a flag not given) adds nothing.
  RunInputs& file(const std::string& what, const std::string& path);
  // The coverage map the cloud's parameters hold, wherever it was named (the preset, --params,
  // --set, --coverage-map), as resolved when they were read; named "<what>.coverage_map".
  RunInputs& cloud(const volume::CloudParams& params, const std::string& what);
  // Every cloud of a sky: a file cloud's file (each existing frame of a sequence) and a preset
  // cloud's coverage map (resolved beside the sky file when it was loaded). `what` names the sky
  // ("--sky 'k.json'").
  RunInputs& sky(const volume::Sky& sky, const std::string& what);

  const std::vector<PathArg>& paths() const { return paths_; }

 private:
  std::vector<PathArg> paths_;
};

}  // namespace nimbus::cli
