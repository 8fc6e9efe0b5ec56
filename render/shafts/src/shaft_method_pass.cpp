// The GPU shaft methods as pass objects (shaft_method_pass.hpp): the ray march (Kind::RayMarch),
// the closed form of the airlight (Kind::Analytic: Sun et al. 2005's stable form, or their F table
// for the isotropic phase; thesis 4.2) and the shadow-volume intervals (Kind::ShadowVolume, thesis
// 4.3: the nearest and farthest skirt crossing per pixel, marched between them).
#include "shaft_method_pass.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "nimbus/render/media/airlight.hpp"
#include "nimbus/render/core/shader_contract.hpp"

namespace nimbus::render::shaft_detail {
namespace {

// Every pixel's ray sampled `steps` times against the shadow maps (thesis 4.1, Alg. 1).
class RayMarchPass final : public ShaftMethodPass {
 public:
  using ShaftMethodPass::ShaftMethodPass;
  void describe(Image& img) const override {
    img.metadata["samples_per_ray"] = std::to_string(method_.steps);
    img.metadata["jitter"] = to_string(method_.jitter);
  }
};

// The airlight in closed form; with the F table, the table for its size is uploaded once.
class AnalyticPass final : public ShaftMethodPass {
 public:
  using ShaftMethodPass::ShaftMethodPass;
  void bind(ShaftRenderer::Impl& s, const ShaderProgram&) const override {
    if (method_.airlight.kind != AirlightMethod::Table) return;
    auto it = s.f_tables.find(method_.airlight.n);
    if (it == s.f_tables.end()) {
      const FTable table(method_.airlight.n);
      const int n = table.size();
      GlTexture t = make_texture_2d(GL_R32F, n, n, TextureParams{GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE, 1});
      glTextureSubImage2D(t.id(), 0, 0, 0, n, n, GL_RED, GL_FLOAT, table.data());
      it = s.f_tables.emplace(n, std::move(t)).first;
    }
    glBindTextureUnit(contract::UNIT_F_TABLE, it->second.id());
  }
};

// Each light's skirts (built once from its shadow map) drawn into a layer of nearest (min) and
// farthest (max) crossings; the shaft pass marches only between them.
class ShadowVolumePass final : public ShaftMethodPass {
 public:
  using ShaftMethodPass::ShaftMethodPass;

  void prepare(ShaftRenderer::Impl& s, int w, int h, GpuTimer& timer, ShaftFrameStats& stats) override {
    const int layers = s.n_point + (s.scene.sun ? 1 : 0);
    make_interval_layers(w, h, layers);
    if (!s.skirts_ready) timer.time(kShadowMaps, [&] { s.build_skirts(); });
    timer.time(kShadowVolume, [&] {
      for (int layer = 0; layer < layers; ++layer) draw_layer(s, layer, w, h, stats);
      check_gl("shadow-volume intervals");
    });
  }

  void bind(ShaftRenderer::Impl& /*s*/, const ShaderProgram& /*p*/) const override {
    glBindTextureUnit(contract::UNIT_SV_NEAR, near_.id());
    glBindTextureUnit(contract::UNIT_SV_FAR, far_.id());
  }

  void describe(Image& img) const override {
    img.metadata["samples_per_ray"] = std::to_string(method_.steps) + " (in [tn, tf] only)";
    img.metadata["jitter"] = to_string(method_.jitter);
  }

 private:
  void make_interval_layers(int w, int h, int layers) {
    GLuint ids[2] = {0, 0};
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 2, ids);
    near_.reset(ids[0]);
    far_.reset(ids[1]);
    for (GLuint id : ids) {
      glTextureStorage3D(id, 1, GL_R32F, w, h, std::max(layers, 1));
      glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
  }

  void draw_layer(ShaftRenderer::Impl& s, int layer, int w, int h, ShaftFrameStats& stats) const {
    const ShaftRenderer::Impl::Skirts& sk = s.skirts[static_cast<std::size_t>(layer)];
    const std::size_t n_quads = sk.count;
    stats.skirt_quads += n_quads;
    stats.skirt_overflow = stats.skirt_overflow || sk.overflow;
    const GlFramebuffer fbo =
        make_framebuffer({{GL_COLOR_ATTACHMENT0, near_.id(), 0, layer}, {GL_COLOR_ATTACHMENT1, far_.id(), 0, layer}});
    const float near_clear[4] = {3.0e38f, 0, 0, 0};
    const float far_clear[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, near_clear);
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 1, far_clear);
    if (sk.overflow) {
      // Too many skirts: mark the whole ray ambiguous (sampled), which is always correct.
      const float zero[4] = {0, 0, 0, 0};
      const float huge[4] = {1.0e30f, 0, 0, 0};
      glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, zero);
      glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 1, huge);
      return;
    }
    if (n_quads == 0) return;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnablei(GL_BLEND, 0);
    glEnablei(GL_BLEND, 1);
    glBlendEquationi(0, GL_MIN);
    glBlendEquationi(1, GL_MAX);
    glBlendFunci(0, GL_ONE, GL_ONE);
    glBlendFunci(1, GL_ONE, GL_ONE);
    s.skirt_interval_program.use();
    glBindTextureUnit(contract::UNIT_SCENE_DISTANCE, s.distance.id());
    glBindVertexArray(sk.vao.id());
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(n_quads * 6));
    glDisablei(GL_BLEND, 0);
    glDisablei(GL_BLEND, 1);
    glBlendEquation(GL_FUNC_ADD);
  }

  GlTexture near_, far_;  // one layer per light: point lights, then the sun
};

}  // namespace

std::unique_ptr<ShaftMethodPass> make_shaft_method_pass(const ShaftMethod& method, const Scene& scene) {
  switch (method.kind) {
    case ShaftMethod::Kind::RayMarch:
      return std::make_unique<RayMarchPass>(method);
    case ShaftMethod::Kind::Analytic:
      if (method.airlight.kind == AirlightMethod::Table && scene.medium.phase.kind != PhaseKind::Isotropic)
        throw std::invalid_argument("method '" + to_string(method) +
                                    "': Sun et al.'s F table covers the isotropic phase only; this scene's phase is " +
                                    to_string(scene.medium.phase) + " (use analytic:stable)");
      return std::make_unique<AnalyticPass>(method);
    case ShaftMethod::Kind::ShadowVolume:
      return std::make_unique<ShadowVolumePass>(method);
    case ShaftMethod::Kind::Reference:
      break;
  }
  throw std::invalid_argument("method 'reference' is the CPU renderer (render_reference), not the GPU one");
}

}  // namespace nimbus::render::shaft_detail
