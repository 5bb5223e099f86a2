// Helpers shared by the sss-fit commands.
#pragma once

#include "Commands.h"

#include "profiles/Profile.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace sss::app {

profiles::ModelOptions model_options(const CommonArgs& a);
// The model named by --model, or nullopt after printing the usage error.
std::optional<profiles::Model> resolve_model(const std::string& name);
nlohmann::json to_json(const Rgb& v);
// Writes `bytes` atomically; on failure prints the error and returns false.
bool write_output(const std::string& path, const std::string& bytes);
// A progress bar on stderr while a long job runs, only when stderr is a terminal.
void progress_bar(const char* what, double fraction);

}  // namespace sss::app
