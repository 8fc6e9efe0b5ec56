// The clouds' density textures on the GPU: half floats (the default: half the memory and
// bandwidth, within the slicer's tolerance of the float path) or floats. A nimbus type, so that
// the frame description carries no GL type; the GL layer maps it to its texture format.
#pragma once

namespace nimbus::render {

enum class VolumeFormat {
  Half,   // 16-bit float texels (GL_R16F)
  Float,  // 32-bit float texels (GL_R32F)
};

}  // namespace nimbus::render
