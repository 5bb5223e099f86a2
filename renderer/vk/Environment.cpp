#include "renderer/vk/Environment.h"

#include <charconv>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace sss::vk {

namespace {
constexpr const char* kChecksVariable = "SSS_VALIDATION_CHECKS";
constexpr const char* kFailVariable = "SSS_FAIL_ALLOCATION_AFTER";

std::optional<std::string_view> variable(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr || *value == '\0') return std::nullopt;
  return std::string_view(value);
}
}  // namespace

std::string_view validation_checks_name(ValidationChecks checks) {
  switch (checks) {
    case ValidationChecks::Core: return "core";
    case ValidationChecks::Sync: return "sync";
    case ValidationChecks::BestPractices: return "best-practices";
  }
  return "unknown";
}

ValidationChecks parse_validation_checks(std::string_view text) {
  for (ValidationChecks c :
       {ValidationChecks::Core, ValidationChecks::Sync, ValidationChecks::BestPractices}) {
    if (text == validation_checks_name(c)) return c;
  }
  throw std::invalid_argument(std::string(kChecksVariable) + "=" + std::string(text) +
                              ": expected core, sync or best-practices");
}

std::optional<ValidationChecks> validation_checks_from_environment() {
  const std::optional<std::string_view> value = variable(kChecksVariable);
  if (!value) return std::nullopt;
  return parse_validation_checks(*value);
}

uint64_t parse_allocation_limit(std::string_view text, std::string_view name) {
  uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, error] = std::from_chars(text.data(), end, value);
  if (text.empty() || error != std::errc() || ptr != end) {
    throw std::invalid_argument(std::string(name) + "=" + std::string(text) +
                                ": expected a number of allocations (a non-negative integer)");
  }
  return value;
}

std::optional<uint64_t> fail_allocation_after_from_environment() {
  const std::optional<std::string_view> value = variable(kFailVariable);
  if (!value) return std::nullopt;
  return parse_allocation_limit(*value, kFailVariable);
}

}  // namespace sss::vk
