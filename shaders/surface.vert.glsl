#version 450 core
// The scene's vertices for surface.frag.glsl.
#include "lib/scene_vertex.glsl"
