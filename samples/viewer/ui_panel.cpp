#include "ui_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

namespace sao::viewer {
namespace {

void sceneSection(UiState& s, const PanelInfo& info, CameraController& camera) {
  const auto names = scenes::builtinSceneNames();
  const std::string current = s.scene >= 0 ? std::string(names[std::size_t(s.scene)]) : s.sceneFile;
  if (ImGui::BeginCombo("scene", current.c_str())) {
    for (int i = 0; i < int(names.size()); ++i) {
      const std::string name(names[std::size_t(i)]);
      if (ImGui::Selectable(name.c_str(), i == s.scene) && i != s.scene) {
        s.scene = i;
        s.view = 0;
        s.sceneChanged = true;
      }
    }
    ImGui::EndCombo();
  }
  if (info.scene && !info.scene->views.empty()) {
    const auto& views = info.scene->views;
    if (ImGui::BeginCombo("view", views[std::size_t(s.view)].name.c_str())) {
      for (int i = 0; i < int(views.size()); ++i)
        if (ImGui::Selectable(views[std::size_t(i)].name.c_str(), i == s.view)) {
          s.view = i;
          s.resetCamera = true;
        }
      ImGui::EndCombo();
    }
  }
  int mode = camera.mode == CameraController::Mode::Orbit ? 0 : 1;
  ImGui::RadioButton("orbit", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("fly (Tab)", &mode, 1);
  camera.mode = mode == 0 ? CameraController::Mode::Orbit : CameraController::Mode::Fly;
  ImGui::SameLine();
  if (ImGui::Button("reset camera")) s.resetCamera = true;
  ImGui::Checkbox("orthographic (O)", &camera.orthographic);
  float speed = float(camera.speed);
  if (ImGui::SliderFloat("move speed [m/s]", &speed, 0.1f, 50.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
    camera.speed = speed;
  ImGui::TextDisabled(camera.orthographic ? "drag: rotate, right drag: pan, wheel: zoom (orbit), WASD QE: move"
                                           : "drag: rotate, right drag: pan, wheel: dolly, WASD QE: move");
}

void viewSection(UiState& s, const FrameStats* stats) {
  const auto modes = viewModes();
  const std::string current(modes[std::size_t(s.mode)].label);
  if (ImGui::BeginCombo("view mode", current.c_str())) {
    for (const auto& m : modes) {
      const std::string label(m.label);
      if (ImGui::Selectable(label.c_str(), m.mode == s.mode)) s.mode = m.mode;
    }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("keys 1-9");
  if (s.mode == ViewMode::Split || s.mode == ViewMode::SplitResolution)
    ImGui::SliderFloat("split", &s.split, 0.0f, 1.0f, "%.2f");
  if (s.mode == ViewMode::SplitResolution)
    ImGui::TextDisabled("AO: divisor 1 | %d (the panel's, or 2)", reducedDivisor(s.settings));
  if (s.mode == ViewMode::ZMip) {
    const int levels = stats && stats->effect.ok() ? int(stats->plan.cszLevels) : 1;
    ImGui::SliderInt("z MIP level", &s.cszLevel, 0, std::max(levels - 1, 0));
  }
  if (s.mode == ViewMode::Error) ImGui::SliderFloat("error at full heat", &s.errorScale, 0.01f, 1.0f, "%.2f");
}

void referenceSection(UiState& s, const PanelInfo& info) {
  ImGui::SliderInt("rays per pixel", &s.referenceRays, 4, 512, "%d", ImGuiSliderFlags_Logarithmic);
  if (ImGui::Button("Compute reference (R)")) s.computeReference = true;
  ImGui::TextWrapped("%s", info.referenceStatus.c_str());
  if (info.haveMetrics) {
    // An undefined metric (NaN, sao/samples/metrics.h) reads "n/a", never "nan".
    auto shown = [](double v, const char* format) {
      if (!samples::isDefined(v)) return std::string("n/a");
      char text[32];
      std::snprintf(text, sizeof text, format, v);
      return std::string(text);
    };
    const auto& m = info.metrics.raw;
    ImGui::Text("RMSE %s  bias %s  SSIM %s", shown(m.rmse, "%.4f").c_str(), shown(m.meanBias, "%+.4f").c_str(),
                shown(m.ssim, "%.3f").c_str());
    ImGui::Text("fitted intensity %s -> RMSE %s", shown(info.metrics.fittedIntensity, "%.3f").c_str(),
                shown(info.metrics.fitted.rmse, "%.4f").c_str());
  }
}

void timingSection(UiState& s, const FrameStats& stats) {
  ImGui::Checkbox("measure", &s.measureTime);
  if (stats.timings.method != TimingMethod::None) {
    ImGui::SameLine();
    ImGui::TextDisabled("(%s)", toString(stats.timings.method));
  }
  if (!stats.timingNote.empty()) ImGui::TextDisabled("%s", stats.timingNote.c_str());
  if (stats.compare.active && stats.compare.timings.method != TimingMethod::None)
    ImGui::TextDisabled("split-resolution's second effect (divisor %d): %.3f ms",
                        compareSettings(s.settings).resolution_divisor, stats.compare.timings.totalMilliseconds());
  if (stats.timings.method == TimingMethod::None) return;
  if (ImGui::BeginTable("timings", 2, ImGuiTableFlags_RowBg)) {
    // Set widths: auto-fitted columns start at zero width in the table's first frame.
    ImGui::TableSetupColumn("pass", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableSetupColumn("ms", ImGuiTableColumnFlags_WidthFixed, ImGui::CalcTextSize("0000.000 ms").x);
    for (const auto& p : stats.timings.passes) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(p.pass.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%8.3f ms", p.milliseconds);
    }
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted("total");
    ImGui::TableNextColumn();
    ImGui::Text("%8.3f ms", stats.timings.totalMilliseconds());
    ImGui::EndTable();
  }
}

void planSection(const FrameStats& stats, std::uint64_t fullBytes) {
  const Plan& p = stats.plan;
  std::ostringstream passes;
  for (const auto& pass : p.passes) passes << (passes.tellp() > 0 ? " " : "") << gen::pass(pass.pass).name;
  ImGui::TextWrapped("passes: %s", passes.str().c_str());
  ImGui::Text("input %ux%u, AO %ux%u, z MIP levels %u", p.inputExtent.width, p.inputExtent.height, p.aoExtent.width,
              p.aoExtent.height, p.cszLevels);
  ImGui::Text("%.2f MiB (a naive allocation: %.2f MiB)", double(p.totalBytes) / 1048576.0, double(fullBytes) / 1048576.0);
  if (!ImGui::TreeNode("images")) return;
  if (ImGui::BeginTable("images", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
    for (const auto& image : p.images) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      const auto name = gen::kResources[std::size_t(image.resource)].name;
      ImGui::Text("%.*s", int(name.size()), name.data());
      ImGui::TableNextColumn();
      ImGui::Text("%ux%u x%u", image.extent.width, image.extent.height, image.mipLevels);
      ImGui::TableNextColumn();
      ImGui::Text("%.1f KiB", double(image.bytes) / 1024.0);
    }
    ImGui::EndTable();
  }
  ImGui::TreePop();
}

}  // namespace

void drawPanel(UiState& s, const PanelInfo& info, CameraController& camera) {
  // Narrow enough to leave most of the window to the scene (framed for the rest, framing.h), wide
  // enough for the settings' labels: 0.28 of the width, 260-360 px (358 px at 1280x720).
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float width = std::clamp(0.28f * display.x, std::min(260.0f, display.x - 16), 360.0f);
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(width, display.y - 16), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.82f);
  const bool open = ImGui::Begin("sao-viewer (H hides)");
  s.panelShown = open && display.x > 0;
  if (s.panelShown) {
    s.panelX0 = ImGui::GetWindowPos().x / display.x;
    s.panelX1 = (ImGui::GetWindowPos().x + ImGui::GetWindowSize().x) / display.x;
  }
  if (!open) {
    ImGui::End();
    return;
  }
  ImGui::PushItemWidth(-150.0f);
  // The backend in one line (clipped at the panel's edge: the widgets below keep their places
  // whatever the driver's name), all of it with the depth conventions on hover.
  const std::size_t cut = info.backend.find("; ");
  ImGui::TextUnformatted(info.backend.substr(0, cut).c_str());
  if (ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 35.0f);
    ImGui::TextUnformatted(info.backend.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
  ImGui::Text("%.1f ms/frame (%.1f fps)", info.frameMs, info.frameMs > 0 ? 1000.0 / info.frameMs : 0.0);
  ImGui::SameLine();
  if (ImGui::SmallButton("Screenshot (F12)")) s.screenshot = true;
  if (!info.message.empty()) ImGui::TextWrapped("%s", info.message.c_str());
  const ImVec4 red(1, 0.4f, 0.3f, 1), orange(1, 0.7f, 0.2f, 1);
  auto wrappedColored = [](const ImVec4& color, const std::string& text) {
    ImGui::PushStyleColor(ImGuiCol_Text, color);
    ImGui::TextWrapped("%s", text.c_str());
    ImGui::PopStyleColor();
  };
  if (info.stats && !info.stats->effect.ok()) wrappedColored(red, "effect: " + info.stats->effect.message);
  if (info.stats && info.stats->compare.active && !info.stats->compare.effect.ok())
    wrappedColored(red, "split-resolution's second effect: " + info.stats->compare.effect.message);
  if (info.scaleWarnings)
    for (const std::string& w : *info.scaleWarnings) wrappedColored(orange, "warning: " + w);
  // What a user reads while tuning stays on top: the view mode, the timings and the plan; the long
  // lists (settings, scene, reference) go in tabs below, scrolling on their own.
  viewSection(s, info.stats);
  if (info.stats && ImGui::CollapsingHeader("Per-pass timings", ImGuiTreeNodeFlags_DefaultOpen))
    timingSection(s, *info.stats);
  if (info.stats && info.stats->effect.ok() && ImGui::CollapsingHeader("Plan", ImGuiTreeNodeFlags_DefaultOpen))
    planSection(*info.stats, info.fullBytes);
  s.topSectionsEndY = ImGui::GetCursorScreenPos().y;
  s.displayHeight = display.y;
  const bool enteredError = s.mode == ViewMode::Error && s.panelMode != ViewMode::Error;
  s.panelMode = s.mode;
  if (ImGui::BeginTabBar("sections")) {
    auto tab = [](const char* name, ImGuiTabItemFlags flags, auto&& body) {
      if (!ImGui::BeginTabItem(name, nullptr, flags)) return;
      ImGui::BeginChild(name);  // the rest of the panel's height, scrolled on its own
      // Sliders 140 px wide: the rest for the longest label ("blur_edge_sharpness [1/m]") and
      // the preset row's "Reset to defaults".
      ImGui::PushItemWidth(140.0f);
      body();
      ImGui::PopItemWidth();
      ImGui::EndChild();
      ImGui::EndTabItem();
    };
    tab("Settings", 0, [&] { drawSettingsPanel(s.settings, s.settingsPanel); });
    tab("Scene and camera", 0, [&] { sceneSection(s, info, camera); });
    tab("Reference", enteredError ? ImGuiTabItemFlags_SetSelected : 0, [&] { referenceSection(s, info); });
    ImGui::EndTabBar();
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

namespace {

// "full resolution (divisor 1), 1.234 ms": the divisor and, when measured, the effect's total time.
std::string halfLabel(const char* what, int divisor, const Status& effect, const Timings& timings) {
  char text[96];
  if (!effect.ok())
    std::snprintf(text, sizeof text, "%s (divisor %d): failed", what, divisor);
  else if (timings.method != TimingMethod::None)
    std::snprintf(text, sizeof text, "%s (divisor %d), AO %.3f ms", what, divisor, timings.totalMilliseconds());
  else
    std::snprintf(text, sizeof text, "%s (divisor %d)", what, divisor);
  return text;
}

// The error view's colour bar (drawn by the composite at errorLegend()): a frame, the values of
// its bottom, middle and top, and what it shows.
void legendLabels(float errorScale) {
  const ImGuiIO& io = ImGui::GetIO();
  const ImVec2 scale = io.DisplayFramebufferScale;
  if (scale.x <= 0 || scale.y <= 0) return;
  const int fbWidth = int(io.DisplaySize.x * scale.x), fbHeight = int(io.DisplaySize.y * scale.y);
  const LegendRect r = errorLegend(fbWidth, fbHeight);
  // Framebuffer rows count from the bottom, ImGui's from the top.
  const float x0 = float(r.x0) / scale.x, x1 = float(r.x1) / scale.x;
  const float top = float(fbHeight - r.y1) / scale.y, bottom = float(fbHeight - r.y0) / scale.y;
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const ImU32 color = IM_COL32(255, 255, 255, 230), shadow = IM_COL32(0, 0, 0, 200);
  draw->AddRect(ImVec2(x0 - 1, top - 1), ImVec2(x1 + 1, bottom + 1), IM_COL32(160, 160, 160, 255));
  auto label = [&](const std::string& text, float x, float y) {
    draw->AddText(ImVec2(x + 1, y + 1), shadow, text.c_str());
    draw->AddText(ImVec2(x, y), color, text.c_str());
  };
  const float h = ImGui::GetFontSize();
  char text[32];
  for (const double f : {0.0, 0.5, 1.0}) {
    std::snprintf(text, sizeof text, f == 1.0 ? ">=%.2f" : "%.2f", f * errorScale);
    const float y = bottom - float(f) * (bottom - top) - 0.5f * h;
    label(text, x0 - 6 - ImGui::CalcTextSize(text).x, y);
  }
  const char* caption = "|AO - ref|";
  label(caption, x1 - ImGui::CalcTextSize(caption).x, top - h - 4);
}

}  // namespace

void drawOverlay(const FrameDesc& frame, const UiState& s, const FrameStats* stats) {
  if (s.mode == ViewMode::Error && frame.referenceValid) legendLabels(float(frame.errorScale));
  if (s.mode != ViewMode::Split && s.mode != ViewMode::SplitResolution) return;
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  const float x = std::floor(float(frame.splitFraction) * size.x), y = size.y - ImGui::GetFontSize() - 8.0f;
  std::string left = "without AO", right = "with AO";
  if (s.mode == ViewMode::SplitResolution) {
    // The main effect runs the panel's divisor, the second one the other side's.
    const bool mainIsFull = s.settings.resolution_divisor == 1;
    const Status none;
    const Timings noTimes;
    const CompareStats noCompare;
    const CompareStats& c = stats && stats->compare.active ? stats->compare : noCompare;
    const Status& mainStatus = stats ? stats->effect : none;
    const Timings& mainTimes = stats ? stats->timings : noTimes;
    left = halfLabel("full resolution", 1, mainIsFull ? mainStatus : c.effect, mainIsFull ? mainTimes : c.timings);
    right = halfLabel("reduced", reducedDivisor(s.settings), mainIsFull ? c.effect : mainStatus,
                      mainIsFull ? c.timings : mainTimes);
  }
  const ImU32 color = IM_COL32(255, 255, 255, 230), shadow = IM_COL32(0, 0, 0, 160);
  const float w = ImGui::CalcTextSize(left.c_str()).x;
  for (auto [text, px] : {std::pair{&left, x - w - 8.0f}, std::pair{&right, x + 8.0f}}) {
    draw->AddText(ImVec2(px + 1, y + 1), shadow, text->c_str());
    draw->AddText(ImVec2(px, y), color, text->c_str());
  }
}

}  // namespace sao::viewer
