// The colours the viewer's panels (Ui*.cpp, Tools*.cpp) write errors and warnings in.
#pragma once

#include <imgui.h>

namespace sss::app {

inline const ImVec4 kErrorColor(1.0f, 0.4f, 0.4f, 1.0f);
inline const ImVec4 kWarningColor(1.0f, 0.85f, 0.3f, 1.0f);

}  // namespace sss::app
