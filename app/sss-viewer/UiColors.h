// The colours the viewer's panels (Ui*.cpp, Tools*.cpp) write errors and warnings in.
#pragma once

#include <imgui.h>

namespace sss::app {

inline const ImVec4 kErrorColor(1.0f, 0.4f, 0.4f, 1.0f);
inline const ImVec4 kWarningColor(1.0f, 0.85f, 0.3f, 1.0f);

// A message in `color`, wrapped at the panel's width: errors name a file or a field and
// say why, which is longer than a panel is wide (TextColored would clip it).
inline void colored_text_wrapped(const ImVec4& color, const char* text) {
  ImGui::PushStyleColor(ImGuiCol_Text, color);
  ImGui::TextWrapped("%s", text);
  ImGui::PopStyleColor();
}

}  // namespace sss::app
