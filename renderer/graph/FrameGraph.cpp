#include "renderer/graph/FrameGraph.h"

#include "renderer/vk/GpuTimer.h"
#include "renderer/vk/Image.h"

#include <algorithm>
#include <stdexcept>

namespace sss::renderer::graph {

namespace {

constexpr VkAccessFlags2 kWriteBits =
    VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;

vk::Scope scope_of(const Access& a) { return {a.stages, a.access}; }

vk::Scope& operator|=(vk::Scope& a, const vk::Scope& b) {
  a.stages |= b.stages;
  a.access |= b.access;
  return a;
}

bool read_only(VkImageLayout layout) {
  return layout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL ||
         layout == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL ||
         layout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
}

bool covers(const vk::Scope& done, const vk::Scope& wanted) {
  return (done.stages & wanted.stages) == wanted.stages &&
         (done.access & wanted.access) == wanted.access;
}

// One use per image: a step that names an image twice uses it once with both accesses.
std::vector<ImageUse> merged(const std::vector<ImageUse>& uses) {
  std::vector<ImageUse> out;
  for (const ImageUse& u : uses) {
    const auto same = std::find_if(out.begin(), out.end(),
                                   [&](const ImageUse& o) { return o.image == u.image; });
    if (same == out.end()) {
      out.push_back(u);
      continue;
    }
    if (same->access.layout != u.access.layout)
      throw std::logic_error("FrameGraph: a step uses image '" + u.image->desc().name +
                             "' in two layouts");
    if (u.access.writes && !same->access.writes) same->access.what = u.access.what;
    same->access.stages |= u.access.stages;
    same->access.access |= u.access.access;
    same->access.writes = same->access.writes || u.access.writes;
  }
  return out;
}

}  // namespace

vk::Scope BarrierTracker::after(const State& s) {
  // Once a barrier has made the write available (and visible to a reader), later ones
  // chain after its readers and name no source access: the writer's access would not
  // match a layout the image has since moved to (best practices,
  // ImageBarrierAccessLayout).
  const bool available = s.visible.stages != VK_PIPELINE_STAGE_2_NONE;
  return {s.write.stages | s.reads.stages, available ? VK_ACCESS_2_NONE : s.write.access};
}

BarrierTracker::State& BarrierTracker::state(const vk::Image* image) {
  const auto it = std::find_if(states_.begin(), states_.end(),
                               [&](const State& s) { return s.image == image; });
  if (it != states_.end()) return *it;
  states_.push_back(State{image, VK_IMAGE_LAYOUT_UNDEFINED, {}, {}, {}});
  return states_.back();
}

std::vector<Transition> BarrierTracker::begin(
    const std::vector<const std::vector<ImageUse>*>& steps, vk::Scope before) {
  states_.clear();
  std::vector<Transition> out;
  for (const std::vector<ImageUse>* uses : steps)
    for (const ImageUse& u : merged(*uses)) {
      const bool seen = std::any_of(states_.begin(), states_.end(),
                                    [&](const State& s) { return s.image == u.image; });
      if (seen) continue;
      State& s = state(u.image);
      if (!u.access.writes && read_only(u.access.layout)) {
        // Read before anything writes it this frame (its shader does not fetch it in this
        // mode): to GENERAL now, and to its read-only layout at the use, chained through
        // the reader's stages. UNDEFINED straight to a read-only layout would be a read
        // of discarded contents (best practices: TransitionUndefinedToReadOnly).
        s.layout = VK_IMAGE_LAYOUT_GENERAL;
        s.reads = {u.access.stages, VK_ACCESS_2_NONE};
        out.push_back({u.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, before,
                       {u.access.stages, VK_ACCESS_2_NONE}});
        continue;
      }
      s.layout = u.access.layout;
      out.push_back({u.image, VK_IMAGE_LAYOUT_UNDEFINED, u.access.layout, before, scope_of(u.access)});
    }
  return out;
}

std::vector<Transition> BarrierTracker::use(const std::vector<ImageUse>& uses) {
  std::vector<Transition> out;
  for (const ImageUse& u : merged(uses)) {
    State& s = state(u.image);
    const vk::Scope dst = scope_of(u.access);
    const bool relayout = u.access.layout != s.layout;
    if (u.access.writes || relayout) {
      // After the last write and every read since: an execution dependency on the
      // readers, and the writer's writes made available.
      const vk::Scope src = after(s);
      if (relayout || src.stages != VK_PIPELINE_STAGE_2_NONE)
        out.push_back({u.image, s.layout, u.access.layout, src, dst});
      s.layout = u.access.layout;
      if (u.access.writes) {
        s.write = {u.access.stages, u.access.access & kWriteBits};
        s.reads = {};
        s.visible = {};
      } else {
        s.reads |= dst;
        s.visible |= dst;
      }
      continue;
    }
    // A read in the same layout: the last write made visible to this kind of reader once.
    // When an earlier barrier already made the write available (and, with a change of
    // layout, left the writer's layout), this one only chains after that barrier's
    // readers and makes it visible: no source access, which would not match the layout.
    if (s.write.stages != VK_PIPELINE_STAGE_2_NONE && !covers(s.visible, dst)) {
      out.push_back({u.image, s.layout, s.layout, after(s), dst});
      s.visible |= dst;
    }
    s.reads |= dst;
  }
  return out;
}

std::vector<Transition> BarrierTracker::leave(const vk::Image& image, VkImageLayout layout,
                                              vk::Scope then) {
  State& s = state(&image);
  if (s.layout == layout) return {};
  std::vector<Transition> out{{&image, s.layout, layout, after(s), then}};
  s = State{&image, layout, {}, {}, {}};
  return out;
}

FrameGraph::PassBuilder& FrameGraph::PassBuilder::step(std::vector<ImageUse> uses,
                                                        Commands commands) {
  graph_.passes_[pass_].steps.push_back({std::move(uses), std::move(commands)});
  return *this;
}

FrameGraph::PassBuilder FrameGraph::add_pass(std::string_view name, bool timed) {
  passes_.push_back({std::string(name), timed, {}});
  return PassBuilder(*this, passes_.size() - 1);
}

void FrameGraph::keep(const vk::Image& image, VkImageLayout layout) {
  kept_.emplace_back(&image, layout);
}

namespace {
void record_barriers(VkCommandBuffer cmd, const std::vector<Transition>& transitions) {
  if (transitions.empty()) return;
  std::vector<VkImageMemoryBarrier2> barriers;
  barriers.reserve(transitions.size());
  for (const Transition& t : transitions)
    barriers.push_back(vk::image_barrier(*t.image, t.old_layout, t.new_layout, t.src, t.dst));
  vk::pipeline_barrier(cmd, barriers);
}
}  // namespace

void FrameGraph::record(VkCommandBuffer cmd, vk::GpuTimer& timer) const {
  std::vector<const std::vector<ImageUse>*> steps;
  for (const Pass& pass : passes_)
    for (const Step& step : pass.steps) steps.push_back(&step.uses);
  BarrierTracker tracker;
  // After everything the previous frame did with the images (the window's blit included).
  record_barriers(cmd, tracker.begin(steps, {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                              VK_ACCESS_2_MEMORY_WRITE_BIT}));
  for (const Pass& pass : passes_) {
    if (pass.timed) timer.begin(cmd, pass.name);
    for (const Step& step : pass.steps) {
      record_barriers(cmd, tracker.use(step.uses));
      step.commands(cmd);
    }
    if (pass.timed) timer.end(cmd);
  }
  for (const auto& [image, layout] : kept_)
    record_barriers(cmd, tracker.leave(*image, layout, vk::kAllCommands));
}

std::string FrameGraph::describe() const {
  std::string out;
  for (const Pass& pass : passes_)
    for (std::size_t k = 0; k < pass.steps.size(); ++k) {
      std::string reads, writes;
      for (const ImageUse& u : merged(pass.steps[k].uses)) {
        std::string& list = u.access.writes ? writes : reads;
        list += (list.empty() ? "" : ", ") + u.image->desc().name + " (" + u.access.what + ")";
      }
      out += pass.name;
      if (pass.steps.size() > 1) out += " [" + std::to_string(k + 1) + "]";
      out += " | " + (reads.empty() ? std::string("-") : reads) + " | " +
             (writes.empty() ? std::string("-") : writes) + "\n";
    }
  return out;
}

std::string FrameGraph::pass_order() const {
  std::string out;
  for (const Pass& pass : passes_) out += (out.empty() ? "" : " -> ") + pass.name;
  return out;
}

}  // namespace sss::renderer::graph
