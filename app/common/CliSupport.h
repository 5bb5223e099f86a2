// Small pieces every executable's main() needs alike (DESIGN.md §4): the usage error
// (message, a pointer to --help, exit 2), the input error (a file that does not load:
// exit 2, no pointer to --help, which would not help), parsing with a suggestion for a
// mistyped option or subcommand, messages printed once, and the lower-cased extension of
// a file name.
#pragma once

#include "ExitCodes.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <iostream>
#include <optional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace sss::app {

// "TOOL: error: MESSAGE" and "Run 'TOOL --help' for usage." on stderr; returns 2.
inline int usage_error(const std::string& tool, const std::string& message) {
  std::cerr << tool << ": error: " << message << "\nRun '" << tool << " --help' for usage.\n";
  return kExitUsage;
}

// "TOOL: error: MESSAGE" on stderr; returns 2. For input that does not load (a missing or
// malformed file): the message names the file and the field, and --help would not help.
inline int input_error(const std::string& tool, const std::string& message) {
  std::cerr << tool << ": error: " << message << '\n';
  return kExitUsage;
}

// Levenshtein distance, for "did you mean".
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The nearest of `candidates` to `word` within a third of its length (at least 2 edits),
// or empty.
inline std::string nearest_name(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

// After a parse error: "did you mean '--gaussians'?" for an option that no command in
// reach knows, or "did you mean 'fit'?" for a mistyped subcommand; empty otherwise.
inline std::string command_line_suggestion(CLI::App& app, int argc, char** argv) {
  std::vector<CLI::App*> scopes{&app};
  std::vector<std::string> subcommands;
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) subcommands.push_back(sub->get_name());
  const std::vector<CLI::App*> parsed = app.get_subcommands();
  for (CLI::App* sub : parsed) scopes.push_back(sub);
  std::vector<std::string> options;
  for (CLI::App* scope : scopes)
    for (const CLI::Option* o : scope->get_options())
      for (const std::string& name : o->get_lnames()) options.push_back("--" + name);
  bool positional_seen = false;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg.rfind("--", 0) == 0) {
      arg = arg.substr(0, arg.find('='));
      if (std::find(options.begin(), options.end(), arg) != options.end()) continue;
      if (const std::string n = nearest_name(arg, options); !n.empty())
        return "did you mean '" + n + "' for '" + arg + "'?";
      continue;
    }
    if (!positional_seen && parsed.empty() && !subcommands.empty() && arg[0] != '-') {
      positional_seen = true;
      if (std::find(subcommands.begin(), subcommands.end(), arg) != subcommands.end()) continue;
      const std::string n = nearest_name(arg, subcommands);
      if (n.empty()) continue;
      std::string all;
      for (const std::string& c : subcommands) all += (all.empty() ? "" : ", ") + c;
      return "did you mean '" + n + "' for '" + arg + "'? (commands: " + all + ")";
    }
  }
  return {};
}

// Parses the command line. Returns the code to exit with when main() must stop (--help
// printed: 0; bad usage: 2, reported by usage_error with a suggestion where one is near),
// or nothing to go on.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv,
                                             const std::string& tool) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --help-all, --version: printed, exit 0
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const std::string hint = command_line_suggestion(app, argc, argv);
    return usage_error(tool, std::string(e.what()) + (hint.empty() ? "" : "; " + hint));
  }
  return std::nullopt;
}

// "TOOL: LEVEL: MESSAGE" on stderr for each distinct message, in first-seen order, with
// "(N times)" after one that came more than once.
inline void print_messages(const std::string& tool, const char* level,
                           const std::vector<std::string>& messages) {
  std::map<std::string, int> count;
  for (const std::string& m : messages) ++count[m];
  for (const std::string& m : messages) {
    auto it = count.find(m);
    if (it == count.end()) continue;  // printed already
    std::cerr << tool << ": " << level << ": " << m;
    if (it->second > 1) std::cerr << " (" << it->second << " times)";
    std::cerr << '\n';
    count.erase(it);
  }
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
