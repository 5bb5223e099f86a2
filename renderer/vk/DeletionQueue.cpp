#include "renderer/vk/DeletionQueue.h"

#include "renderer/vk/Context.h"

#include <stdexcept>
#include <string>

namespace sss::vk {

DeletionQueue::DeletionQueue(const Context& context, uint32_t frames_in_flight)
    : context_(&context), frames_(frames_in_flight) {
  if (frames_in_flight == 0) throw std::invalid_argument("DeletionQueue: no frames in flight");
}

DeletionQueue::~DeletionQueue() {
  try {
    flush_all();
  } catch (...) {
    // Only a lost device makes the wait fail; nothing executes any more, so the objects
    // may still be destroyed, which retire() does without waiting.
    for (uint32_t f = 0; f < frames_in_flight(); ++f) retire(f);
  }
}

std::vector<std::unique_ptr<DeletionQueue::Entry>>& DeletionQueue::slot(uint32_t frame) {
  if (frame >= frames_.size()) {
    throw std::out_of_range("DeletionQueue: frame " + std::to_string(frame) + " of " +
                            std::to_string(frames_.size()) + " frames in flight");
  }
  return frames_[frame];
}

void DeletionQueue::add(uint32_t frame, std::unique_ptr<Entry> entry) {
  slot(frame).push_back(std::move(entry));
}

void DeletionQueue::push(uint32_t frame, std::function<void()> destroy) {
  if (!destroy) return;
  add(frame, std::make_unique<Callback>(std::move(destroy)));
}

void DeletionQueue::retire(uint32_t frame) {
  std::vector<std::unique_ptr<Entry>>& entries = slot(frame);
  // Take the list first, so that a destructor that defers more work (into another
  // frame) does not modify the vector being walked.
  std::vector<std::unique_ptr<Entry>> doomed = std::move(entries);
  entries.clear();
  while (!doomed.empty()) doomed.pop_back();
}

void DeletionQueue::flush_all() {
  if (pending() == 0) return;
  context_->wait_idle();
  for (uint32_t f = 0; f < frames_in_flight(); ++f) retire(f);
}

std::size_t DeletionQueue::pending(uint32_t frame) const {
  return frame < frames_.size() ? frames_[frame].size() : 0;
}

std::size_t DeletionQueue::pending() const {
  std::size_t n = 0;
  for (const auto& f : frames_) n += f.size();
  return n;
}

}  // namespace sss::vk
