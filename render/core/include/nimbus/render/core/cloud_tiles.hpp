// A periodic field drawn to the horizon: which copies of each periodic cloud's tile
// (CloudVolume::period_m) the slicer draws out to CloudSliceSettings::repeat_to_m, and in which of
// its two passes. A ray from the eye crosses a convex region around the eye first and never comes
// back to it. The near pass holds what lies in one such region (a rectangle in x and z): the eye's
// copy of each periodic tile, every cloud that does not repeat, and the copies that overlap them.
// The far pass holds every other copy within reach and in view; it is drawn behind the near one
// ("under"), so the two composite in the order a ray meets them. Copies share their cloud's
// texture: nothing is uploaded twice.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_volume.hpp"

namespace nimbus::render {

// One drawn copy: cloud `cloud` of the list, moved by `offset_m` (a whole number of periods).
struct CloudInstance {
  std::size_t cloud = 0;
  glm::dvec3 offset_m{0.0};
};

struct CloudTilePlan {
  std::vector<CloudInstance> near, far;
  std::size_t left_out = 0;  // copies within reach and in view not drawn (beyond kMaxFarCopies, the nearest kept)
};

constexpr std::size_t kMaxFarCopies = 1024;
constexpr int kMaxRepeatsPerAxis = 64;  // copies each way from the eye's tile, per axis, at most

// What is wrong with the cloud's period, "along x (10 m) is shorter than the cloud (600 m): its
// copies would overlap", or empty when nothing is: not finite, negative, a y part, shorter than
// the cloud's extent along its axis, or shorter than a voxel. A period that is not an exact whole number of voxels
// leaves a seam; the caller's tiles are exact.
std::string period_fault(const CloudVolume& cloud);
// std::invalid_argument "cloud '<name>': period <fault>" when period_fault finds one.
void validate_period(const CloudVolume& cloud);

// The copies drawn for `camera`. repeat_to_m = 0, or no periodic cloud: near is every cloud
// where it is (offset 0) and far is empty, which is the slicer without tiles. Otherwise the
// eye's copy of each periodic cloud is the one whose tile centre is nearest the eye in x and z;
// far copies are those whose support box comes within repeat_to_m of the eye in x and z and
// meets the camera's view frustum (its side and near planes).
CloudTilePlan plan_cloud_tiles(const std::vector<CloudVolume>& clouds, const Camera& camera, double repeat_to_m);

}  // namespace nimbus::render
