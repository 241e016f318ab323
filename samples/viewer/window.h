// The GLFW window and its input: a window for OpenGL (a 4.3 core context, current) or Vulkan
// (no client API), per-frame mouse motion, scroll and key edges.
#pragma once
#include <array>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "sao/status.h"

struct GLFWwindow;

namespace sao::viewer {

enum class Api { OpenGL, Vulkan };

// What the mouse and keyboard did since the last pollEvents().
struct Input {
  glm::dvec2 mouseDelta{0, 0};
  double scroll = 0;
  bool left = false, right = false, middle = false;
};

class Window {
 public:
  static Status create(Api api, int width, int height, const std::string& title, std::unique_ptr<Window>& out);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }
  bool shouldClose() const;
  void requestClose();
  void setVsync(bool on);  // OpenGL only: swap interval 1 or 0
  void pollEvents();       // updates input() and the key edges
  void waitEvents();       // blocks until something happens (minimised windows)
  glm::ivec2 framebufferSize() const;
  const Input& input() const { return input_; }
  bool keyDown(int glfwKey) const;
  bool keyPressed(int glfwKey) const;  // went down during the last pollEvents()

 private:
  Window() = default;
  static void onScroll(GLFWwindow* window, double dx, double dy);
  GLFWwindow* window_ = nullptr;
  Input input_;
  double pendingScroll_ = 0;
  glm::dvec2 lastCursor_{0, 0};
  bool haveCursor_ = false;
  static constexpr int kKeys = 349;  // GLFW_KEY_LAST + 1
  std::array<bool, kKeys> down_{}, pressed_{};
};

}  // namespace sao::viewer
