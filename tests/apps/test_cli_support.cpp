// app/common/CliSupport.h: the suggestion for a mistyped word, and messages said once.
#include "app/common/CliSupport.h"

#include <gtest/gtest.h>

#include <sstream>

namespace {

TEST(CliSupport, NearestNameIsWithinAThirdOfTheWord) {
  const std::vector<std::string> options{"--gaussians", "--preset", "--plot", "--plot-mc"};
  EXPECT_EQ(sss::app::nearest_name("--gaussian", options), "--gaussians");
  EXPECT_EQ(sss::app::nearest_name("--prest", options), "--preset");
  EXPECT_EQ(sss::app::nearest_name("--plotmc", options), "--plot-mc");
  EXPECT_EQ(sss::app::nearest_name("--zzzzzz", options), "");
  EXPECT_EQ(sss::app::edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(sss::app::edit_distance("", "abc"), 3u);
}

// The same warning from every primitive of a mesh, or every frame, prints once with its
// count; distinct ones keep their order.
TEST(CliSupport, IdenticalMessagesPrintOnceWithTheirCount) {
  std::ostringstream captured;
  std::streambuf* old = std::cerr.rdbuf(captured.rdbuf());
  sss::app::print_messages("tool", "warning", {"b", "a", "b", "c", "b"});
  std::cerr.rdbuf(old);
  EXPECT_EQ(captured.str(), "tool: warning: b (3 times)\ntool: warning: a\ntool: warning: c\n");
}

}  // namespace
