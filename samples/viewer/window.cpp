#include "window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <utility>

namespace sao::viewer {
namespace {

void onGlfwError(int code, const char* text) { std::fprintf(stderr, "sao-viewer: GLFW error %d: %s\n", code, text); }

}  // namespace

static_assert(GLFW_KEY_LAST + 1 == 349);

Status Window::create(Api api, int width, int height, const std::string& title, std::unique_ptr<Window>& out) {
  glfwSetErrorCallback(onGlfwError);
  if (!glfwInit()) return Status::error(StatusCode::DriverError, "cannot initialise GLFW (is DISPLAY set?)");
  std::unique_ptr<Window> w(new Window());
  glfwDefaultWindowHints();
  if (api == Api::OpenGL) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_DEPTH_BITS, 0);  // the prepass renders into its own depth texture
  } else {
    if (!glfwVulkanSupported()) {
      glfwTerminate();
      return Status::error(StatusCode::DriverError, "GLFW found no Vulkan loader");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  }
  w->window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!w->window_) {
    glfwTerminate();
    return Status::error(StatusCode::DriverError, api == Api::OpenGL
                                                      ? "cannot create a window with an OpenGL 4.3 core context"
                                                      : "cannot create a window for Vulkan");
  }
  if (api == Api::OpenGL) glfwMakeContextCurrent(w->window_);
  glfwSetWindowUserPointer(w->window_, w.get());
  // Installed before ImGui's GLFW backend, which chains to it; the key callback goes in front of
  // ImGui's later (takeKeyCallback).
  glfwSetScrollCallback(w->window_, onScroll);
  out = std::move(w);
  return Status::success();
}

Window::~Window() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

void Window::onScroll(GLFWwindow* window, double, double dy) {
  if (auto* self = static_cast<Window*>(glfwGetWindowUserPointer(window))) self->pendingScroll_ += dy;
}

void Window::takeKeyCallback() { imguiKey_ = glfwSetKeyCallback(window_, onKey); }

void Window::onKey(GLFWwindow* window, int key, int scancode, int action, int mods) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(window));
  if (!self) return;
  const bool known = key >= 0 && key < kKeys;  // not GLFW_KEY_UNKNOWN
  if (known && action == GLFW_PRESS) {
    self->down_[std::size_t(key)] = true;
    self->pressedSincePoll_[std::size_t(key)] = true;
    self->pending_.push_back(key);
  } else if (known && action == GLFW_RELEASE) {
    self->down_[std::size_t(key)] = false;
    if (self->pressedSincePoll_[std::size_t(key)]) {  // ImGui has not seen it down yet
      self->heldReleases_.push_back({key, scancode, mods});
      return;
    }
  }
  if (self->imguiKey_) self->imguiKey_(window, key, scancode, action, mods);
}

bool Window::shouldClose() const { return glfwWindowShouldClose(window_); }
void Window::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void Window::setVsync(bool on) { glfwSwapInterval(on ? 1 : 0); }
void Window::waitEvents() { glfwWaitEvents(); }

void Window::pollEvents() {
  // ImGui saw these keys down for a frame: now they go up.
  for (const auto& [key, scancode, mods] : std::exchange(heldReleases_, {}))
    if (imguiKey_) imguiKey_(window_, key, scancode, GLFW_RELEASE, mods);
  pressedSincePoll_ = {};
  glfwPollEvents();
  input_ = {};
  input_.scroll = pendingScroll_;
  pendingScroll_ = 0;
  glm::dvec2 cursor;
  glfwGetCursorPos(window_, &cursor.x, &cursor.y);
  if (haveCursor_) input_.mouseDelta = cursor - lastCursor_;
  lastCursor_ = cursor;
  haveCursor_ = true;
  input_.left = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  input_.right = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  input_.middle = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
  // Presses queued since the last poll, waitEvents() included.
  presses_.swap(pending_);
  pending_.clear();
}

glm::ivec2 Window::framebufferSize() const {
  glm::ivec2 s;
  glfwGetFramebufferSize(window_, &s.x, &s.y);
  return s;
}

bool Window::keyDown(int key) const {
  if (key < 0 || key >= kKeys) return false;
  return down_[std::size_t(key)] || std::find(presses_.begin(), presses_.end(), key) != presses_.end();
}

}  // namespace sao::viewer
