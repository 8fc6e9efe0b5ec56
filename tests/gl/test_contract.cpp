// The C++/GLSL contract checked on the GL context (shaders/lib/contract.glsl,
// render/gl/uniform_blocks.hpp): every program that declares a uniform block has it at the
// contract's binding with the C++ struct's size and member offsets (and no member C++ lacks);
// every sampler and image has the unit the contract gives its role, and no two in one program
// share one; and the phase codes select the same phase function on the GPU as on the CPU.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/core/shader_contract.hpp"
#include "nimbus/render/gl/shader_program.hpp"
#include "nimbus/render/gl/uniform_blocks.hpp"
#include "nimbus/render/shafts/airlight_gl.hpp"
#include "test_gl_support.hpp"

namespace nimbus::render {
namespace {

struct ProgramSpec {
  std::vector<std::string> stages;
  std::string defines;
};

std::string shaft_defines(int method, bool table) {
  return "#define METHOD " + std::to_string(method) + "\n#define STEPS 8\n#define AIRLIGHT_TABLE " +
         (table ? "1" : "0") + "\n#define CLOUD_SHADOW 1\n";
}

// Every program the renderers build, in the variants that declare the most.
std::vector<ProgramSpec> renderer_programs() {
  return {
      {{"fullscreen.vert.glsl", "shafts.frag.glsl"}, shaft_defines(SHAFT_METHOD_RAYMARCH, false)},
      {{"fullscreen.vert.glsl", "shafts.frag.glsl"}, shaft_defines(SHAFT_METHOD_ANALYTIC, true)},
      {{"fullscreen.vert.glsl", "shafts.frag.glsl"}, shaft_defines(SHAFT_METHOD_SHADOW_VOLUME, false)},
      {{"surface.vert.glsl", "surface.frag.glsl"}, "#define CLOUD_SHADOW 1\n"},
      {{"shadow_distance.vert.glsl", "shadow_distance.frag.glsl"}, ""},
      {{"shadow_volume_build.comp.glsl"}, ""},
      {{"shadow_volume_interval.vert.glsl", "shadow_volume_interval.frag.glsl"}, ""},
      {{"cloud_slice.vert.glsl", "cloud_slice.frag.glsl"}, "#define UNDERLAY 1\n#define OCTAVES 2\n"},
      {{"cloud_slice.vert.glsl", "cloud_slice.frag.glsl"}, "#define UNDERLAY 1\n#define OCTAVES 0\n#define MS_VOLUME 1\n"},
      {{"cloud_slice.vert.glsl", "cloud_slice.frag.glsl"}, "#define UNDERLAY 1\n#define OCTAVES 0\n#define MS_VOLUME 2\n"},
      {{"cloud_light.vert.glsl", "cloud_light.frag.glsl"}, ""},
      {{"fullscreen.vert.glsl", "cloud_light_blur.frag.glsl"}, ""},
      {{"fullscreen.vert.glsl", "cloud_composite.frag.glsl"}, ""},
      {{"cloud_shadow_build.comp.glsl"}, ""},
      {{"light_volume_radiance.comp.glsl"}, ""},
      {{"airlight_eval.comp.glsl"}, ""},
  };
}

std::string describe(const ProgramSpec& p) {
  std::string s;
  for (const auto& n : p.stages) s += (s.empty() ? "" : " + ") + n;
  return s + (p.defines.empty() ? "" : " [" + p.defines + "]");
}

GLint resource_int(GLuint program, GLenum interface, GLuint index, GLenum property) {
  GLint value = -1;
  glGetProgramResourceiv(program, interface, index, 1, &property, 1, nullptr, &value);
  return value;
}

std::string resource_name(GLuint program, GLenum interface, GLuint index) {
  char name[256] = {0};
  glGetProgramResourceName(program, interface, index, sizeof name, nullptr, name);
  return name;
}

TEST(Contract, UniformBlocksMatchTheirCppStructs) {
  NIMBUS_REQUIRE_GL();
  std::map<std::string, int> programs_using;
  for (const ProgramSpec& spec : renderer_programs()) {
    const ShaderProgram program(spec.stages, spec.defines);
    const GLuint id = program.id();
    GLint blocks = 0;
    glGetProgramInterfaceiv(id, GL_UNIFORM_BLOCK, GL_ACTIVE_RESOURCES, &blocks);
    for (GLint b = 0; b < blocks; ++b) {
      const std::string name = resource_name(id, GL_UNIFORM_BLOCK, static_cast<GLuint>(b));
      bool known = false;
      for (const BlockLayout& layout : uniform_block_layouts()) {
        if (name != layout.block) continue;
        known = true;
        ++programs_using[name];
        EXPECT_EQ(resource_int(id, GL_UNIFORM_BLOCK, static_cast<GLuint>(b), GL_BUFFER_BINDING), layout.binding)
            << name << " in " << describe(spec);
        EXPECT_EQ(resource_int(id, GL_UNIFORM_BLOCK, static_cast<GLuint>(b), GL_BUFFER_DATA_SIZE),
                  static_cast<GLint>(layout.size))
            << name << " in " << describe(spec);
        EXPECT_EQ(resource_int(id, GL_UNIFORM_BLOCK, static_cast<GLuint>(b), GL_NUM_ACTIVE_VARIABLES),
                  static_cast<GLint>(layout.members.size()))
            << name << " in " << describe(spec) << ": GLSL and C++ list different members";
        for (const BlockMember& m : layout.members) {
          const GLuint index = glGetProgramResourceIndex(id, GL_UNIFORM, m.name.c_str());
          ASSERT_NE(index, GL_INVALID_INDEX) << m.name << " missing from " << describe(spec);
          EXPECT_EQ(resource_int(id, GL_UNIFORM, index, GL_OFFSET), static_cast<GLint>(m.offset))
              << m.name << " in " << describe(spec);
        }
      }
      EXPECT_TRUE(known) << describe(spec) << " declares block " << name << ", which the contract does not list";
    }
  }
  for (const BlockLayout& layout : uniform_block_layouts())
    EXPECT_GT(programs_using[layout.block], 0) << layout.block << " is used by no program: the test checks nothing";
  check_gl("contract blocks");
}

bool is_opaque(GLint type) {
  switch (type) {
    case GL_SAMPLER_2D:
    case GL_SAMPLER_3D:
    case GL_SAMPLER_2D_ARRAY:
    case GL_SAMPLER_CUBE_MAP_ARRAY:
    case GL_IMAGE_2D:
    case GL_IMAGE_3D:
      return true;
    default:
      return false;
  }
}

// Each sampler's role and the unit the contract gives it (written out here, apart from the GLSL).
const std::map<std::string, int>& expected_units() {
  static const std::map<std::string, int> units = {
      {"u_density", contract::UNIT_CLOUD_DENSITY},       {"u_point_shadow", contract::UNIT_POINT_SHADOW},
      {"u_cube", contract::UNIT_POINT_SHADOW},           {"u_sun_shadow", contract::UNIT_SUN_SHADOW},
      {"u_map", contract::UNIT_SUN_SHADOW},              {"u_surface_radiance", contract::UNIT_SURFACE_RADIANCE},
      {"u_surface_distance", contract::UNIT_SCENE_DISTANCE}, {"u_scene_distance", contract::UNIT_SCENE_DISTANCE},
      {"u_jitter", contract::UNIT_JITTER},               {"u_sv_near", contract::UNIT_SV_NEAR},
      {"u_sv_far", contract::UNIT_SV_FAR},               {"u_F_table", contract::UNIT_F_TABLE},
      {"u_cloud_tau", contract::UNIT_CLOUD_TAU},         {"u_cloud_range", contract::UNIT_CLOUD_RANGE},
      {"u_light", contract::UNIT_LIGHT_BUFFER},          {"u_previous", contract::UNIT_LIGHT_BUFFER},
      {"u_scene_color", contract::UNIT_SCENE_COLOR},     {"u_cloud_color", contract::UNIT_CLOUD_COLOR},
      {"u_cloud_distance", contract::UNIT_CLOUD_DISTANCE}, {"u_tau", contract::IMAGE_CLOUD_TAU},
      {"u_range", contract::IMAGE_CLOUD_RANGE},         {"u_density_next", contract::UNIT_CLOUD_DENSITY_NEXT},
      {"u_frame", contract::UNIT_SCENE_COLOR},            {"u_sky_view", contract::UNIT_SKY_VIEW},
      {"u_aerial_scattering", contract::UNIT_AERIAL_SCATTERING}, {"u_aerial_transmittance", contract::UNIT_AERIAL_TRANSMITTANCE},
      {"u_light_volume", contract::UNIT_LIGHT_VOLUME},  {"u_surface_airlight_table", contract::UNIT_SURFACE_AIRLIGHT},
      {"u_light_radiance", contract::UNIT_LIGHT_RADIANCE}, {"u_radiance", contract::IMAGE_LIGHT_RADIANCE},
      {"u_ground_albedo", contract::UNIT_GROUND_ALBEDO},
  };
  return units;
}

TEST(Contract, SamplersHaveTheirRolesUnitAndNeverShareOne) {
  NIMBUS_REQUIRE_GL();
  int checked = 0;
  for (const ProgramSpec& spec : renderer_programs()) {
    const ShaderProgram program(spec.stages, spec.defines);
    const GLuint id = program.id();
    GLint uniforms = 0;
    glGetProgramInterfaceiv(id, GL_UNIFORM, GL_ACTIVE_RESOURCES, &uniforms);
    std::map<std::pair<bool, GLint>, std::string> used;  // (image?, unit) -> name
    for (GLint u = 0; u < uniforms; ++u) {
      const GLint type = resource_int(id, GL_UNIFORM, static_cast<GLuint>(u), GL_TYPE);
      if (!is_opaque(type)) continue;
      const std::string name = resource_name(id, GL_UNIFORM, static_cast<GLuint>(u));
      GLint unit = -1;
      glGetUniformiv(id, resource_int(id, GL_UNIFORM, static_cast<GLuint>(u), GL_LOCATION), &unit);
      const auto expected = expected_units().find(name);
      ASSERT_NE(expected, expected_units().end()) << name << " in " << describe(spec) << " has no role in the contract";
      EXPECT_EQ(unit, expected->second) << name << " in " << describe(spec);
      const auto key = std::make_pair(type == GL_IMAGE_2D || type == GL_IMAGE_3D, unit);
      EXPECT_EQ(used.count(key), 0u) << name << " and " << used[key] << " share unit " << unit << " in "
                                     << describe(spec);
      used[key] = name;
      ++checked;
    }
  }
  EXPECT_GT(checked, 15);
  check_gl("contract samplers");
}

// A phase code sent to the GPU selects the same function as the kind does on the CPU: the GPU's
// ray-marched airlight (its own float phase) against the CPU's (double phase) for every kind.
TEST(Contract, PhaseCodesSelectTheSameFunctionOnTheGpu) {
  NIMBUS_REQUIRE_GL();
  std::vector<AirlightQuery> queries;
  for (double gamma : {0.2, 1.0, 2.0, 2.9}) queries.push_back({0.05, 10.0, 8.0, 30.0, gamma});
  const AirlightMethod march{AirlightMethod::RayMarch, 256};
  for (PhaseKind kind : {PhaseKind::Isotropic, PhaseKind::HenyeyGreenstein, PhaseKind::Schlick, PhaseKind::Rayleigh}) {
    const Phase phase{kind, 0.6};
    const std::vector<double> gpu = evaluate_airlight_gl(queries, march, phase);
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const double cpu = airlight_raymarch(queries[i], march.n, phase);
      EXPECT_NEAR(gpu[i], cpu, 1e-4 * cpu) << to_string(phase) << " gamma " << queries[i].gamma;
    }
  }
}

}  // namespace
}  // namespace nimbus::render
