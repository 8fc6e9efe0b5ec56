// The one contract between the C++ renderer and its shaders: codes, limits, texture units and
// buffer bindings. Written in the common subset of GLSL 4.50 and C++: the shaders include it,
// and C++ includes it through nimbus/render/core/shader_contract.hpp (namespace
// nimbus::render::contract). C++ maps its enums to these codes with explicit switches (never an
// enum's order), and the uniform blocks' C++ structs (render/gl/uniform_blocks.hpp) are checked
// against the layouts below by static_assert and by a GL test.
#ifndef NIMBUS_CONTRACT_GLSL
#define NIMBUS_CONTRACT_GLSL

// --- Light limits -------------------------------------------------------------------------
const int MAX_POINT_LIGHTS = 4;  // point lights one GPU frame lights (Lights block)

// --- Light kinds (LightRecord.position.w of lib/light_record.glsl; render::light_record) ------
const int LIGHT_SUN = 0;   // parallel light; position.xyz is the unit direction towards the sun
const int LIGHT_LAMP = 1;  // a point light, a spot among them; position.xyz is where it is

// --- Phase function codes (lib/phase.glsl; render::phase_code) -----------------------------
const int PHASE_ISOTROPIC = 0;
const int PHASE_HENYEY_GREENSTEIN = 1;
const int PHASE_SCHLICK = 2;
const int PHASE_RAYLEIGH = 3;

// --- Which light a shadow map belongs to (shadow_distance.frag.glsl and
//     shadow_volume_build.comp.glsl u_mode) -------------------------------------------------
const int SHADOW_POINT_LIGHT = 0;  // a cube map of distances from the light
const int SHADOW_SUN = 1;          // an orthographic map of distances along the sun's direction

// --- Jitter of ray-marched samples (shafts.frag.glsl u_jitter_mode; render::jitter_code) ---
const int JITTER_NONE = 0;         // the middle of each step
const int JITTER_WHITE = 1;        // a hash per pixel
const int JITTER_BLUE_NOISE = 2;   // the tiled blue-noise texture

// --- Light-shaft methods: the METHOD define of shafts.frag.glsl, compared by the
//     preprocessor, hence macros (render::shaft_method_code) -------------------------------
#define SHAFT_METHOD_RAYMARCH 0
#define SHAFT_METHOD_ANALYTIC 1
#define SHAFT_METHOD_SHADOW_VOLUME 2

// --- Airlight evaluations (airlight_eval.comp.glsl u_method; render::airlight_eval_code) ---
const int AIRLIGHT_EVAL_STABLE = 0;
const int AIRLIGHT_EVAL_TABLE = 1;
const int AIRLIGHT_EVAL_RAYMARCH = 2;

// --- Texture units (layout(binding = ...) of samplers; glBindTextureUnit) -----------------
// One unit per role; a role shared by several programs keeps its unit in all of them.
const int UNIT_CLOUD_DENSITY = 0;      // sampler3D: a cloud's density (slices, light pass, cloud shadow)
const int UNIT_POINT_SHADOW = 1;       // samplerCubeArray: point lights' distance maps
const int UNIT_SUN_SHADOW = 2;         // sampler2D: the sun's distance map
const int UNIT_SURFACE_RADIANCE = 3;   // sampler2D: radiance leaving the visible surfaces
const int UNIT_SCENE_DISTANCE = 4;     // sampler2D: metres to the visible surface, 0 = none
const int UNIT_JITTER = 5;             // sampler2D: tiled jitter values
const int UNIT_SV_NEAR = 6;            // sampler2DArray: nearest shadow-volume crossing per light
const int UNIT_SV_FAR = 7;             // sampler2DArray: farthest crossing
const int UNIT_F_TABLE = 8;            // sampler2D: Sun et al.'s F(u, v)
const int UNIT_CLOUD_TAU = 9;          // sampler2D: the clouds' optical depth toward the sun
const int UNIT_CLOUD_RANGE = 10;       // sampler2D: the depth range of the cloud matter
const int UNIT_LIGHT_BUFFER = 11;      // sampler2D: the slicer's optical depth toward the light
const int UNIT_SCENE_COLOR = 12;       // sampler2D: the scene under the clouds (the viewer's display: the finished frame)
const int UNIT_CLOUD_COLOR = 13;       // sampler2D: the clouds' premultiplied radiance
const int UNIT_CLOUD_DISTANCE = 14;    // sampler2D: the clouds' weighted distances
const int UNIT_CLOUD_DENSITY_NEXT = 15; // sampler3D: the cloud's next keyframe (CloudBlock.blend mixes it in)
// Units past 15 are fine: GL 4.5 guarantees 80 combined units; 16 is the limit per stage's count.
const int UNIT_SKY_VIEW = 16;            // sampler2D: the physical sky's radiance (atmosphere_tables.hpp)
const int UNIT_AERIAL_SCATTERING = 17;   // sampler3D: the air's in-scattered radiance to a distance
const int UNIT_AERIAL_TRANSMITTANCE = 18; // sampler3D: the air's transmittance to a distance
const int UNIT_LIGHT_VOLUME = 19;        // sampler3D: scattered light's fluence and flux (lib/cloud_light_volume.glsl)
const int UNIT_SURFACE_AIRLIGHT = 20;    // sampler2D: the surface airlight's g(ln Tsp, theta_s) (lib/surface_airlight_texture.glsl)
const int UNIT_LIGHT_RADIANCE = 21;      // sampler3D: the light volume's in-scattered radiance toward this frame's eye
const int UNIT_GROUND_ALBEDO = 22;       // sampler2D: the ground's albedo texture, mipmapped, repeating (lib/ground_albedo.glsl)

// --- Image units (layout(binding = ...) of images; glBindImageTexture) --------------------
const int IMAGE_CLOUD_TAU = 0;         // image2D r32f: the cloud shadow map being built
const int IMAGE_CLOUD_RANGE = 1;       // image2D rg32f
const int IMAGE_LIGHT_RADIANCE = 2;    // image3D rgba32f: the light volume's radiance toward the eye being made

// --- Shader storage buffers (layout(std430, binding = ...); glBindBufferBase) -------------
const int STORAGE_AIRLIGHT_QUERIES = 0;
const int STORAGE_AIRLIGHT_RESULTS = 1;
const int STORAGE_SKIRT_QUADS = 0;
const int STORAGE_SKIRT_COUNTER = 1;

// --- Uniform blocks (layout(std140, binding = ...); glBindBufferBase / Range) -------------
const int BLOCK_CAMERA = 0;            // CameraBlock (lib/camera_ray.glsl)
const int BLOCK_LIGHTS = 1;            // LightsBlock (lib/light_list.glsl)
const int BLOCK_CLOUD = 2;             // CloudBlock (lib/cloud_block.glsl), one range per cloud
const int BLOCK_SLICE_LIGHT = 3;       // SliceLightBlock (lib/cloud_light_block.glsl): the slicer pass's light
const int BLOCK_CLOUD_SHADOW_MARCH = 4;  // CloudShadowMarchBlock (cloud_shadow_build.comp.glsl), one range per cloud
const int BLOCK_SHADOW_MAP = 5;        // ShadowMapBlock (lib/shadow_map_block.glsl): a shadow map's light, its skirts
const int BLOCK_SCENE_SHADOWS = 6;     // SceneShadowsBlock (lib/lights.glsl): the scene's shadow maps, looked up
const int BLOCK_SKY = 7;               // SkyBlock (lib/sky_block.glsl): the sky behind the scene, the aerial perspective
const int BLOCK_LIGHT_VOLUME = 8;      // LightVolumeBlock (lib/cloud_light_volume.glsl): the light volume's grid
const int BLOCK_SHAFT_PASS = 9;        // ShaftPassBlock (shafts.frag.glsl): the shaft pass's march and jitter
const int BLOCK_SURFACE_DRAW = 10;     // SurfaceDrawBlock (surface.frag.glsl): what the surface pass draws now
const int BLOCK_GROUND_ALBEDO = 11;    // GroundAlbedoBlock (lib/ground_albedo.glsl): the ground's texture's scales

#endif
