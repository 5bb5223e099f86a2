// A Dear ImGui context for tests that draw the viewer's panels without a window: a 960x540
// display, no .ini file, the font atlas built (as a backend would), destroyed at scope end.
#pragma once

#include <imgui.h>

namespace sss::renderer::testing {

class HeadlessImGui {
 public:
  HeadlessImGui() {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(960, 540);
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  }
  ~HeadlessImGui() { ImGui::DestroyContext(); }
  HeadlessImGui(const HeadlessImGui&) = delete;
  HeadlessImGui& operator=(const HeadlessImGui&) = delete;

  ImGuiIO& io() { return ImGui::GetIO(); }
};

}  // namespace sss::renderer::testing
