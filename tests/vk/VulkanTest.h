// The fixture of the renderer/vk tests: a Context on lavapipe (or the device named by
// SSS_TEST_DEVICE; an empty value picks the best device) with the validation layer,
// core and synchronization checks. At the end of each test it waits for the device,
// destroys the Context and fails the test for every message the layer reported,
// including objects the test leaked (reported while the device is destroyed).
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
