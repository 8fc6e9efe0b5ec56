#version 450 core
// The scene's vertices for shadow_distance.frag.glsl.
#include "lib/scene_vertex.glsl"
