// The environment variables that renderer/vk reads, all in one place (Environment.cpp),
// so that tests, the viewer and the scripts that launch them select the same behaviour.
//
//   SSS_VALIDATION_CHECKS=core|sync|best-practices
//     Which checks the validation layer runs when a Context asks for it
//     (ContextOptions::enable_validation). One mode per run, because the issue asks for
//     three separate clean runs (scripts/test-validation.sh): "core" (the layer's
//     default checks), "sync" (core + synchronization validation), "best-practices"
//     (core + best practices). Unset: the caller's own ContextOptions decide.
//
//   SSS_FAIL_ALLOCATION_AFTER=N
//     After N successful device-memory allocations through allocate_memory (Memory.cpp,
//     the one place that calls vkAllocateMemory), every further allocation of that
//     Context fails as if vkAllocateMemory had returned VK_ERROR_OUT_OF_DEVICE_MEMORY.
//     For testing out-of-memory handling (the viewer, the soak). Unset: no limit.
//
// A malformed value is refused with std::invalid_argument naming the variable and the
// value (not ignored: a typo must not silently run a test without what it asked for).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace sss::vk {

enum class ValidationChecks { Core, Sync, BestPractices };

std::string_view validation_checks_name(ValidationChecks checks);
// "core", "sync" or "best-practices"; throws std::invalid_argument otherwise.
ValidationChecks parse_validation_checks(std::string_view text);
// SSS_VALIDATION_CHECKS, or nullopt when it is unset or empty.
std::optional<ValidationChecks> validation_checks_from_environment();

// A non-negative decimal integer; throws std::invalid_argument naming `variable`.
uint64_t parse_allocation_limit(std::string_view text, std::string_view variable);
// SSS_FAIL_ALLOCATION_AFTER, or nullopt when it is unset or empty.
std::optional<uint64_t> fail_allocation_after_from_environment();

}  // namespace sss::vk
