#include "renderer/vk/GpuTimer.h"

#include "renderer/vk/Check.h"
#include "renderer/vk/Context.h"

#include <cstdio>
#include <stdexcept>

namespace sss::vk {

GpuTimer::GpuTimer(const Context& context, uint32_t max_scopes)
    : context_(&context), max_scopes_(max_scopes) {
  const DeviceInfo& info = context.info();
  if (info.timestamp_valid_bits == 0 || max_scopes == 0) return;  // labels only
  mask_ = info.timestamp_valid_bits >= 64 ? ~uint64_t{0}
                                          : (uint64_t{1} << info.timestamp_valid_bits) - 1;
  ns_per_tick_ = static_cast<double>(info.timestamp_period);

  VkQueryPoolCreateInfo create{};
  create.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  create.queryType = VK_QUERY_TYPE_TIMESTAMP;
  create.queryCount = 2 * max_scopes;
  VkQueryPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateQueryPool(context.device(), &create, nullptr, &pool));
  pool_ = QueryPoolHandle(context.device(), pool);
}

void GpuTimer::reset(VkCommandBuffer cmd) {
  if (!open_.empty()) throw std::logic_error("GpuTimer::reset: a scope is still open");
  recorded_.clear();
  overflowed_ = false;
  if (pool_) vkCmdResetQueryPool(cmd, pool_.get(), 0, 2 * max_scopes_);
}

void GpuTimer::begin(VkCommandBuffer cmd, std::string_view name) {
  context_->begin_label(cmd, name);
  if (!pool_ || recorded_.size() >= max_scopes_) {
    if (pool_ && !overflowed_) {
      std::fprintf(stderr,
                   "warning: GpuTimer: more than %u scopes in a frame; \"%.*s\" is not timed\n",
                   max_scopes_, static_cast<int>(name.size()), name.data());
      overflowed_ = true;
    }
    open_.push_back(kNoQuery);
    return;
  }
  const auto index = static_cast<uint32_t>(recorded_.size());
  recorded_.emplace_back(name);
  open_.push_back(index);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_.get(), 2 * index);
}

void GpuTimer::end(VkCommandBuffer cmd) {
  if (open_.empty()) throw std::logic_error("GpuTimer::end without begin");
  const uint32_t index = open_.back();
  open_.pop_back();
  if (index != kNoQuery) {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_.get(), 2 * index + 1);
  }
  context_->end_label(cmd);
}

const std::vector<PassTime>& GpuTimer::resolve() {
  if (!open_.empty()) throw std::logic_error("GpuTimer::resolve: a scope is still open");
  results_.clear();
  if (recorded_.empty()) return results_;

  std::vector<uint64_t> ticks(2 * recorded_.size());
  VK_CHECK(vkGetQueryPoolResults(context_->device(), pool_.get(), 0,
                                 static_cast<uint32_t>(ticks.size()),
                                 ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  for (std::size_t i = 0; i < recorded_.size(); ++i) {
    // Masked difference: correct across a wrap of a counter narrower than 64 bits.
    const uint64_t delta = (ticks[2 * i + 1] - ticks[2 * i]) & mask_;
    const double ms = static_cast<double>(delta) * ns_per_tick_ * 1e-6;
    PassTime* existing = nullptr;
    for (PassTime& p : results_) {
      if (p.name == recorded_[i]) existing = &p;
    }
    if (existing == nullptr) {
      results_.push_back({recorded_[i], ms, 1});
    } else {
      existing->ms += ms;
      ++existing->count;
    }
  }
  recorded_.clear();
  return results_;
}

std::optional<double> GpuTimer::milliseconds(std::string_view name) const {
  for (const PassTime& p : results_) {
    if (p.name == name) return p.ms;
  }
  return std::nullopt;
}

}  // namespace sss::vk
