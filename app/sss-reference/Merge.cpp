#include "Merge.h"

#include "CliSupport.h"

#include "profiles/Medium.h"
#include "image/Image.h"
#include "image/Tonemap.h"
#include "reference/TileMerge.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>

namespace sss::app {

namespace {

int merge_usage(const std::string& message) { return usage_error("sss-reference merge", message); }

}  // namespace

bool folders_exist(const std::vector<const std::string*>& files) {
  for (const std::string* file : files) {
    if (file->empty()) continue;
    const std::filesystem::path parent = std::filesystem::path(*file).parent_path();
    std::error_code ec;
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
      std::cerr << "sss-reference: error: " << *file << ": the folder " << parent.string()
                << " does not exist or is not a folder\n";
      return false;
    }
  }
  return true;
}

int merge_main(int argc, char** argv) {
  CLI::App app{"sss-reference merge: put the tiles of one random-walk or probe render (--tile K/N) back together into the "
               "frame and its variance, bit for bit what one process renders",
               "sss-reference merge"};
  std::vector<std::string> tiles;
  std::string out, variance, png;
  float exposure = 1.0f;
  app.add_option("tiles", tiles, "The mean and variance EXRs of every tile, in any order")->required();
  app.add_option("--out", out, "The frame: FILE.exr")->required();
  app.add_option("--variance", variance, "Its variance of the mean: FILE.exr");
  app.add_option("--png", png, "Also the tonemapped frame as a PNG");
  app.add_option("--exposure", exposure, "Exposure of the PNG (default 1)");
  if (const auto stop = parse_command_line(app, argc, argv, "sss-reference merge")) return *stop;
  if (lower_extension(out) != ".exr") return merge_usage("--out: expected a .exr file name, got '" + out + "'");
  if (!variance.empty() && lower_extension(variance) != ".exr")
    return merge_usage("--variance: expected a .exr file name, got '" + variance + "'");
  if (!png.empty() && lower_extension(png) != ".png") return merge_usage("--png: expected a .png file name, got '" + png + "'");
  if (!(std::isfinite(exposure) && exposure > 0.0f))
    return merge_usage("--exposure: expected a finite number > 0, got " + message_number(exposure));
  for (const std::string& t : tiles)
    for (const std::string* o : {&out, &variance, &png})
      if (!o->empty() && std::filesystem::weakly_canonical(t) == std::filesystem::weakly_canonical(*o))
        return merge_usage(*o + " is one of the tiles; write the frame elsewhere");
  if (!variance.empty() && std::filesystem::weakly_canonical(variance) == std::filesystem::weakly_canonical(out))
    return merge_usage("--variance: the same file as --out");
  if (!png.empty() && std::filesystem::weakly_canonical(png) == std::filesystem::weakly_canonical(out))
    return merge_usage("--png: the same file as --out");
  if (!folders_exist({&out, &variance, &png})) return kExitRuntime;
  auto merged = reference::merge_tiles(tiles);
  if (auto* e = std::get_if<std::string>(&merged)) return merge_usage(*e);
  const reference::MergedFrame& f = std::get<reference::MergedFrame>(merged);
  try {
    image::write_exr(out, f.mean);
    if (!variance.empty()) image::write_exr(variance, f.variance);
    if (!png.empty()) image::write_png(png, image::tonemap(f.mean, exposure));
  } catch (const std::exception& e) {
    std::cerr << "sss-reference: error: " << e.what() << '\n';
    return kExitRuntime;
  }
  return kExitOk;
}

}  // namespace sss::app
