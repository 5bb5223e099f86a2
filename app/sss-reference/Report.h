// What sss-reference prints while it renders (a progress bar with the time left) and after
// (--stats: counts, rates and stage times), on stderr.
#pragma once

#include "reference/GroundTruth.h"
#include "reference/ReferenceRenderer.h"

#include <chrono>
#include <string>

namespace sss::app {

// "12s", "3m05s", "1h02m".
std::string duration(double seconds);

// A one-line bar redrawn in place on a terminal, with the time left once a stage has run a
// second; on a pipe or file, a line per stage done and, for long stages, one every 10%.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  void operator()(const char* stage, double fraction);

 private:
  bool enabled_, tty_;
  std::string stage_, stage_done_, eta_;
  int percent_ = -1, last_tenth_ = 0;
  double fraction_ = 0.0;
  std::chrono::steady_clock::time_point stage_start_;
};

void print_stats(const reference::ReferenceStats& s);
void print_stats(const reference::GroundTruthStats& s, int threads);

}  // namespace sss::app
