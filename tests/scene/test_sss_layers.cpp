// extras.sss.layers and `sss-fit --layers FILE.json` (issue 19): a stack of layers, top
// first, read back value for value, and an error naming the layer and the field as the
// user wrote them for every bad input.
#include "scene/SssLayers.h"

#include "profiles/Presets.h"

#include "SssExpect.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <unistd.h>

namespace sss::scene {
namespace {

namespace fs = std::filesystem;
using profiles::LayerStack;

constexpr double kInf = std::numeric_limits<double>::infinity();

LayerStack parse_ok(std::string_view text) {
  return testing::expect_parsed<LayerStack>([](std::string_view t) { return parse_sss_layers_text(t); }, text);
}

FieldError parse_error(std::string_view text) {
  return testing::expect_refused([](std::string_view t) { return parse_sss_layers_text(t); }, text);
}

// A file of its own under the system's temporary folder, removed at the end of the test.
class TempFile {
 public:
  TempFile(const std::string& name, const std::string& contents)
      : path_(fs::temp_directory_path() /
              ("sss-layers-" + std::to_string(::getpid()) + "-" + name)) {
    std::ofstream(path_, std::ios::binary) << contents;
  }
  ~TempFile() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  std::string path() const { return path_.string(); }

 private:
  fs::path path_;
};

TEST(SssLayers, TwoLayerFileReadsBackEveryValue) {
  const TempFile file("two.json", R"({"layers": [
      {"sigma_a": [0.2, 0.3, 0.5], "sigma_s": [20, 25, 30], "g": [0.1, 0.2, 0.3],
       "eta": 1.4, "thickness_mm": 0.25},
      {"sigma_a": [0.03, 0.17, 0.48], "sigma_s": 0.9, "g": 0.5, "eta": [1.4, 1.4, 1.4]}
    ]})");
  auto r = parse_sss_layers_file(file.path());
  ASSERT_TRUE(std::holds_alternative<LayerStack>(r)) << std::get<FieldError>(r).what();
  const LayerStack& s = std::get<LayerStack>(r);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].sigma_a, (Rgb{0.2, 0.3, 0.5}));
  EXPECT_EQ(s[0].sigma_s, (Rgb{20, 25, 30}));
  EXPECT_EQ(s[0].g, (Rgb{0.1, 0.2, 0.3}));
  EXPECT_EQ(s[0].eta, (Rgb{1.4, 1.4, 1.4}));
  EXPECT_EQ(s[0].thickness_mm, 0.25);
  EXPECT_EQ(s[1].sigma_a, (Rgb{0.03, 0.17, 0.48}));
  EXPECT_EQ(s[1].sigma_s, (Rgb{0.9, 0.9, 0.9}));
  EXPECT_EQ(s[1].g, (Rgb{0.5, 0.5, 0.5}));
  EXPECT_EQ(s[1].eta, (Rgb{1.4, 1.4, 1.4}));
  EXPECT_EQ(s[1].thickness_mm, kInf);  // no thickness_mm on the last layer: semi-infinite
  EXPECT_FALSE(s[1].is_slab());
}

TEST(SssLayers, ScalarOrArraySigmaAndTheDefaults) {
  const LayerStack s = parse_ok(
      R"({"layers": [{"sigma_a": 0.1, "sigma_s": [1, 2, 3], "thickness_mm": 2},
                     {"sigma_a": [0.1, 0.2, 0.3], "sigma_s": 4}]})");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].sigma_a, (Rgb{0.1, 0.1, 0.1}));
  EXPECT_EQ(s[0].sigma_s, (Rgb{1, 2, 3}));
  EXPECT_EQ(s[1].sigma_a, (Rgb{0.1, 0.2, 0.3}));
  EXPECT_EQ(s[1].sigma_s, (Rgb{4, 4, 4}));
  // As in extras.sss: g 0 and eta 1.3 when left out.
  for (const auto& m : s) {
    EXPECT_EQ(m.g, (Rgb{0, 0, 0}));
    EXPECT_EQ(m.eta, (Rgb{1.3, 1.3, 1.3}));
  }
}

TEST(SssLayers, PresetLayersTakeThePresetsMediumAndTheirThickness) {
  const LayerStack s = parse_ok(
      R"({"layers": [{"preset": "skin1", "thickness_mm": 2}, {"preset": "skin2"}]})");
  ASSERT_EQ(s.size(), 2u);
  const profiles::Medium skin1 = profiles::preset_medium(*profiles::find_preset("skin1"));
  const profiles::Medium skin2 = profiles::preset_medium(*profiles::find_preset("skin2"));
  EXPECT_EQ(s[0].sigma_a, skin1.sigma_a);
  EXPECT_EQ(s[0].sigma_s, skin1.sigma_s);
  EXPECT_EQ(s[0].g, skin1.g);
  EXPECT_EQ(s[0].eta, skin1.eta);
  EXPECT_EQ(s[0].thickness_mm, 2.0);
  EXPECT_EQ(s[1].sigma_a, skin2.sigma_a);
  EXPECT_EQ(s[1].sigma_s, skin2.sigma_s);
  EXPECT_EQ(s[1].thickness_mm, kInf);
  // A preset under a coefficient layer, and marble's own eta (1.5) matched by the top.
  const LayerStack m = parse_ok(
      R"({"layers": [{"sigma_a": 0.1, "sigma_s": 10, "eta": 1.5, "thickness_mm": 1},
                     {"preset": "marble", "thickness_mm": 3}]})");
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[1].eta, (Rgb{1.5, 1.5, 1.5}));
  EXPECT_EQ(m[1].thickness_mm, 3.0);
}

TEST(SssLayers, OnlyAMissingLastThicknessIsSemiInfinite) {
  const LayerStack one = parse_ok(R"({"layers": [{"preset": "skin1"}]})");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].thickness_mm, kInf);
  // A thickness on the last layer too: a stack with a finite bottom.
  const LayerStack finite = parse_ok(
      R"({"layers": [{"preset": "skin1", "thickness_mm": 2}, {"preset": "skin2", "thickness_mm": 5}]})");
  ASSERT_EQ(finite.size(), 2u);
  EXPECT_EQ(finite[1].thickness_mm, 5.0);
  EXPECT_TRUE(finite[1].is_slab());
}

TEST(SssLayers, AtMostMaxLayers) {
  nlohmann::json layers = nlohmann::json::array();
  for (int k = 0; k < profiles::kMaxLayers; ++k)
    layers.push_back({{"preset", "skin1"}, {"thickness_mm", 2}});
  auto ok = parse_sss_layers(layers);
  ASSERT_TRUE(std::holds_alternative<LayerStack>(ok)) << std::get<FieldError>(ok).what();
  EXPECT_EQ(std::get<LayerStack>(ok).size(), static_cast<std::size_t>(profiles::kMaxLayers));
  layers.push_back({{"preset", "skin1"}});
  auto bad = parse_sss_layers(layers);
  ASSERT_TRUE(std::holds_alternative<FieldError>(bad));
  EXPECT_EQ(std::get<FieldError>(bad).field, "layers");
  EXPECT_NE(std::get<FieldError>(bad).message.find(std::to_string(profiles::kMaxLayers)),
            std::string::npos);
}

struct Bad {
  const char* layers;    // the array, as the value of "layers"
  const char* field;     // exactly
  const char* message;   // a piece of it
};

void PrintTo(const Bad& b, std::ostream* os) { *os << b.field; }

// "7_layers_0__thickness_mm": the case's index and its field.
struct BadName {
  std::string operator()(const ::testing::TestParamInfo<Bad>& info) const {
    std::string name = std::to_string(info.index) + "_" + info.param.field;
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
  }
};

class SssLayersErrors : public ::testing::TestWithParam<Bad> {};

TEST_P(SssLayersErrors, NameTheLayerAndTheField) {
  const Bad& b = GetParam();
  const FieldError e = parse_error(std::string(R"({"layers": )") + b.layers + "}");
  EXPECT_EQ(e.field, b.field) << b.layers << " -> " << e.what();
  EXPECT_NE(e.message.find(b.message), std::string::npos) << b.layers << " -> " << e.what();
  // The array itself gives the same error.
  auto direct = parse_sss_layers(nlohmann::json::parse(b.layers));
  ASSERT_TRUE(std::holds_alternative<FieldError>(direct)) << b.layers;
  EXPECT_EQ(std::get<FieldError>(direct).field, b.field);
}

INSTANTIATE_TEST_SUITE_P(
    Every, SssLayersErrors,
    ::testing::Values(
        Bad{R"(3)", "layers", "must be an array"},
        Bad{R"({"preset": "skin1"})", "layers", "must be an array"},
        Bad{R"([])", "layers", "at least one layer"},
        Bad{R"([5])", "layers[0]", "must be a JSON object"},
        Bad{R"([{"preset": "skin1", "thickness_mm": 1}, "skin2"])", "layers[1]", "JSON object"},
        Bad{R"([{"preset": "skin1", "colour": 1}])", "layers[0].colour", "unknown field"},
        Bad{R"([{"preset": "skin1", "thickness": 1}, {"preset": "skin1"}])", "layers[0].thickness",
            "unknown field"},
        Bad{R"([{"preset": "skin1"}, {"preset": "skin2"}])", "layers[0].thickness_mm",
            "is required on every layer but the last"},
        Bad{R"([{"preset": "skin1", "thickness_mm": 1}, {"preset": "skin1"}, {"preset": "skin2"}])",
            "layers[1].thickness_mm", "is required"},
        Bad{R"([{"preset": "skin1", "thickness_mm": 0}])", "layers[0].thickness_mm", "> 0"},
        Bad{R"([{"preset": "skin1", "thickness_mm": -1}])", "layers[0].thickness_mm", "> 0"},
        Bad{R"([{"preset": "skin1", "thickness_mm": "1"}])", "layers[0].thickness_mm", "\"1\""},
        Bad{R"([{"preset": "skin1", "thickness_mm": null}])", "layers[0].thickness_mm", "null"},
        Bad{R"([{"preset": "skin1", "thickness_mm": 1}, {"preset": "skin1", "thickness_mm": [1]}])",
            "layers[1].thickness_mm", "> 0"},
        Bad{R"([{"preset": "skin1", "thickness_mm": 1}, {"preset": "skin1", "thickness_mm": 1},
               {"preset": "jade"}])",
            "layers[2].preset", "unknown preset \"jade\"; known: apple, chicken1"},
        Bad{R"([{"preset": 3}])", "layers[0].preset", "a string"},
        Bad{R"([{"preset": "spectralon"}])", "layers[0].preset", "cannot be a layer"},
        Bad{R"([{"preset": "skin1", "g": 0.5}])", "layers[0].g", "cannot be combined with a preset"},
        Bad{R"([{"preset": "skin1", "sigma_a": 0.5}])", "layers[0].sigma_a", "cannot be combined"},
        Bad{R"([{"preset": "skin1", "eta": 1.3}])", "layers[0].eta", "cannot be combined"},
        Bad{R"([{"thickness_mm": 1, "g": 0.5}, {"preset": "skin1"}])", "layers[0]",
            "needs a preset, or sigma_a and sigma_s"},
        Bad{R"([{"sigma_a": 0.1}])", "layers[0].sigma_s", "is required"},
        Bad{R"([{"sigma_s": 1}])", "layers[0].sigma_a", "is required"},
        Bad{R"([{"sigma_a": 0.1, "sigma_s": 10, "thickness_mm": 1},
               {"sigma_a": [1, 2, "x"], "sigma_s": 1}])",
            "layers[1].sigma_a[2]", "must be a number"},
        Bad{R"([{"sigma_a": [0.1, 0.2], "sigma_s": 10}])", "layers[0].sigma_a", "array of 3"},
        Bad{R"([{"sigma_a": "0.1", "sigma_s": 10}])", "layers[0].sigma_a", "array of 3"},
        Bad{R"([{"sigma_a": -0.1, "sigma_s": 10}])", "layers[0].sigma_a", ""},
        Bad{R"([{"sigma_a": 0.1, "sigma_s": 10, "thickness_mm": 1},
               {"sigma_a": [0.1, 0.1, -0.1], "sigma_s": 10}])",
            "layers[1].sigma_a[2]", ""},
        Bad{R"([{"sigma_a": 0.1, "sigma_s": [10, -1, 10]}])", "layers[0].sigma_s[1]", ""},
        Bad{R"([{"sigma_a": 0.1, "sigma_s": 10, "g": 1}])", "layers[0].g", ""},
        Bad{R"([{"sigma_a": 0.1, "sigma_s": 10, "g": [0, 0, -1.5]}])", "layers[0].g[2]", ""},
        Bad{R"([{"sigma_a": 0.1, "sigma_s": 10, "eta": 3}])", "layers[0].eta", ""},
        Bad{R"([{"sigma_a": 0, "sigma_s": 10}])", "layers[0].sigma_a", "albedo of 1"},
        // Every layer has the top layer's eta, wherever it came from.
        Bad{R"([{"sigma_a": 0.1, "sigma_s": 10, "thickness_mm": 1},
               {"sigma_a": 0.1, "sigma_s": 10, "eta": 1.4}])",
            "layers[1].eta", "index-matched"},
        Bad{R"([{"sigma_a": 0.1, "sigma_s": 10, "thickness_mm": 1},
               {"sigma_a": 0.1, "sigma_s": 10, "eta": [1.3, 1.3, 1.5]}])",
            "layers[1].eta[2]", "the top layer's is 1.3"},
        Bad{R"([{"sigma_a": 0.1, "sigma_s": 10, "eta": 1.4, "thickness_mm": 1},
               {"sigma_a": 0.1, "sigma_s": 10}])",
            "layers[1].eta", "the default"},
        Bad{R"([{"preset": "skin1", "thickness_mm": 1}, {"preset": "marble"}])",
            "layers[1].preset", "has eta 1.5"}),
    BadName());

TEST(SssLayers, NanThicknessIsRefused) {
  // JSON text cannot spell NaN, but a document built in code (a glTF's extras) can.
  nlohmann::json layers = nlohmann::json::array();
  layers.push_back({{"preset", "skin1"}, {"thickness_mm", std::nan("")}});
  auto r = parse_sss_layers(layers);
  ASSERT_TRUE(std::holds_alternative<FieldError>(r));
  EXPECT_EQ(std::get<FieldError>(r).field, "layers[0].thickness_mm");
  layers[0]["thickness_mm"] = kInf;  // semi-infinite is said by leaving it out
  r = parse_sss_layers(layers);
  ASSERT_TRUE(std::holds_alternative<FieldError>(r));
  EXPECT_EQ(std::get<FieldError>(r).field, "layers[0].thickness_mm");
}

TEST(SssLayers, TheFilesOwnErrors) {
  // The document: only {"layers": [...]}.
  EXPECT_EQ(parse_error(R"({})").field, "layers");
  EXPECT_NE(parse_error(R"({})").message.find("is required"), std::string::npos);
  EXPECT_EQ(parse_error(R"({"layers": [{"preset": "skin1"}], "version": 1})").field, "version");
  EXPECT_EQ(parse_error(R"([{"preset": "skin1"}])").field, "");
  EXPECT_NE(parse_error(R"([{"preset": "skin1"}])").message.find("JSON object"), std::string::npos);
  EXPECT_EQ(parse_error(std::string(100, '[') + std::string(100, ']')).field, "");

  // The file: every error about it names it.
  const std::string missing =
      (fs::temp_directory_path() / ("sss-layers-" + std::to_string(::getpid()) + "-none.json")).string();
  auto r = parse_sss_layers_file(missing);
  ASSERT_TRUE(std::holds_alternative<FieldError>(r));
  EXPECT_EQ(std::get<FieldError>(r).field, missing);
  EXPECT_NE(std::get<FieldError>(r).message.find("cannot be opened"), std::string::npos);

  r = parse_sss_layers_file(fs::temp_directory_path().string());
  ASSERT_TRUE(std::holds_alternative<FieldError>(r));
  EXPECT_EQ(std::get<FieldError>(r).field, fs::temp_directory_path().string());
  EXPECT_NE(std::get<FieldError>(r).message.find("directory"), std::string::npos);

  const TempFile malformed("malformed.json", "{\"layers\": [\n  {\"preset\": \"skin1\",}\n]}");
  r = parse_sss_layers_file(malformed.path());
  ASSERT_TRUE(std::holds_alternative<FieldError>(r));
  EXPECT_EQ(std::get<FieldError>(r).field, malformed.path());
  const std::string& message = std::get<FieldError>(r).message;
  EXPECT_NE(message.find("is not valid JSON"), std::string::npos) << message;
  EXPECT_NE(message.find("line 2"), std::string::npos) << message;
  EXPECT_EQ(message.find("[json.exception"), std::string::npos) << message;

  const TempFile empty("empty.json", "");
  r = parse_sss_layers_file(empty.path());
  ASSERT_TRUE(std::holds_alternative<FieldError>(r));
  EXPECT_EQ(std::get<FieldError>(r).field, empty.path());

  // An error inside the document names the field, not the file.
  const TempFile bad_layer("bad-layer.json", R"({"layers": [{"preset": "jade"}]})");
  r = parse_sss_layers_file(bad_layer.path());
  ASSERT_TRUE(std::holds_alternative<FieldError>(r));
  EXPECT_EQ(std::get<FieldError>(r).field, "layers[0].preset");
  const TempFile no_layers("no-layers.json", R"({"stack": []})");
  r = parse_sss_layers_file(no_layers.path());
  ASSERT_TRUE(std::holds_alternative<FieldError>(r));
  EXPECT_EQ(std::get<FieldError>(r).field, "stack");
}

}  // namespace
}  // namespace sss::scene
