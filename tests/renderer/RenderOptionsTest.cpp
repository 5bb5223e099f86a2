// RenderOptions' SSS technique: one enum for the CLI's two options (--sss, --mode), whose
// values the shaders read (FrameUniforms::options.y). No GPU.
#include "renderer/RenderOptions.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <variant>

namespace sss::renderer {
namespace {

TEST(SssTechnique, EveryNameParsesBackAndTheValuesAreTheShadersCodes) {
  std::set<std::string> names;
  for (const SssTechnique t : all_techniques()) {
    EXPECT_EQ(parse_technique(technique_name(t)), t);
    names.insert(std::string(technique_name(t)));
  }
  EXPECT_EQ(names.size(), all_techniques().size());
  EXPECT_FALSE(parse_technique("screen"));  // a CLI spelling, not a technique
  EXPECT_FALSE(parse_technique("Separable"));
  // The shaders compare FrameUniforms::options.y with these macros.
  EXPECT_EQ(static_cast<int>(SssTechnique::Off), SSS_TECHNIQUE_OFF);
  EXPECT_EQ(static_cast<int>(SssTechnique::Separable), SSS_TECHNIQUE_SEPARABLE);
  EXPECT_EQ(static_cast<int>(SssTechnique::Gaussians), SSS_TECHNIQUE_GAUSSIANS);
  EXPECT_EQ(static_cast<int>(SssTechnique::Texture), SSS_TECHNIQUE_TEXTURE);
  EXPECT_EQ(RenderOptions{}.technique, SssTechnique::Separable);
}

TEST(SssTechnique, TheCliSpellingsMapToOneTechniqueAndBadOnesNameTheirOption) {
  struct Row {
    const char* sss;
    const char* mode;
    SssTechnique expected;
  };
  for (const Row& r : {Row{"off", "separable", SssTechnique::Off}, Row{"off", "gaussians", SssTechnique::Off},
                       Row{"screen", "separable", SssTechnique::Separable},
                       Row{"screen", "gaussians", SssTechnique::Gaussians},
                       Row{"texture", "separable", SssTechnique::Texture},
                       Row{"texture", "gaussians", SssTechnique::Texture}}) {
    const auto t = technique_from_cli(r.sss, r.mode);
    ASSERT_TRUE(std::holds_alternative<SssTechnique>(t)) << r.sss << " " << r.mode;
    EXPECT_EQ(std::get<SssTechnique>(t), r.expected) << r.sss << " " << r.mode;
  }
  const auto bad_sss = technique_from_cli("fuzzy", "separable");
  ASSERT_TRUE(std::holds_alternative<std::string>(bad_sss));
  EXPECT_EQ(std::get<std::string>(bad_sss), "--sss: expected off, screen or texture, got 'fuzzy'");
  // --mode is checked even where the technique does not read it: a typo is not ignored.
  const auto bad_mode = technique_from_cli("texture", "blurry");
  ASSERT_TRUE(std::holds_alternative<std::string>(bad_mode));
  EXPECT_EQ(std::get<std::string>(bad_mode), "--mode: expected separable or gaussians, got 'blurry'");
}

}  // namespace
}  // namespace sss::renderer
