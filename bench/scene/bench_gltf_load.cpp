// What compressed glTF costs to load (issue 21): load_gltf on the same model as written
// uncompressed (the baseline, measured in the same process), quantized by gltfpack,
// meshopt-compressed by gltfpack (-c, and -cc with the octahedral filter) and
// Draco-compressed by glTF-Transform (tools/node/variants.mjs). The variants are written
// once into a temporary folder by the tools the tests use; a variant whose tool is missing
// is skipped with a message. Models: assets/bunny.glb (1.8 k vertices) and assimp's
// 2CylinderEngine (Debian's assimp-testmodels, 34 meshes, 110 k triangles).
// Counter vs_uncompressed: this variant's load time over the uncompressed file's.
//   scripts/bench.sh --benchmark_filter='GltfLoad'
#include "scene/GltfLoader.h"

#include <benchmark/benchmark.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <variant>

namespace {

namespace fs = std::filesystem;

struct Model {
  const char* name;
  fs::path path;
};

const Model kModels[] = {
    {"bunny", fs::path(SSS_SOURCE_DIR) / "assets" / "bunny.glb"},
    {"engine", "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"},
};

struct Variant {
  const char* name;
  const char* command;  // IN and OUT are replaced; empty: the file itself
};

const Variant kVariants[] = {
    {"uncompressed", ""},
    {"gltfpack", "gltfpack -i IN -o OUT"},
    {"gltfpack-c", "gltfpack -c -i IN -o OUT"},
    {"gltfpack-cc", "gltfpack -cc -i IN -o OUT"},
    {"draco", "node " SSS_SOURCE_DIR "/tools/node/variants.mjs IN OUT draco"},
};

fs::path folder() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("sss_bench_gltf_" + std::to_string(::getpid()));
    fs::create_directories(d);
    std::atexit([] { fs::remove_all(fs::temp_directory_path() / ("sss_bench_gltf_" + std::to_string(::getpid()))); });
    return d;
  }();
  return dir;
}

// The variant's file, written on first use; empty when its tool failed or is missing.
fs::path variant_file(const Model& m, const Variant& v) {
  static std::map<std::string, fs::path> made;
  const std::string key = std::string(m.name) + "/" + v.name;
  if (auto it = made.find(key); it != made.end()) return it->second;
  fs::path out;
  if (!fs::exists(m.path)) {
  } else if (*v.command == '\0') {
    out = m.path;
  } else {
    std::string cmd = v.command;
    const fs::path file = folder() / (key.substr(0, key.find('/')) + "_" + v.name + ".glb");
    cmd.replace(cmd.find("IN"), 2, "'" + m.path.string() + "'");
    cmd.replace(cmd.find("OUT"), 3, "'" + file.string() + "'");
    if (std::system((cmd + " >/dev/null 2>&1").c_str()) == 0 && fs::exists(file)) out = file;
  }
  made[key] = out;
  return out;
}

double seconds_per_load(const fs::path& file) {
  const auto start = std::chrono::steady_clock::now();
  int n = 0;
  while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(500)) {
    benchmark::DoNotOptimize(sss::scene::load_gltf(file.string()));
    ++n;
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / n;
}

double baseline(const Model& m) {
  static std::map<std::string, double> s;
  if (!s.count(m.name)) s[m.name] = seconds_per_load(m.path);
  return s[m.name];
}

void BM_GltfLoad(benchmark::State& state) {
  const Model& m = kModels[state.range(0)];
  const Variant& v = kVariants[state.range(1)];
  const fs::path file = variant_file(m, v);
  if (file.empty()) {
    state.SkipWithError((std::string(m.name) + " " + v.name + ": model or tool missing").c_str());
    return;
  }
  auto first = sss::scene::load_gltf(file.string());
  if (first.index() != 0) {
    state.SkipWithError(std::get<sss::scene::LoadError>(first).what().c_str());
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(sss::scene::load_gltf(file.string()));
  state.SetLabel(std::string(m.name) + " " + v.name + ", " + std::to_string(fs::file_size(file) / 1024) + " KiB");
  const double per = seconds_per_load(file);
  state.counters["vs_uncompressed"] = per / baseline(m);
  state.counters["ms"] = per * 1e3;
}
BENCHMARK(BM_GltfLoad)->ArgsProduct({{0, 1}, {0, 1, 2, 3, 4}})->Unit(benchmark::kMillisecond);

}  // namespace
