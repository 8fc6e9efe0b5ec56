// The CPU layers' link check (render/CMakeLists.txt): every object of core, media, scene, image,
// reference and sky is linked into this program, which links no OpenGL or EGL library. If any of
// them called GL, the link would fail. Running it renders one pixel of the reference, so it does something.
#include <cstdio>

#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/reference/reference_renderer.hpp"

int main() {
  nimbus::render::Scene scene = nimbus::render::make_scene("lamps");
  scene.camera.width = scene.camera.height = 1;
  const nimbus::render::Image image = nimbus::render::render_reference(scene, scene.camera);
  std::printf("%g\n", static_cast<double>(image.rgba[0]));
  return 0;
}
