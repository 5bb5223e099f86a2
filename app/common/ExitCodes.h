// Exit codes of every executable (DESIGN.md §4): 2 for bad usage or input, 1 for a
// runtime failure. sss-compare adds 3 (the images were compared and differ beyond the
// limits); sss-reference adds 130 for an interrupted run (128 + SIGINT).
#pragma once

namespace sss::app {

inline constexpr int kExitOk = 0, kExitRuntime = 1, kExitUsage = 2, kExitDiffer = 3,
                     kExitInterrupted = 130;

}  // namespace sss::app
