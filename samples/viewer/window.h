// The GLFW window and its input: a window for OpenGL (a 4.3 core context, current) or Vulkan
// (no client API), per-frame mouse motion, scroll and key presses. Keys come from GLFW's key
// callback, queued between frames: at a few frames a second a press shorter than a frame still
// counts (polling glfwGetKey once a frame would miss it). The callback also feeds ImGui's GLFW
// backend, holding back a release that follows its press within one frame gap until the next
// pollEvents(), since ImGui 1.86 reads key state once a frame (a short Enter would not close a
// text field).
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

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
  // After ImGui's GLFW backend has installed its callbacks: puts the viewer's key callback in front
  // of ImGui's (which it then calls). Before this the viewer sees no keys.
  void takeKeyCallback();
  void pollEvents();       // updates input() and the key presses
  void waitEvents();       // blocks until something happens (minimised windows)
  glm::ivec2 framebufferSize() const;
  const Input& input() const { return input_; }
  // Held now, or pressed since the previous pollEvents() (a tap between two frames moves too).
  bool keyDown(int glfwKey) const;
  // The keys that went down since the previous pollEvents(), in order, each press once (however
  // short, and twice if pressed twice; key repeat not counted).
  const std::vector<int>& keyPresses() const { return presses_; }

 private:
  Window() = default;
  static void onScroll(GLFWwindow* window, double dx, double dy);
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  GLFWwindow* window_ = nullptr;
  Input input_;
  double pendingScroll_ = 0;
  glm::dvec2 lastCursor_{0, 0};
  bool haveCursor_ = false;
  static constexpr int kKeys = 349;  // GLFW_KEY_LAST + 1
  std::array<bool, kKeys> down_{};   // from the callback: pressed and not yet released
  std::vector<int> pending_, presses_;  // presses queued by the callback / of the last pollEvents()
  // ImGui's key callback, and the releases it gets at the next pollEvents() (key, scancode, mods).
  void (*imguiKey_)(GLFWwindow*, int, int, int, int) = nullptr;
  std::array<bool, kKeys> pressedSincePoll_{};
  std::vector<std::array<int, 3>> heldReleases_;
};

}  // namespace sao::viewer
