// The OpenGL prepass: needs GL 4.5 (direct state access, glClipControl for [0, 1] clip depth).
// Either owns a headless EGL debug context (the default: create() leaves it current on the calling
// thread; render() and the destructor make it current and then put back the EGL context that was
// current before) or works in the context current on the calling thread, whose GL state it saves
// and restores around render().
#pragma once
#include <memory>

#include "sao/gl/headless.h"
#include "sao/prepass/prepass.h"

namespace sao::prepass {

struct GlPrepassOptions {
  // false: use the context current on the calling thread (GL 4.5 core), which must also be
  // current when render() is called and when the GlPrepass is destroyed.
  bool ownContext = true;
  bool debug = true;       // with ownContext: a debug context collecting KHR_debug messages
};

class GlPrepass final : public Prepass {
 public:
  static Status create(std::unique_ptr<GlPrepass>& out, const GlPrepassOptions& options = {});
  ~GlPrepass() override;  // with ownContext it makes its context current to delete its objects
  GlPrepass(const GlPrepass&) = delete;
  GlPrepass& operator=(const GlPrepass&) = delete;

  std::string_view name() const override { return "gl"; }
  std::string description() const override { return description_; }
  bool supportsClip(ClipDepth) const override { return true; }  // [-1, 1] natively, [0, 1] by glClipControl
  Status render(const scenes::Mesh& mesh, const scenes::View& view, const Camera& camera,
                const PrepassOptions& options, PrepassResult& out) override;

  // The owned context (debug messages for tests), or nullptr in the caller's context.
  gl::HeadlessContext* context() { return context_.get(); }

 private:
  GlPrepass() = default;
  struct Objects;
  Status init();
  Status uploadMesh(const scenes::Mesh& mesh, std::uint64_t digest);
  Status ensureTargets(Extent extent, DepthFormat format, bool secondLayer);
  std::unique_ptr<gl::HeadlessContext> context_;
  std::unique_ptr<Objects> gl_;
  std::string description_;
};

}  // namespace sao::prepass
