// The random-walk ground truth (reference/GroundTruth.h, issue 16): how fast the
// walk runs, and what one scattering event costs in Embree ray casts.
//
//  * BM_RandomWalk/<scene>: render_ground_truth at 160x90 with a fixed sample count on
//    every hardware thread (2 on CI machines; each iteration ~1-3 s there), for
//    builtin:sphere, builtin:bunny and builtin:materials. Counters: paths/s, events/s
//    (scattering events), events/path, and the baseline measured in the same run on the
//    same number of threads: casts/s, the rate of RayScene::intersect on the same scene
//    (rays from the centre of each subsurface instance's bounding box, inside the mesh, in
//    uniformly random directions: the walk's own query, a nearest hit from inside the
//    medium; ray_hit_% says how many found a face, 100 when the centre is inside a closed
//    mesh). events/casts is events/s over casts/s, the ratio asked for: the fraction of
//    the bare ray-cast rate the walk reaches in events; casts/event is its inverse, how
//    many ray casts one scattering event costs (its one intersect for the free flight,
//    plus next-event estimation, sampling and bookkeeping).
//  * BM_RandomWalkThreads: builtin:bunny at 160x90 on 1 thread and on every hardware
//    thread; `speedup` is the 1-thread walk time over the all-threads walk time.
//
// Time: wall-clock (steady_clock) throughout. The walk's time is the renderer's own,
// GroundTruthStats::seconds - setup_seconds (the sampling passes, without building the
// BVH, the media and the direct beams); the casts are timed the same way around the
// casting threads. The benchmark's reported time is that walk time (manual time).
// Wall time counts what other processes take from the cores: run it on an idle machine.
//
//   build/bench/bench_random_walk [--benchmark_filter=Threads]
#include "reference/GroundTruth.h"
#include "reference/MediumMesh.h"
#include "reference/RayScene.h"
#include "scene/BuiltinScenes.h"

#include <benchmark/benchmark.h>

#include <glm/geometric.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

namespace {

using namespace sss;
using Clock = std::chrono::steady_clock;

constexpr std::uint32_t kWidth = 160, kHeight = 90;

scene::Scene load(const char* name) {
  auto loaded = scene::load_scene(name);
  if (auto* e = std::get_if<scene::LoadError>(&loaded)) throw std::runtime_error(e->what());
  scene::Scene s = std::move(std::get<scene::Scene>(loaded));
  scene::add_camera_if_missing(s);
  scene::add_light_if_missing(s);
  return s;
}

int thread_count(int threads) { return threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency())); }

struct CastRate {
  double per_second = 0.0;
  double hit_fraction = 0.0;
};

// RayScene::intersect from the bounding-box centre of every instance of a subsurface mesh
// (taken in turn) in uniformly random directions, on `threads` threads for `seconds` of
// wall time. The directions are drawn beforehand, so only the casts are timed.
CastRate cast_rate(const scene::Scene& s, int threads, double seconds = 0.5) {
  const reference::RayScene rays(s, threads);
  std::vector<glm::vec3> origins;
  for (const reference::MediumSurface& surface : reference::medium_surfaces(s, rays))
    for (const std::uint32_t instance : surface.instances) {
      scene::Bounds b;
      for (const glm::vec3& p : rays.world_positions(instance)) b.extend(p);
      if (!b.empty()) origins.push_back(b.center());
    }
  if (origins.empty()) throw std::runtime_error(s.name + ": no subsurface mesh to cast rays from");
  constexpr std::size_t kBatch = 4096;
  std::atomic<std::uint64_t> casts{0}, hits{0};
  std::atomic<bool> go{false};
  std::vector<std::thread> pool;
  Clock::time_point start;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      std::mt19937_64 rng(0x5eed + std::uint64_t(t));
      std::uniform_real_distribution<float> u(0.0f, 1.0f);
      std::vector<glm::vec3> dirs(kBatch);
      for (glm::vec3& d : dirs) {
        const float z = 1.0f - 2.0f * u(rng), phi = 6.2831853f * u(rng), r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        d = glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
      }
      while (!go.load(std::memory_order_acquire)) std::this_thread::yield();
      std::uint64_t n = 0, h = 0;
      for (std::size_t batch = 0;; ++batch) {
        const glm::vec3 o = origins[(std::size_t(t) + batch) % origins.size()];
        for (const glm::vec3& d : dirs) h += rays.intersect(o, d).has_value() ? 1u : 0u;
        n += kBatch;
        if (std::chrono::duration<double>(Clock::now() - start).count() >= seconds) break;
      }
      casts += n;
      hits += h;
    });
  start = Clock::now();
  go.store(true, std::memory_order_release);
  for (std::thread& th : pool) th.join();
  const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  return {double(casts.load()) / elapsed, double(hits.load()) / double(std::max<std::uint64_t>(casts.load(), 1))};
}

struct WalkRun {
  reference::GroundTruthStats stats;
  double walk_seconds = 0.0;
};

WalkRun walk(const scene::Scene& s, std::uint64_t spp, int threads) {
  reference::GroundTruthOptions o;
  o.width = kWidth;
  o.height = kHeight;
  o.spp = spp;
  o.threads = threads;
  WalkRun r;
  r.stats = reference::render_ground_truth(s, o).stats;
  r.walk_seconds = std::max(r.stats.seconds - r.stats.setup_seconds, 1e-9);
  return r;
}

void BM_RandomWalk(benchmark::State& state, const char* scene_name, std::uint64_t spp) {
  const scene::Scene s = load(scene_name);
  const int threads = thread_count(0);
  for (auto _ : state) {
    const WalkRun r = walk(s, spp, 0);
    state.SetIterationTime(r.walk_seconds);
    const CastRate casts = cast_rate(s, threads);
    const reference::WalkStats& w = r.stats.walk;
    const double events_per_s = double(w.scattering_events) / r.walk_seconds;
    state.counters["spp"] = double(r.stats.spp);
    state.counters["threads"] = threads;
    state.counters["walk_s"] = r.walk_seconds;
    state.counters["paths/s"] = double(w.paths) / r.walk_seconds;
    state.counters["events/s"] = events_per_s;
    state.counters["events/path"] = w.paths ? double(w.scattering_events) / double(w.paths) : 0.0;
    state.counters["casts/s"] = casts.per_second;
    state.counters["ray_hit_%"] = 100.0 * casts.hit_fraction;
    state.counters["events/casts"] = events_per_s / casts.per_second;
    state.counters["casts/event"] = casts.per_second / events_per_s;
  }
}
// Sample counts for ~1-3 s per iteration on 2 cores.
BENCHMARK_CAPTURE(BM_RandomWalk, sphere, "builtin:sphere", 64)->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RandomWalk, bunny, "builtin:bunny", 16)->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RandomWalk, materials, "builtin:materials", 24)->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_RandomWalkThreads(benchmark::State& state) {
  static double one_thread_s = 0.0;
  const scene::Scene s = load("builtin:bunny");
  const int threads = int(state.range(0));
  for (auto _ : state) {
    const WalkRun r = walk(s, 8, threads);
    state.SetIterationTime(r.walk_seconds);
    const reference::WalkStats& w = r.stats.walk;
    state.counters["threads"] = thread_count(threads);
    state.counters["walk_s"] = r.walk_seconds;
    state.counters["paths/s"] = double(w.paths) / r.walk_seconds;
    state.counters["events/s"] = double(w.scattering_events) / r.walk_seconds;
    if (threads == 1) one_thread_s = r.walk_seconds;
    else if (one_thread_s > 0.0) state.counters["speedup"] = one_thread_s / r.walk_seconds;
  }
}
BENCHMARK(BM_RandomWalkThreads)->Arg(1)->Arg(0)->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
