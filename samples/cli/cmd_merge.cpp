// `nimbus merge BRICKS... -o whole.vdb`: joins the bricks that `generate --brick I/N` wrote into
// the one grid a single process would have generated (volume/brick.hpp).
#include <chrono>
#include <cstdio>

#include "cli.hpp"
#include "outputs.hpp"
#include "nimbus/base/memory.hpp"
#include "nimbus/volume/brick.hpp"
#include "nimbus/volume/vdb_io.hpp"

namespace nimbus::cli {
namespace {

struct MergeArgs {
  std::vector<std::string> bricks;
  std::string output;
};

int run_merge(const MergeArgs& a) {
  if (a.bricks.empty()) throw UsageError("BRICKS: give the brick files (e.g. bricks/*.vdb)");
  if (a.output.empty()) throw UsageError("-o: an output file is required");
  RunInputs inputs;
  for (const std::string& b : a.bricks) inputs.file("BRICKS", b);
  check_outputs({{"-o", a.output}}, inputs);
  checks_done();
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::filesystem::path> files(a.bricks.begin(), a.bricks.end());
  const volume::JoinedField joined = volume::join_bricks(files);
  const auto t1 = std::chrono::steady_clock::now();
  // As generate refuses a cloud with no voxel, so does the whole it would have written in one go.
  if (joined.active_voxels == 0)
    throw std::runtime_error("BRICKS: the " + std::to_string(joined.layout.size()) + " bricks of " + joined.layout.text() +
                             " hold no voxel of density >= 1e-6 (shapes smaller than a voxel, or coverage, weight or "
                             "density leave nothing); nothing written");
  std::vector<openvdb::FloatGrid::ConstPtr> grids(joined.grids.begin(), joined.grids.end());
  volume::write_volume_vdb(a.output, grids, joined.info, joined.options);
  const auto t2 = std::chrono::steady_clock::now();
  std::printf("wrote %s: %d bricks of %s joined, %lld active voxels%s; read and joined in %.2f s, written in %.2f s, "
              "peak memory %.0f MiB\n",
              a.output.c_str(), joined.layout.size(), joined.layout.text().c_str(),
              static_cast<long long>(joined.active_voxels), grids.size() > 1 ? " + temperature" : "",
              std::chrono::duration<double>(t1 - t0).count(), std::chrono::duration<double>(t2 - t1).count(),
              double(peak_resident_bytes()) / (1 << 20));
  return 0;
}

}  // namespace

void add_merge_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<MergeArgs>();
  CLI::App* cmd = app.add_subcommand("merge", "Join the bricks of generate --brick into one OpenVDB file");
  cmd->add_option("BRICKS", a->bricks, "brick files, every brick of one field exactly once")->required();
  cmd->add_option("-o,--output", a->output, "output .vdb file")->required();
  cmd->callback([&action, a] { action = [a] { return run_merge(*a); }; });
}

}  // namespace nimbus::cli
