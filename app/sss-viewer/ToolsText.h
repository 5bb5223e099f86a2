// Small text and file helpers the Tools window's parts share (Tools.cpp, ToolsExport.cpp).
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>

namespace sss::app::tools_text {

inline void copy_to(char* dst, std::size_t size, const std::string& s) {
  std::snprintf(dst, size, "%s", s.c_str());
}

inline bool exists(const std::string& path) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

inline bool is_builtin(const std::string& source) { return source.rfind("builtin:", 0) == 0; }

inline std::string file_stem(const std::string& source) {
  if (is_builtin(source)) return source.substr(8);
  return std::filesystem::path(source).stem().string();
}

}  // namespace sss::app::tools_text
