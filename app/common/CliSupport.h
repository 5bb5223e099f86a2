// Small pieces every executable's main() needs alike (DESIGN.md §4): the usage error
// (message, a pointer to --help, exit 2), parsing with it, and the lower-cased
// extension of a file name.
#pragma once

#include "ExitCodes.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <iostream>
#include <optional>
#include <string>

namespace sss::app {

// "TOOL: error: MESSAGE" and "Run 'TOOL --help' for usage." on stderr; returns 2.
inline int usage_error(const std::string& tool, const std::string& message) {
  std::cerr << tool << ": error: " << message << "\nRun '" << tool << " --help' for usage.\n";
  return kExitUsage;
}

// Parses the command line. Returns the code to exit with when main() must stop (--help
// printed: 0; bad usage: 2, reported by usage_error), or nothing to go on.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv,
                                             const std::string& tool) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --help-all, --version: printed, exit 0
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return usage_error(tool, e.what());
  }
  return std::nullopt;
}

// ".png" for "A/B.PNG"; empty when the name has no dot.
inline std::string lower_extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return {};
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace sss::app
