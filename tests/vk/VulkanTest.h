// The fixture of the renderer/vk tests: a Context on lavapipe (or the device named by
// SSS_TEST_DEVICE; an empty value picks the best device) with the validation layer.
// Which checks: SSS_VALIDATION_CHECKS=core|sync|best-practices when set (the three
// separate runs of scripts/test-validation.sh; renderer/vk/Environment.h), otherwise
// core + synchronization, so that the ordinary test run keeps catching hazards as it
// always did. At the end of each test it waits for the device, destroys the Context and
// fails the test for every message the layer reported, including objects the test
// leaked (reported while the device is destroyed).
#pragma once

#include "renderer/vk/Context.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

namespace sss::vk::testing {

inline std::string test_device_name() {
  const char* env = std::getenv("SSS_TEST_DEVICE");
  return env != nullptr ? std::string(env) : std::string("llvmpipe");
}

inline ContextOptions validated_options() {
  ContextOptions options;
  options.enable_validation = true;
  options.sync_validation = true;
  options.device_name = test_device_name();
  return options;
}

// Sets (value == nullptr: unsets) an environment variable for one scope and restores it
// (ctest runs each test in its own process, so nothing else sees the change).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) {
      old_ = old;
      had_ = true;
    }
    if (value != nullptr) {
      ::setenv(name, value, 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (had_) {
      ::setenv(name_, old_.c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

class VulkanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    log_ = std::make_shared<ValidationLog>();
    ContextOptions options = validated_options();
    options.validation_log = log_;
    ctx_ = std::make_unique<Context>(options);
  }

  void TearDown() override {
    if (ctx_) {
      ctx_->wait_idle();
      ctx_.reset();
    }
    for (const ValidationMessage& m : log_->messages()) ADD_FAILURE() << to_string(m);
  }

  Context& ctx() { return *ctx_; }
  // Messages so far; a test that provokes some on purpose clears them.
  ValidationLog& log() { return *log_; }

 private:
  std::shared_ptr<ValidationLog> log_;
  std::unique_ptr<Context> ctx_;
};

}  // namespace sss::vk::testing
