// Deferred destruction (DESIGN.md §8): an object that a frame's commands may still use
// is handed to the queue under that frame's index instead of being destroyed, and is
// destroyed when the renderer knows the frame is over: after waiting for the frame's
// fence it calls retire(frame_index), which destroys everything queued under that
// index, newest first. At shutdown flush_all() waits for the device to go idle and
// destroys the rest; the destructor does the same.
//
//   deletion.defer(frame, std::move(old_swapchain_images));   // recording frame `frame`
//   ...
//   wait_for_fence(ctx, frames[frame].fence);                  // next time round
//   deletion.retire(frame);
//
// Anything movable can be deferred: Handles, Buffer, Image, or a callback with push().
// Not thread-safe: one thread (the renderer's) records frames and retires them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace sss::vk {

class Context;

class DeletionQueue {
 public:
  // context: waited on by flush_all(); frames_in_flight: the number of frame indices.
  DeletionQueue(const Context& context, uint32_t frames_in_flight);
  ~DeletionQueue();
  DeletionQueue(const DeletionQueue&) = delete;
  DeletionQueue& operator=(const DeletionQueue&) = delete;

  uint32_t frames_in_flight() const { return static_cast<uint32_t>(frames_.size()); }

  // Takes ownership of `object` (moved in) and destroys it at retire(frame).
  template <typename T>
  requires(!std::is_lvalue_reference_v<T> &&
           std::is_move_constructible_v<T>) void defer(uint32_t frame, T&& object) {
    add(frame, std::make_unique<Holder<T>>(std::move(object)));
  }

  // Calls `destroy` at retire(frame) (for objects that are not RAII types).
  void push(uint32_t frame, std::function<void()> destroy);

  // The frame's fence has signalled: destroys what was deferred under `frame`, newest
  // first (a view before its image).
  void retire(uint32_t frame);

  // Waits for the device to be idle, then destroys everything, frame by frame.
  void flush_all();

  std::size_t pending(uint32_t frame) const;
  std::size_t pending() const;

 private:
  struct Entry {
    virtual ~Entry() = default;
  };
  template <typename T>
  struct Holder final : Entry {
    explicit Holder(T&& o) : object(std::move(o)) {}
    T object;
  };
  struct Callback final : Entry {
    explicit Callback(std::function<void()> f) : destroy(std::move(f)) {}
    ~Callback() override {
      if (destroy) destroy();
    }
    std::function<void()> destroy;
  };

  void add(uint32_t frame, std::unique_ptr<Entry> entry);
  std::vector<std::unique_ptr<Entry>>& slot(uint32_t frame);

  const Context* context_;
  std::vector<std::vector<std::unique_ptr<Entry>>> frames_;
};

}  // namespace sss::vk
