// Per-pixel Monte Carlo frames in pieces: the ground truth (issue 16, GroundTruth.h) and the
// diffusion reference's probe estimator (issue 17, ProbeReference.h). A tile is a pair of
// EXRs (mean and variance) of the whole frame's size that hold the rows it rendered (rows y
// with y mod N = K - 1, interleaved so that every tile sees the same mix of easy and hard
// rows; the other rows are 0 with alpha 0). Both renderers draw sample k of pixel i from
// its own stream (seed, i, k), so a tile's rows are bit for bit the whole frame's. Every
// such EXR says what it is in string attributes of its header:
//   sssContent   "mean" or "variance"
//   sssTile      "K/N" (absent on a whole frame)
//   sssSettings  every option that changes the pixels (the tool's command line without the
//                output names, --tile, --threads and the display options)
//   sssSpp       samples per pixel
//   sssRelativeStandardError  of the pixels it holds (GroundTruth.h)
// merge_tiles() checks that the files are the mean and variance tiles of one render, each
// once, and copies each row from the tile that owns it: the frame and its variance are bit
// for bit what one process renders with the same settings, and get the same attributes,
// so the merged files are byte-identical to a single render's.
#pragma once

#include "image/Image.h"

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace sss::reference {

struct TileSpec {
  std::uint32_t index = 1;  // K, 1-based
  std::uint32_t count = 1;  // N
  bool whole() const { return count == 1; }
  bool owns_row(std::uint32_t y) const { return y % count == index - 1; }
};
// "K/N" with 1 <= K <= N; the error says what is wrong with the text.
std::optional<TileSpec> parse_tile(const std::string& text, std::string& error);
// Throws std::invalid_argument ("tile: ...") unless `tile` is K/N with 1 <= K <= N, the
// image has at least N rows, and the render runs a fixed number of samples (a target error
// is a property of the whole frame, which a tile cannot measure).
void check_tile(const TileSpec& tile, std::uint32_t height, double target_error);

inline constexpr const char* kAttrContent = "sssContent";
inline constexpr const char* kAttrTile = "sssTile";
inline constexpr const char* kAttrSettings = "sssSettings";
inline constexpr const char* kAttrSpp = "sssSpp";
inline constexpr const char* kAttrRelativeError = "sssRelativeStandardError";

// The value of an attribute, if the image has it.
std::optional<std::string> attribute(const image::Image& image, const std::string& name);

// The attributes of a ground-truth output (mean or variance image).
std::vector<std::pair<std::string, std::string>> ground_truth_attributes(const std::string& content,
                                                                         const std::string& tile,
                                                                         const std::string& settings,
                                                                         std::uint64_t spp, double relative_error);

struct MergedFrame {
  image::Image mean, variance;
  std::uint32_t tiles = 0;
};

// The files may be given in any order, mean and variance tiles mixed; every one of the N
// of each must be there. Errors name the file and what does not fit ("b.exr: tile 2/4 again (also a.exr)", "tile 3/4 is missing",
// "c.exr: rendered with other settings than a.exr: ...").
std::variant<MergedFrame, std::string> merge_tiles(const std::vector<std::string>& files);

}  // namespace sss::reference
