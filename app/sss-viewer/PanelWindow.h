// What the viewer's two ImGui windows (the material panel, Ui.cpp, and Tools, Tools.cpp)
// share in how they open.
#pragma once

#include <imgui.h>
#include <imgui_internal.h>

namespace sss::app {

// Call after ImGui::Begin() with what it returned: a click on the collapsed window's title
// opens it. ImGui opens a window only on a double click or on its arrow, and users click
// the title. A drag that moves the window is not a click.
inline void open_on_title_click(bool shown) {
  if (!shown && ImGui::IsWindowHovered() && ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
      ImGui::GetCurrentWindow()->TitleBarRect().Contains(ImGui::GetIO().MousePos) &&
      ImGui::GetMouseDragDelta(ImGuiMouseButton_Left).x == 0.0f &&
      ImGui::GetMouseDragDelta(ImGuiMouseButton_Left).y == 0.0f)
    ImGui::SetWindowCollapsed(false);
}

}  // namespace sss::app
