// A density volume on the GPU for the slice renderer: the dense active box of a fog
// grid as a 3D texture, and the affine map from world space (metres) to its texture coordinates.
#pragma once
#include <openvdb/openvdb.h>

#include <array>

#include <glm/glm.hpp>

#include "nimbus/render/gl/resources.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::render {

struct VolumeTexture {
  GlTexture texture;                 // 3D, one channel, linear filtering, border 0 (as OpenVDB's
                                     // trilinear sampler sees the background outside the box)
  std::array<int, 3> size{0, 0, 0};  // texels per axis = voxels of the active box
  // World point (metres) -> texture coordinates: the centre of voxel (i, j, k) of the box lands
  // on ((i - origin.x + 0.5) / size.x, ...), as OpenVDB puts voxel centres at integer indices.
  glm::dmat4 world_to_texture{1.0};
  // World bounds of the support, where trilinear density can be non-zero: index origin - 1 to
  // origin + size on each axis (one voxel beyond the outermost voxel centres).
  glm::dvec3 world_min{0.0}, world_max{0.0};
  float max_density = 0.0f;
};

// Uploads `box` (volume::dense_active_box) of a grid with `transform`. internal_format is
// GL_R16F (half the memory; densities keep 11 significant bits) or GL_R32F (exact). Throws
// std::invalid_argument for an empty box, values that do not match the size, a non-affine
// transform, or an axis longer than GL_MAX_3D_TEXTURE_SIZE (naming the axis and both sizes).
// Needs a current GL 4.5 context.
VolumeTexture upload_volume(const volume::DenseBox& box, const openvdb::math::Transform& transform,
                            GLenum internal_format = GL_R16F);

}  // namespace nimbus::render
