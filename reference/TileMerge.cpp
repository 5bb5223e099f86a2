#include "reference/TileMerge.h"

#include "reference/GroundTruth.h"

#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>

namespace sss::reference {

std::optional<TileSpec> parse_tile(const std::string& text, std::string& error) {
  const auto slash = text.find('/');
  auto number = [](const std::string& s, std::uint32_t& out) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::uint32_t(std::stoul(s));
    return true;
  };
  TileSpec t;
  if (slash == std::string::npos || !number(text.substr(0, slash), t.index) || !number(text.substr(slash + 1), t.count)) {
    error = "expected K/N (tile K of N, e.g. 3/8), got '" + text + "'";
    return std::nullopt;
  }
  if (t.count == 0 || t.index == 0 || t.index > t.count) {
    error = "expected K/N with 1 <= K <= N, got '" + text + "'";
    return std::nullopt;
  }
  return t;
}

void check_tile(const TileSpec& tile, std::uint32_t height, double target_error) {
  if (tile.count == 0 || tile.index == 0 || tile.index > tile.count)
    throw std::invalid_argument("tile: expected K/N with 1 <= K <= N, got " + std::to_string(tile.index) + "/" +
                                std::to_string(tile.count));
  if (tile.count > height)
    throw std::invalid_argument("tile: " + std::to_string(tile.count) + " tiles of interleaved rows need at least " +
                                std::to_string(tile.count) + " rows, the image has " + std::to_string(height));
  if (!tile.whole() && target_error > 0.0)
    throw std::invalid_argument(
        "tile: a target error is a property of the whole frame, so tiles need a fixed --spp (render one tile with "
        "--target-error to learn it)");
}

std::optional<std::string> attribute(const image::Image& image, const std::string& name) {
  for (const auto& [k, v] : image.attributes)
    if (k == name) return v;
  return std::nullopt;
}

std::vector<std::pair<std::string, std::string>> ground_truth_attributes(const std::string& content,
                                                                         const std::string& tile,
                                                                         const std::string& settings,
                                                                         std::uint64_t spp, double relative_error) {
  char error[64];
  std::snprintf(error, sizeof error, "%.9g", relative_error);
  std::vector<std::pair<std::string, std::string>> a = {{kAttrContent, content}};
  if (!tile.empty()) a.emplace_back(kAttrTile, tile);
  a.emplace_back(kAttrSettings, settings);
  a.emplace_back(kAttrSpp, std::to_string(spp));
  a.emplace_back(kAttrRelativeError, error);
  return a;
}

namespace {

struct TileFile {
  std::string path;
  image::Image image;
  std::string content, settings, spp;
  TileSpec tile;
};

// One tile's EXR with its attributes read and checked, or what is wrong with it.
std::variant<TileFile, std::string> read_tile(const std::string& path) {
  auto read = image::read_image(path);
  if (auto* e = std::get_if<image::ImageError>(&read)) return e->what();
  TileFile t;
  t.path = path;
  t.image = std::move(std::get<image::Image>(read));
  const auto content = attribute(t.image, kAttrContent);
  const auto tile = attribute(t.image, kAttrTile);
  const auto settings = attribute(t.image, kAttrSettings);
  const auto spp = attribute(t.image, kAttrSpp);
  if (!content || !settings || !spp)
    return path + ": not a tile of a per-pixel Monte Carlo render (no " + kAttrContent + "/" + kAttrSettings + "/" + kAttrSpp +
           " attributes: written by sss-reference --method random-walk or --estimator probe)";
  if (spp->empty() || spp->size() > 18 || spp->find_first_not_of("0123456789") != std::string::npos)
    return path + ": " + kAttrSpp + " is '" + *spp + "', expected a sample count";
  if (*content != "mean" && *content != "variance")
    return path + ": " + kAttrContent + " is '" + *content + "', expected mean or variance";
  if (!tile) return path + ": a whole frame, not a tile (it has no " + kAttrTile + " attribute): nothing to merge";
  std::string why;
  const std::optional<TileSpec> spec = parse_tile(*tile, why);
  if (!spec) return path + ": " + kAttrTile + ": " + why;
  t.content = *content;
  t.settings = *settings;
  t.spp = *spp;
  t.tile = *spec;
  return t;
}

// The tiles by content (mean, variance) and index; what is duplicated or missing.
std::variant<std::map<std::string, std::vector<const TileFile*>>, std::string> slot_tiles(
    const std::vector<TileFile>& tiles) {
  const std::uint32_t n = tiles.front().tile.count;
  std::map<std::string, std::vector<const TileFile*>> by_content;
  by_content["mean"].assign(n, nullptr);
  by_content["variance"].assign(n, nullptr);
  for (const TileFile& t : tiles) {
    const TileFile*& slot = by_content[t.content][t.tile.index - 1];
    if (slot)
      return t.path + ": " + t.content + " tile " + std::to_string(t.tile.index) + "/" + std::to_string(n) +
             " again (also " + slot->path + ")";
    slot = &t;
  }
  for (const auto& [content, slots] : by_content)
    for (std::uint32_t k = 0; k < n; ++k)
      if (!slots[k])
        return content + " tile " + std::to_string(k + 1) + "/" + std::to_string(n) +
               " is missing (a merge needs the mean and the variance EXR of every tile)";

  return by_content;
}

}  // namespace

std::variant<MergedFrame, std::string> merge_tiles(const std::vector<std::string>& files) {
  if (files.empty()) return std::string("no tiles given");
  std::vector<TileFile> tiles;
  for (const std::string& path : files) {
    auto read = read_tile(path);
    if (auto* e = std::get_if<std::string>(&read)) return *e;
    tiles.push_back(std::move(std::get<TileFile>(read)));
  }
  const TileFile& first = tiles.front();
  auto describe = [](const TileFile& t) {
    return std::to_string(t.image.width) + "x" + std::to_string(t.image.height) + ", " + std::to_string(t.tile.count) +
           " tiles, " + t.spp + " spp, settings '" + t.settings + "'";
  };
  for (const TileFile& t : tiles)
    if (t.image.width != first.image.width || t.image.height != first.image.height || t.tile.count != first.tile.count ||
        t.spp != first.spp || t.settings != first.settings)
      return t.path + ": rendered with other settings than " + first.path + " (" + describe(t) + " against " +
             describe(first) + ")";
  const std::uint32_t n = first.tile.count;
  auto slotted = slot_tiles(tiles);
  if (auto* e = std::get_if<std::string>(&slotted)) return *e;
  auto& by_content = std::get<0>(slotted);
  MergedFrame out;
  out.tiles = n;
  const int w = first.image.width, h = first.image.height;
  for (const char* content : {"mean", "variance"}) {
    image::Image merged(w, h);
    const std::vector<const TileFile*>& slots = by_content[content];
    for (int y = 0; y < h; ++y) {
      const image::Image& src = slots[std::size_t(std::uint32_t(y) % n)]->image;
      std::memcpy(merged.pixel(0, y), src.pixel(0, y), sizeof(float) * 4 * std::size_t(w));
    }
    (std::string(content) == "mean" ? out.mean : out.variance) = std::move(merged);
  }
  const double error = relative_standard_error(out.mean, out.variance);
  const std::uint64_t spp = std::stoull(first.spp);
  out.mean.attributes = ground_truth_attributes("mean", "", first.settings, spp, error);
  out.variance.attributes = ground_truth_attributes("variance", "", first.settings, spp, error);
  return out;
}

}  // namespace sss::reference
