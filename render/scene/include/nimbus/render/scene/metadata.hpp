// The metadata every renderer writes into its image (camera, scene, lights, medium, clouds), in
// one format, so that an EXR from the GPU and one from a CPU reference describe a frame alike.
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_optics.hpp"
#include "nimbus/render/core/cloud_volume.hpp"
#include "nimbus/render/core/image.hpp"
#include "nimbus/render/scene/scene.hpp"

namespace nimbus::render {

// "x,y,z" with 9 significant digits.
std::string fmt3(const glm::dvec3& v);

// Positions and directions in nimbus's Z-up world (world_axes.hpp), as every flag takes them.
// "eye X,Y,Z look_at X,Y,Z up X,Y,Z fov_deg F (z up)": the value of the "camera" key.
std::string describe_camera(const Camera& camera);
// "sun towards X,Y,Z (z up) E_w_m2 R,G,B" or "point X,Y,Z (z up) I_w_sr R,G,B [spot axis X,Y,Z inner_rad A
// outer_rad B]": a light as the "light" key of a cloud frame names it.
std::string describe_light(const Light& light);
// Several lights, "; " between them.
std::string describe_lights(const std::vector<Light>& lights);

// Keys "scene", "method", "camera", "medium", "lights" and, under a sky, "sky".
void describe_frame(Image& image, const Scene& scene, const Camera& camera, const std::string& method);

// Keys "clouds" (their names), "cloud_optics" (size and optics of each) and "light".
void describe_clouds(Image& image, const std::vector<CloudVolume>& clouds, const Light& light);
void describe_clouds(Image& image, const std::vector<CloudVolume>& clouds, const std::vector<Light>& lights);

}  // namespace nimbus::render
