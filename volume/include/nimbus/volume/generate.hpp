// Density grids from a cloud model: a sparse OpenVDB FloatGrid whose active voxels are exactly
// those with density >= kMinDensity. Only leaf blocks (8^3 voxels) that overlap the shapes are visited,
// only voxels whose coverage can still produce density evaluate the noise, and the noise
// keeps only the octaves the voxel size resolves.
#pragma once
#include <openvdb/openvdb.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "nimbus/volume/cloud_model.hpp"

namespace nimbus::volume {

// Below this a voxel is empty: half floats round densities under 2^-24 to 0, and a file should
// never hold active voxels of value 0.
inline constexpr float kMinDensity = 1e-6f;

// The tests of a generation that do not change with time when the wind is 0 (a sky's clouds,
// whose drift the renderer applies), saved for the next one: which leaf blocks no shape can
// reach, and which voxels of the others no displacement can move into a shape (CloudModel's far
// test). A generation of the same cloud at the same voxel size, origin, clip and axes, at any
// time, reads them instead of testing, and its voxels are the same bits. generate_density fills
// it; saved for other inputs (another drift included), the tests are made and saved anew, never
// read.
struct GenerationReuse {
  std::vector<double> key;        // the inputs the tests depend on (generate_density lists them)
  std::vector<uint8_t> touched;   // per leaf block: may a shape reach it
  std::vector<uint64_t> far;      // per leaf block, 8 words: bit i set when voxel i is far
  int64_t reused_blocks = 0;      // blocks of the last generation that read their tests here
};

struct GenerateOptions {
  double voxel_size = 25.0;  // metres; voxel (i, j, k) is centred at (i, j, k) * voxel_size
  double time = 0.0;         // seconds
  bool sparse = true;        // false: evaluate every voxel of the bounds (the naive anchor)
  bool octave_limit = true;  // false: keep every octave, even those the voxels cannot resolve
  // Only the voxels inside this index box (inclusive). Each voxel's value is a function of its
  // world position alone, so the grid of a sub-box equals the whole grid's voxels there.
  std::optional<openvdb::CoordBBox> clip;
  // Where the model's origin goes in the grid's world (metres): voxel (i, j, k) holds the model's
  // density at (i, j, k) * voxel_size - origin_m. A sky's clouds at their positions (sky_volume.hpp).
  glm::dvec3 origin_m{0.0};
  // The grid y-up (Houdini's, and the renderer's): voxel (i, j, k) holds what the z-up grid holds
  // at (i, -k, j), so the grid equals rotate_z_up_to_y_up of the z-up one (up_axis.hpp), made
  // directly; a clip is then a box of y-up indices.
  bool y_up = false;
  // Called now and then with the share of leaf blocks done, from any thread (the callee
  // serialises); may be empty.
  std::function<void(double)> progress;
  // Reused, or filled, as GenerationReuse says; null: every test is made.
  GenerationReuse* reuse = nullptr;
};

struct GenerateStats {
  int64_t voxels_in_bounds = 0;   // voxels of the model's bounding box
  int64_t voxels_visited = 0;     // voxels of the leaf blocks that overlap a shape
  int64_t noise_evaluations = 0;  // voxels that needed the billow noise
  int64_t active_voxels = 0;      // voxels with density >= kMinDensity
  int octaves_used = 0;
  int octaves_requested = 0;
  double seconds = 0.0;
};

// Throws std::invalid_argument for bad parameters, nimbus::OutOfMemoryRequest when the
// bounds hold more voxels than memory could store.
openvdb::FloatGrid::Ptr generate_density(const CloudParams& params, const GenerateOptions& options,
                                         GenerateStats* stats = nullptr);

// The index box (inclusive) that generate_density fills before any clip: every voxel whose centre
// lies in the model's bounds at `time`, at `voxel_size` metres (octaves limited as the options'
// default). Throws std::invalid_argument for bad parameters or an index beyond 2^30.
openvdb::CoordBBox density_index_box(const CloudParams& params, double voxel_size, double time,
                                      const glm::dvec3& origin_m = glm::dvec3(0.0));

// The temperature grid "temperature" of a hot gas, on exactly the density grid's active
// voxels and transform (see CloudParams::temperature_height); nullptr when the parameters
// ask for none. Values in [0, 1].
openvdb::FloatGrid::Ptr generate_temperature(const CloudParams& params, const openvdb::FloatGrid& density);

}  // namespace nimbus::volume
