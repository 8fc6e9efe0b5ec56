// Density volumes as 3D textures (volume_texture.hpp).
#include "nimbus/render/gl/volume_texture.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace nimbus::render {
VolumeTexture upload_volume(const volume::DenseBox& box, const openvdb::math::Transform& transform,
                            GLenum internal_format) {
  if (internal_format != GL_R16F && internal_format != GL_R32F)
    throw std::invalid_argument("volume texture format must be GL_R16F or GL_R32F");
  const char* axis = "xyz";
  std::size_t voxels = 1;
  for (int a = 0; a < 3; ++a) {
    if (box.size[a] <= 0) throw std::invalid_argument("volume is empty: its active box has no voxels");
    voxels *= static_cast<std::size_t>(box.size[a]);
  }
  if (box.values.size() != voxels)
    throw std::invalid_argument("volume box holds " + std::to_string(box.values.size()) + " values for " +
                                std::to_string(voxels) + " voxels");
  if (!transform.isLinear()) throw std::invalid_argument("volume transform is not affine (frustum grids are not supported)");
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max_size);
  for (int a = 0; a < 3; ++a)
    if (box.size[a] > max_size)
      throw std::invalid_argument(std::string("volume active box is ") + std::to_string(box.size[a]) + " voxels along " +
                                  axis[a] + ", more than this GL's 3D texture limit of " + std::to_string(max_size));

  VolumeTexture v;
  for (int a = 0; a < 3; ++a) v.size[a] = static_cast<int>(box.size[a]);
  v.texture = make_texture_3d(internal_format, v.size[0], v.size[1], v.size[2],
                              TextureParams{GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_BORDER, 1});
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage3D(v.texture.id(), 0, 0, 0, 0, v.size[0], v.size[1], v.size[2], GL_RED, GL_FLOAT, box.values.data());
  check_gl("uploading a volume texture");
  v.max_density = box.values.empty() ? 0.0f : *std::max_element(box.values.begin(), box.values.end());

  const glm::dmat4 index_to_world_m = index_to_world_matrix(transform);
  // Index -> texture: (index - origin + 0.5) / size.
  glm::dmat4 index_to_texture(1.0);
  for (int a = 0; a < 3; ++a) {
    index_to_texture[a][a] = 1.0 / v.size[a];
    index_to_texture[3][a] = (0.5 - box.origin[a]) / v.size[a];
  }
  v.world_to_texture = index_to_texture * glm::inverse(index_to_world_m);

  // World bounds of the support: trilinear density is 0 one voxel beyond the outermost
  // voxel centres (index origin - 1 .. origin + size), as the border texels are 0.
  v.world_min = glm::dvec3(1e300);
  v.world_max = glm::dvec3(-1e300);
  for (int c = 0; c < 8; ++c) {
    const double i = box.origin[0] - 1.0 + ((c & 1) ? v.size[0] + 1 : 0);
    const double j = box.origin[1] - 1.0 + ((c & 2) ? v.size[1] + 1 : 0);
    const double k = box.origin[2] - 1.0 + ((c & 4) ? v.size[2] + 1 : 0);
    const glm::dvec3 w = index_to_world(transform, glm::dvec3(i, j, k));
    v.world_min = glm::min(v.world_min, w);
    v.world_max = glm::max(v.world_max, w);
  }
  return v;
}

}  // namespace nimbus::render
