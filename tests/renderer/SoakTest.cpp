// The soak (issue 7): Handle's live-object counters, the soak's verdict on made-up
// curves (a leak must fail it), and the 500-frame CI version of `scripts/soak.sh`: the
// real `sss-viewer --headless --soak` on builtin:sphere, whose CSV this test reads and
// judges itself.
#include <gtest/gtest.h>

#include "vk/VulkanTest.h"

#include "Soak.h"

#include "renderer/vk/Commands.h"
#include "renderer/vk/Handle.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "ViewerRun.h"

namespace {

using sss::app::judge_soak;
using sss::app::SoakSample;

std::int64_t live(std::string_view type) {
  std::int64_t n = 0;
  for (const sss::vk::LiveCount& c : sss::vk::live_objects())
    if (c.type == type) n += c.live;
  return n;
}

class LiveObjects : public sss::vk::testing::VulkanTest {};

// Creating counts, moving keeps the count, reset and destruction give it back.
TEST_F(LiveObjects, HandlesCountWhatTheyOwn) {
  const std::int64_t fences = live("VkFence"), total = sss::vk::live_object_count();
  {
    sss::vk::FenceHandle a = sss::vk::create_fence(ctx(), false);
    sss::vk::SemaphoreHandle s = sss::vk::create_semaphore(ctx());
    EXPECT_EQ(live("VkFence"), fences + 1);
    EXPECT_EQ(sss::vk::live_object_count(), total + 2);
    sss::vk::FenceHandle b = std::move(a);
    EXPECT_EQ(live("VkFence"), fences + 1);
    b.reset();
    EXPECT_EQ(live("VkFence"), fences);
    EXPECT_EQ(sss::vk::live_object_count(), total + 1);
  }
  EXPECT_EQ(sss::vk::live_object_count(), total);
}

// A soak of 10 samples every 100 frames, cycle of 2 steps (warm-up 200 frames).
std::vector<SoakSample> curve(long rss_step_kb, std::int64_t objects_step_per_cycle) {
  std::vector<SoakSample> s;
  for (int f = 0; f <= 1000; f += 100)
    s.push_back({f, 100000 + rss_step_kb * (f / 100),
                 500 + (f / 100) % 2 + objects_step_per_cycle * (f / 200), 2000, "m"});
  return s;
}

TEST(SoakVerdict, ASteadyCurvePasses) {
  const auto v = judge_soak(curve(0, 0), 100, 2, 1024);
  EXPECT_EQ(v.warmup_frames, 200);
  EXPECT_TRUE(v.rss_ok);
  EXPECT_TRUE(v.objects_ok) << v.objects_detail;
  EXPECT_EQ(v.rss_growth_kb, 0);
}

TEST(SoakVerdict, OneObjectPerCycleIsALeak) {
  const auto v = judge_soak(curve(0, 1), 100, 2, 1024);
  EXPECT_FALSE(v.objects_ok);
  EXPECT_NE(v.objects_detail.find("frame 400"), std::string::npos) << v.objects_detail;
}

TEST(SoakVerdict, MemoryGrowingPastTheLimitFails) {
  // Rising by `step` per sample, the peak of the first cycle after warm-up is at frame
  // 400 and that of the last at 1000: 6 steps apart. 6 x 171 = 1026 kB is not below
  // the limit, 6 x 170 = 1020 is.
  const auto v = judge_soak(curve(171, 0), 100, 2, 1024);
  EXPECT_EQ(v.rss_growth_kb, 1026);
  EXPECT_EQ(v.rss_end_minus_warmup_kb, 8 * 171);
  EXPECT_FALSE(v.rss_ok);
  EXPECT_TRUE(judge_soak(curve(170, 0), 100, 2, 1024).rss_ok);
}

// The allocator's swing (a block freed and kept, then handed back) is not growth: RSS
// alternating by 1.4 MB between samples, as measured on the bunny, passes.
TEST(SoakVerdict, ASwingingRssWithTheSamePeaksPasses) {
  std::vector<SoakSample> s = curve(0, 0);
  for (SoakSample& x : s) x.rss_kb += (x.frame / 100) % 3 == 0 ? 1400 : 0;
  const auto v = judge_soak(s, 100, 2, 1024);
  EXPECT_TRUE(v.rss_ok) << v.rss_growth_kb;
}

// A one-time step (an allocator arena or a validation layer's cache growing once: a CI
// run measured +3.1 MB between two samples) is not a leak: RSS 3.1 MB up from frame 500 on
// rises in one cycle only. The same step every cycle is one.
TEST(SoakVerdict, AOneTimeStepPassesAStepEveryCycleFails) {
  std::vector<SoakSample> s = curve(0, 0);
  for (SoakSample& x : s) x.rss_kb += x.frame >= 500 ? 3100 : 0;
  auto v = judge_soak(s, 100, 2, 1024);
  EXPECT_TRUE(v.rss_ok) << v.rss_growth_kb;
  EXPECT_EQ(v.rss_growth_kb, 0);
  s = curve(0, 0);
  for (SoakSample& x : s) x.rss_kb += 600 * ((x.frame + 100) / 200);  // +600 kB each cycle
  v = judge_soak(s, 100, 2, 1024);
  EXPECT_EQ(v.rss_growth_kb, 3 * 600);
  EXPECT_FALSE(v.rss_ok);
}

// The CI soak's shape (every 50 frames, cycles of 2 steps, 800 frames: 7 cycles after the
// warm-up, 6 rises). RSS rising in two cycles running by +2,244 and +2,784 kB, as one CI
// run under the best-practices layer measured (a rerun of 1,600 frames rose in none), is
// not a leak: the lower median of the 6 rises is 0. A leak of 200 kB per cycle under a
// +-400 kB swing from sample to sample is one: 6 x 200 = 1,200 kB.
TEST(SoakVerdict, TwoStepsInARowPassALeakUnderNoiseFails) {
  std::vector<SoakSample> s;
  for (int f = 0; f <= 800; f += 50)
    s.push_back({f, 100000 + (f > 300 ? 2244 : 0) + (f > 400 ? 2784 : 0), 500, 2000, "m"});
  auto v = judge_soak(s, 50, 2, 1024);
  EXPECT_TRUE(v.rss_ok) << v.rss_growth_kb;
  EXPECT_EQ(v.rss_growth_kb, 0);
  for (SoakSample& x : s)
    x.rss_kb = 100000 + 200 * (x.frame / 100) + ((x.frame / 50) % 3 == 0 ? 400 : -400);
  v = judge_soak(s, 50, 2, 1024);
  EXPECT_FALSE(v.rss_ok) << v.rss_growth_kb;
  EXPECT_GE(v.rss_growth_kb, 1024);
}

TEST(SoakVerdict, TooShortToPassItsWarmUp) {
  std::vector<SoakSample> s = curve(0, 0);
  s.resize(3);  // frames 0..200: nothing after warm-up
  EXPECT_FALSE(judge_soak(s, 100, 2, 1024).ok());
}

#ifdef SSS_VIEWER_EXE

struct Row {
  long rss_kb = 0;
  std::int64_t objects = 0;
  std::string material;
};

// frame -> row of the soak's CSV.
std::map<int, Row> read_csv(const std::string& path) {
  std::map<int, Row> rows;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string frame, rss, objects, heap, material;
    std::getline(s, frame, ',');
    std::getline(s, rss, ',');
    std::getline(s, objects, ',');
    std::getline(s, heap, ',');
    std::getline(s, material);
    rows[std::stoi(frame)] = {std::stol(rss), std::stoll(objects), material};
  }
  return rows;
}

// The CI soak: 800 frames of builtin:sphere at 160x90, the material changed every 50
// frames through the material panel's code, alternating a preset (apple) and a
// coefficient edit: a cycle of 2 steps = 100 frames, which is the warm-up (each step's
// first fit, upload and pipelines happen in it), then seven cycles. Criteria:
//   - the program's verdict on RSS (Soak.h): the peak of each cycle after warm-up, the
//     lower median of the 6 rises from one peak to the next times the 6 rises, below
//     1 MB (1024 kB). Peaks, not single samples of different phase: the two steps keep
//     different amounts of memory alive (a CI run measured 'coefficients' 1.7 MB under
//     'apple'). The median, not one rise: steps that are not leaks rise in some cycles
//     and not in the others (CI runs measured +3.1 MB once under the synchronization
//     layer, and +2.2 then +2.8 MB in two cycles running under best practices with three
//     cycles, where 1,600 frames of the same build rose in none); a leak rises in every
//     cycle. Nothing in a frame or a material change should keep memory, so the expected
//     growth is 0. 1 MB is the bound for the 10,000-frame soak and catches any
//     per-frame leak of 1.8 kB or more here (1 MB over 6 cycles of 100 frames) and any
//     per-change leak of 86 kB or more (1 MB over 6 cycles of 2 changes);
//   - the live Vulkan objects at every sample from frame 200 on equal those at the same
//     point of the first cycle after warm-up (100 or 150): one leaked object per change
//     fails it.
TEST(Soak, EightHundredFramesKeepMemoryAndVulkanObjects) {
  const std::string csv = sss::testing::viewer_temp_path("soak_test", "soak.csv");
  const std::string svg = sss::testing::viewer_temp_path("soak_test", "soak.svg");
  std::filesystem::remove(csv);
  std::filesystem::remove(svg);
  const sss::testing::CliRun r = sss::testing::run_shell(
      std::string(SSS_VIEWER_EXE) +
      " builtin:sphere --headless --width 160 --height 90 --soak 800 --soak-every 50"
      " --soak-cycle 2 --soak-csv " + csv + " --soak-svg " + svg);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("soak: pass"), std::string::npos) << r.out;
  const std::map<int, Row> rows = read_csv(csv);
  ASSERT_EQ(rows.size(), 17u) << r.out;
  for (int f = 0; f <= 800; f += 50) ASSERT_TRUE(rows.count(f)) << f;
  EXPECT_EQ(rows.at(100).material, "coefficients");
  EXPECT_EQ(rows.at(150).material, "apple");
  EXPECT_GT(rows.at(100).objects, 0);
  for (int f = 200; f <= 800; f += 50)
    EXPECT_EQ(rows.at(f).objects, rows.at(f % 100 == 0 ? 100 : 150).objects) << f << "\n" << r.out;
  std::ifstream plot(svg);
  std::string head;
  std::getline(plot, head);
  EXPECT_EQ(head.rfind("<svg", 0), 0u) << head;
  std::filesystem::remove(csv);
  std::filesystem::remove(svg);
}

TEST(Soak, OptionsOutsideTheSoakAreRefused) {
  for (const char* args : {"--soak 10", "--headless --soak-csv x.csv --out x.png",
                           "--headless --soak 0", "--headless --soak 10 --soak-every 0"}) {
    const sss::testing::CliRun r =
        sss::testing::run_shell(std::string(SSS_VIEWER_EXE) + " builtin:sphere " + args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.out;
    EXPECT_NE(r.out.find("soak"), std::string::npos) << args << "\n" << r.out;
  }
}

#endif  // SSS_VIEWER_EXE

}  // namespace
