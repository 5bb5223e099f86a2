// GPU time per pass, from timestamp queries, with a debug label of the same name
// (DESIGN.md §5: one pass name labels its debug marker, its timestamp query and its row
// in --stats).
//
// One GpuTimer per frame in flight. Each frame:
//
//   timer.reset(cmd);                        // first command, outside rendering
//   timer.begin(cmd, "sss blur");  ...  timer.end(cmd);
//   ... submit with the frame's fence ...
//   wait_for_fence(ctx, fence);              // next time this frame slot comes round
//   for (const PassTime& p : timer.resolve()) print(p.name, p.ms);
//
// Scopes nest (a label inside a label); scopes with the same name in one frame add up.
// Both timestamps are written at ALL_COMMANDS, so a scope measures its own commands
// from the completion of everything before it. On lavapipe the timestamps measure CPU
// time (1 ns period). Without timestamp support on the queue, the labels remain and
// resolve() returns no times.
#pragma once

#include "renderer/vk/Handle.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sss::vk {

class Context;

struct PassTime {
  std::string name;
  double ms = 0.0;     // summed over the scopes of this name
  uint32_t count = 0;  // how many scopes had this name
};

class GpuTimer {
 public:
  explicit GpuTimer(const Context& context, uint32_t max_scopes = 64);

  bool supported() const { return static_cast<bool>(pool_); }

  void reset(VkCommandBuffer cmd);
  void begin(VkCommandBuffer cmd, std::string_view name);
  void end(VkCommandBuffer cmd);

  // Reads the queries written since reset(); the command buffer that wrote them must
  // have completed (its fence waited on). Results are in order of first begin().
  // Throws std::logic_error while a scope is still open.
  const std::vector<PassTime>& resolve();
  const std::vector<PassTime>& results() const { return results_; }
  std::optional<double> milliseconds(std::string_view name) const;

  // begin() now, end() when it goes out of scope.
  class Scope {
   public:
    Scope(GpuTimer& timer, VkCommandBuffer cmd, std::string_view name) : timer_(timer), cmd_(cmd) {
      timer_.begin(cmd_, name);
    }
    ~Scope() { timer_.end(cmd_); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    GpuTimer& timer_;
    VkCommandBuffer cmd_;
  };
  [[nodiscard]] Scope scope(VkCommandBuffer cmd, std::string_view name) {
    return Scope(*this, cmd, name);
  }

 private:
  static constexpr uint32_t kNoQuery = UINT32_MAX;

  const Context* context_;
  QueryPoolHandle pool_;
  uint32_t max_scopes_;
  uint64_t mask_ = 0;  // timestampValidBits
  double ns_per_tick_ = 0.0;
  std::vector<std::string> recorded_;  // scope i uses queries 2i and 2i+1
  std::vector<uint32_t> open_;         // indices of open scopes (kNoQuery when untimed)
  bool overflowed_ = false;
  std::vector<PassTime> results_;
};

}  // namespace sss::vk
