// A camera for clouds nobody placed one for: framed on their bounds, and its clip planes fitted
// to them. `nimbus render` and the viewer start from it.
#pragma once
#include <vector>

#include "nimbus/render/core/camera.hpp"
#include "nimbus/render/core/cloud_volume.hpp"

namespace nimbus::render {

// `camera` moved to see every cloud: it looks at the centre of their bounds from its own side
// (eye - look_at), far enough for their bounding sphere to fit the field of view (15 % margin).
// on_ground (under a sky): the eye stands 2 m above y = 0 and pitches up only as far as it must,
// so the horizon (and the clouds' shadows) stay in the lower part of the picture. Near and far
// planes fit the clouds. Width, height and fov are kept. An empty list leaves it as it is.
Camera frame_clouds(Camera camera, const std::vector<CloudVolume>& clouds, bool on_ground);

// The same, with the left `covered_px` pixels of the picture hidden (the viewer's panel): the
// clouds are framed in the part to their right, centred in it. A camera as wide as that part
// (the same focal length) is framed on them, then turned left about the vertical by the angle
// between the picture's centre and the part's centre. covered_px is clamped to [0, 3/4 width];
// below one pixel this is frame_clouds.
Camera frame_clouds_right_of(Camera camera, const std::vector<CloudVolume>& clouds, bool on_ground, double covered_px);

// A camera placed by hand: its far plane pushed out, if need be, to reach every cloud.
// With repeat_to_m > 0, periodic clouds' copies out to that distance (cloud_tiles.hpp) fit too.
Camera fit_far_plane(Camera camera, const std::vector<CloudVolume>& clouds, double repeat_to_m = 0.0);

}  // namespace nimbus::render
