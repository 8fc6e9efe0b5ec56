#version 450 core
// Light pass vertices of the half-angle slicer (see lib/cloud_slice_vertex.glsl).
#include "lib/cloud_slice_vertex.glsl"
