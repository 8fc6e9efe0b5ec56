// `nimbus bench volume`'s keyframe table: the default sky's evolution keyframes made as the
// viewer makes them (render/sky SkyKeyframes: tests saved at the first keyframe and read at the
// next, grids made y-up) against the same keyframes made plainly (every test made, the z-up grid
// turned y-up), the anchor, in the same run, with the voxels compared.
#pragma once

namespace nimbus::cli {

// `count` keyframes (0, 1, ... at the sky's interval), each made both ways, alternating.
void bench_sky_keyframes(int count);

}  // namespace nimbus::cli
