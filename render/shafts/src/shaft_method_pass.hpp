// Each GPU shaft method as a pass object: what it does before the shaft pass (the shadow-volume
// method's per-pixel intervals), what it binds for shaders/shafts.frag.glsl (its METHOD define
// picks the integrator), and the metadata it adds. Private to render/shafts/src/shaft_*.cpp.
#pragma once
#include <memory>

#include "nimbus/render/core/image.hpp"
#include "nimbus/render/scene/scene.hpp"
#include "nimbus/render/media/shaft_method.hpp"
#include "shaft_renderer_impl.hpp"

namespace nimbus::render::shaft_detail {

class ShaftMethodPass {
 public:
  explicit ShaftMethodPass(const ShaftMethod& method) : method_(method) {}
  virtual ~ShaftMethodPass() = default;
  const ShaftMethod& method() const { return method_; }

  // Work before the shaft pass for a w x h frame, timed in the timer's own slots.
  virtual void prepare(ShaftRenderer::Impl& /*s*/, int /*w*/, int /*h*/, GpuTimer& /*timer*/,
                       ShaftFrameStats& /*stats*/) {}
  // The method's textures and uniforms on the bound shaft program p.
  virtual void bind(ShaftRenderer::Impl& /*s*/, const ShaderProgram& /*p*/) const {}
  // The method's metadata keys.
  virtual void describe(Image& /*image*/) const {}

 protected:
  ShaftMethod method_;
};

// The pass of a GPU method. Throws std::invalid_argument for Reference (the CPU renderer) and for
// Sun et al.'s F table with a phase other than the isotropic one.
std::unique_ptr<ShaftMethodPass> make_shaft_method_pass(const ShaftMethod& method, const Scene& scene);

}  // namespace nimbus::render::shaft_detail
