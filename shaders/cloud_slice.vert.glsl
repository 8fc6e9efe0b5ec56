#version 450 core
// Eye pass vertices of the half-angle slicer (see lib/cloud_slice_vertex.glsl).
#include "lib/cloud_slice_vertex.glsl"
