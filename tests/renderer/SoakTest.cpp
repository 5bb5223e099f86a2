// The soak (issue 7): Handle's live-object counters, the soak's verdict on made-up
// curves (a leak must fail it), and the 800-frame CI version of `scripts/soak.sh`: the
// real `sss-viewer --headless --soak` on builtin:sphere, whose CSV this test reads and
// judges itself.
#include <gtest/gtest.h>

#include "vk/VulkanTest.h"

#include "Soak.h"

#include "renderer/vk/Commands.h"
#include "renderer/vk/Handle.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <stdexcept>
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

// A soak's samples every `every` frames up to `frames`, the live objects alternating with
// the phase of a 2-step cycle plus objects_per_cycle more each cycle.
std::vector<SoakSample> samples(int frames, int every, std::int64_t objects_per_cycle = 0) {
  std::vector<SoakSample> s;
  for (int f = 0; f <= frames; f += every)
    s.push_back({f, 100000, 500 + (f / every) % 2 + objects_per_cycle * (f / (2 * every)), 2000, "m"});
  return s;
}

// VmRSS after each of `frames` frames: rss(f) for the reading after frame f (1-based).
template <class F>
std::vector<long> readings(int frames, F rss) {
  std::vector<long> r;
  for (int f = 1; f <= frames; ++f) r.push_back(rss(f));
  return r;
}

// The t quantiles the verdict uses against published tables (Abramowitz & Stegun table
// 26.10; NIST/SEMATECH e-Handbook 1.3.6.7.2), to their 3 or 4 significant digits.
TEST(SoakVerdict, StudentTQuantilesMatchTheTables) {
  using sss::app::student_t_quantile;
  EXPECT_NEAR(student_t_quantile(0.999, 1), 318.309, 0.01);
  EXPECT_NEAR(student_t_quantile(0.999, 2), 22.327, 0.001);
  EXPECT_NEAR(student_t_quantile(0.999, 5), 5.893, 0.001);
  EXPECT_NEAR(student_t_quantile(0.999, 13), 3.852, 0.001);
  EXPECT_NEAR(student_t_quantile(0.999, 30), 3.385, 0.001);
  EXPECT_NEAR(student_t_quantile(0.975, 10), 2.228, 0.001);
  EXPECT_NEAR(student_t_quantile(0.95, 1), 6.314, 0.001);
  EXPECT_NEAR(student_t_quantile(0.95, 4), 2.132, 0.001);
  EXPECT_THROW(student_t_quantile(0.4, 3), std::invalid_argument);
  EXPECT_THROW(student_t_quantile(0.99, 0), std::invalid_argument);
}

// 1,400 frames sampled every 100, cycles of 2 steps: warm-up 200 frames, then 6 cycles,
// the fewest the memory verdict judges (kSoakMinCycles: 3 a half).
TEST(SoakVerdict, ASteadyCurvePasses) {
  const auto v = judge_soak(samples(1400, 100), readings(1400, [](int) { return 100000L; }), 100, 2, 1024);
  EXPECT_EQ(v.warmup_frames, 200);
  EXPECT_EQ(v.cycle_median_kb.size(), 6u);
  EXPECT_TRUE(v.rss_judged);
  EXPECT_TRUE(v.rss_ok);
  EXPECT_TRUE(v.objects_ok) << v.objects_detail;
  EXPECT_EQ(v.rss_growth_kb, 0);
  EXPECT_EQ(v.rss_growth_se_kb, 0);
}

// Five cycles after warm-up are too few to judge memory: the verdict says so and leaves
// the run to the Vulkan objects.
TEST(SoakVerdict, FewerThanSixCyclesAreNotJudged) {
  const auto v = judge_soak(samples(1200, 100), readings(1200, [](int f) { return 100000L + 10 * f; }),
                            100, 2, 1024);
  EXPECT_EQ(v.cycle_median_kb.size(), 5u);
  EXPECT_FALSE(v.rss_judged);
  EXPECT_TRUE(v.ok());
}

TEST(SoakVerdict, OneObjectPerCycleIsALeak) {
  const auto v = judge_soak(samples(1000, 100, 1), readings(1000, [](int) { return 100000L; }), 100, 2, 1024);
  EXPECT_FALSE(v.objects_ok);
  EXPECT_NE(v.objects_detail.find("frame 400"), std::string::npos) << v.objects_detail;
}

// A leak of 1 kB a frame: the medians of the 6 cycles after warm-up (1,400 frames) lie on
// a line 200 kB a cycle apart, and each half's line says 1,000 kB over the run, with no
// scatter. It fails a limit of 999 kB and passes one of 1,001.
TEST(SoakVerdict, MemoryGrowingPastTheLimitFails) {
  const auto rss = readings(1400, [](int f) { return 100000L + f; });
  auto v = judge_soak(samples(1400, 100), rss, 100, 2, 999);
  EXPECT_EQ(v.rss_growth_kb, 1000);
  EXPECT_EQ(v.half[0].growth_kb, 1000);
  EXPECT_EQ(v.half[1].growth_kb, 1000);
  EXPECT_EQ(v.half[0].se_kb, 0);
  EXPECT_FALSE(v.rss_ok);
  EXPECT_TRUE(judge_soak(samples(1400, 100), rss, 100, 2, 1001).rss_ok);
}

// What the frames themselves do is not growth: RSS up by 8 MB after one frame in three
// (lavapipe's binning, the allocator), or down by 3 MB for 40 frames of a 200-frame cycle
// (a trim), leaves every cycle's median where it was.
TEST(SoakVerdict, TheFramesSwingIsNotGrowth) {
  auto v = judge_soak(samples(1400, 100),
                      readings(1400, [](int f) { return 100000L + (f % 3 == 0 ? 8000 : 0); }), 100, 2, 1024);
  EXPECT_TRUE(v.rss_ok) << v.rss_growth_kb;
  EXPECT_EQ(v.rss_growth_kb, 0);
  v = judge_soak(samples(1400, 100),
                 readings(1400, [](int f) { return 100000L - (f % 200 < 40 ? 3000 : 0); }), 100, 2, 1024);
  EXPECT_TRUE(v.rss_ok) << v.rss_growth_kb;
  EXPECT_EQ(v.rss_growth_kb, 0);
}

// The CI soak's shape (every 25 frames, cycles of 2, 800 frames: 15 cycles after warm-up,
// halves of 7 and 8). RSS stepping up once and staying (a CI run measured +3.1 MB between
// two samples under the synchronization layer), or twice 50 frames apart (+2,244 then
// +2,784 kB under best practices), passes wherever after warm-up it happens, although a
// line through all the medians rises by up to 4.3 MB for the first and 6.9 MB for the
// second: the step lies in one half (or between them) and the other half is flat. 12 kB a
// frame (8.4 MB over the run) fails, also under a +-400 kB swing from frame to frame and
// with the 3.1 MB step on top.
TEST(SoakVerdict, StepsPassALeakUnderNoiseFails) {
  for (int at = 75; at < 800; at += 25) {
    auto v = judge_soak(samples(800, 25),
                        readings(800, [at](int f) { return 100000L + (f > at ? 3100 : 0); }), 25, 2, 1024);
    EXPECT_TRUE(v.rss_ok) << "step after frame " << at << ": " << v.half[0].growth_kb << " +- "
                          << v.half[0].se_kb << ", " << v.half[1].growth_kb << " +- " << v.half[1].se_kb;
    v = judge_soak(samples(800, 25), readings(800, [at](int f) {
                     return 100000L + (f > at ? 2244 : 0) + (f > at + 50 ? 2784 : 0);
                   }), 25, 2, 1024);
    EXPECT_TRUE(v.rss_ok) << "two steps after frame " << at << ": " << v.half[0].growth_kb
                          << " +- " << v.half[0].se_kb << ", " << v.half[1].growth_kb << " +- "
                          << v.half[1].se_kb;
  }
  const auto leak = [](int f) { return 100000L + 12 * f + (f % 2 == 0 ? 400 : -400); };
  auto v = judge_soak(samples(800, 25), readings(800, leak), 25, 2, 1024);
  EXPECT_NEAR(v.rss_growth_kb, 8400, 5);
  EXPECT_FALSE(v.rss_ok) << v.rss_growth_kb;
  v = judge_soak(samples(800, 25), readings(800, [&](int f) { return leak(f) + (f > 400 ? 3100 : 0); }),
                 25, 2, 1024);
  EXPECT_FALSE(v.rss_ok) << v.half[0].growth_kb << " " << v.half[1].growth_kb;
}

// The verdict's level, by simulation: 100,000 soaks of the CI's 15 cycles whose medians
// scatter as independent Gaussians (sigma 1 MB) about a line. A half of m cycles estimates
// the run's growth with an error of 14 sigma / sqrt(Sxx_m) (2.65 sigma for the first 7,
// 2.16 for the last 8), from m - 2 degrees of freedom, and flags it with probability
//   P = integral over chi-square_(m-2) x of Q((limit - growth) / error + t sqrt(x / (m - 2)))
// (Q the Gaussian upper tail, t the half's quantile at 0.968377); the run fails with the
// product of the halves' P. Integrated numerically (midpoint rule, 20,000 steps): 0.001000
// where the growth is exactly the limit (the level, by construction), 1.67e-4 with no
// growth, and 0.99847 at limit + 16 sigma. Expected failures of 100,000 with binomial bounds
// at 4.5 standard deviations: 100 (55 to 145), 16.7 (at most 35), 99,847 (at least 99,791).
TEST(SoakVerdict, TheGrowthTestFailsAtItsLevel) {
  constexpr int kRuns = 100000, kCycles = 15;
  constexpr double kSigma = 1000.0, kLimit = 1024.0;
  std::mt19937_64 rng(20261207);
  std::normal_distribution<double> noise(0.0, kSigma);
  const std::vector<SoakSample> s = samples(2 * (kCycles + 1), 1);  // a cycle = 2 frames
  const auto failures = [&](double growth) {
    int failed = 0;
    for (int run = 0; run < kRuns; ++run) {
      std::vector<double> median(kCycles);
      for (int k = 0; k < kCycles; ++k) median[k] = 1e6 + growth * k / (kCycles - 1) + noise(rng);
      // Both readings of cycle k (frames 2k + 3, 2k + 4) at its median.
      const auto rss = readings(2 * (kCycles + 1), [&](int f) {
        return f <= 2 ? 1000000L : std::lround(median[std::size_t((f - 3) / 2)]);
      });
      if (!judge_soak(s, rss, 1, 2, long(kLimit)).rss_ok) ++failed;
    }
    return failed;
  };
  const int at_limit = failures(kLimit), at_zero = failures(0.0),
            far = failures(kLimit + 16.0 * kSigma);
  std::printf("failures of %d: %d at the limit, %d with no growth, %d at limit + 16 sigma\n",
              kRuns, at_limit, at_zero, far);
  EXPECT_GE(at_limit, 55);
  EXPECT_LE(at_limit, 145);
  EXPECT_LE(at_zero, 35);
  EXPECT_GE(far, 99791);
}

TEST(SoakVerdict, TooShortToPassItsWarmUp) {
  EXPECT_FALSE(judge_soak(samples(200, 100), readings(200, [](int) { return 100000L; }), 100, 2, 1024).ok());
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
    std::string frame, rss, median, objects, heap, material;
    std::getline(s, frame, ',');
    std::getline(s, rss, ',');
    std::getline(s, median, ',');  // empty at frame 0
    std::getline(s, objects, ',');
    std::getline(s, heap, ',');
    std::getline(s, material);
    rows[std::stoi(frame)] = {std::stol(rss), std::stoll(objects), material};
  }
  return rows;
}

// The CI soak: 800 frames of builtin:sphere at 160x90, the material changed every 25
// frames through the material panel's code, alternating a preset (apple) and a
// coefficient edit: a cycle of 2 steps = 50 frames, which is the warm-up (each step's
// first fit, upload and pipelines happen in it), then fifteen cycles. Criteria:
//   - the program's verdict on RSS (SoakVerdict in Soak.h): the median RSS of each cycle
//     after warm-up (VmRSS after each of its 50 frames); a least-squares line through the
//     first 7 medians and another through the last 8, each giving the growth over the run
//     with its standard error; the run fails when both say growth - t x error >= 1 MB (t
//     2.38 and 2.27: Student's, one-sided 96.8% with 5 and 6 degrees of freedom, 99.9%
//     together). Nothing in a frame or a material change should keep memory, so the
//     expected growth is 0. Six runs under the best-practices layer on 2 cores gave a line
//     through all 15 medians an error of 611 to 1,261 kB, a scatter of the medians of 0.73
//     to 1.5 MB (the error is 0.837 x the scatter). For that scatter a run without a leak
//     fails 8e-5 to 3.2e-4 of the time (the integral in TheGrowthTestFailsAtItsLevel), and
//     the first half flags (with probability 1/2) a growth over the 700 frames of about
//     5.6 to 10.8 MB, the second 4.6 to 8.6 MB: a leak of 8 to 15 kB a frame, or of 200
//     to 400 kB a material change (28 changes after warm-up). Smaller leaks are for
//     scripts/soak.sh's 10,000 frames. One-time steps pass (StepsPassALeakUnderNoiseFails).
//     Fifteen cycles of 50 frames rather than seven of 100 for the same frames: halves of
//     7 and 8 cycles (3 and 4 with seven cycles, 1 and 2 degrees of freedom, t 10.0 and 3.8
//     at 96.8%), and medians that scatter less (two traces of 800 frames: 0.7 and 1.1 MB
//     with 50-frame cycles, 0.9 and 1.6 MB with 100-frame cycles);
//   - the live Vulkan objects at every sample from frame 100 on equal those at the same
//     point of the first cycle after warm-up (50 or 75): one leaked object per change
//     fails it.
TEST(Soak, EightHundredFramesKeepMemoryAndVulkanObjects) {
  const std::string csv = sss::testing::viewer_temp_path("soak_test", "soak.csv");
  const std::string svg = sss::testing::viewer_temp_path("soak_test", "soak.svg");
  std::filesystem::remove(csv);
  std::filesystem::remove(svg);
  const sss::testing::CliRun r = sss::testing::run_shell(
      std::string(SSS_VIEWER_EXE) +
      " builtin:sphere --headless --width 160 --height 90 --soak 800 --soak-every 25"
      " --soak-cycle 2 --soak-csv " + csv + " --soak-svg " + svg);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("soak: pass"), std::string::npos) << r.out;
  const std::map<int, Row> rows = read_csv(csv);
  ASSERT_EQ(rows.size(), 33u) << r.out;
  for (int f = 0; f <= 800; f += 25) ASSERT_TRUE(rows.count(f)) << f;
  EXPECT_EQ(rows.at(50).material, "coefficients");
  EXPECT_EQ(rows.at(75).material, "apple");
  EXPECT_GT(rows.at(50).objects, 0);
  for (int f = 100; f <= 800; f += 25)
    EXPECT_EQ(rows.at(f).objects, rows.at(f % 50 == 0 ? 50 : 75).objects) << f << "\n" << r.out;
  EXPECT_NE(r.out.find("RSS medians of the 15 full cycles"), std::string::npos) << r.out;
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
