// The fuzz targets (issue 7, "Robustness"): one plain function per hostile input the
// product reads. Each is called by a libFuzzer executable (fuzz/CMakeLists.txt, built by
// the `fuzz` preset with clang's -fsanitize=fuzzer,address,undefined) and by the replay
// test tests/fuzz/test_fuzz_replay.cpp (the ordinary gcc build and the asan preset),
// which runs every file of fuzz/corpus/<name>/ and fuzz/regressions/<name>/ through it.
//
// Contract: any input is allowed; a rejected input (LoadError, FieldError, ImageError,
// CLI11's ParseError) is the expected outcome and returns 0. A crash, a sanitizer
// report, a hang, an uncaught exception or a broken invariant of an accepted result
// (FuzzSupport.h: fuzz_check aborts) is a bug.
#pragma once

#include <cstddef>
#include <cstdint>

// glTF / GLB through scene::load_gltf (GLB when the bytes start with the "glTF" magic),
// then ensure_sss_atlases as load_scene does; an accepted scene must be consistent.
int sss_fuzz_gltf(const std::uint8_t* data, std::size_t size);
// materials[i].extras.sss: scene::parse_sss_extras_text on the bytes as JSON text.
int sss_fuzz_sss_extras(const std::uint8_t* data, std::size_t size);
// The command line of sss-fit / sss-viewer / sss-reference: the MEDIUM options and the
// material overrides (app/common), the bytes split into argv at NUL and whitespace.
int sss_fuzz_medium_args(const std::uint8_t* data, std::size_t size);
// PNG / EXR through image::read_image, as sss-compare reads its inputs.
int sss_fuzz_image(const std::uint8_t* data, std::size_t size);

struct SssFuzzTarget {
  const char* name;  // fuzz/corpus/<name>/, fuzz/regressions/<name>/, build-fuzz/fuzz/fuzz_<name>
  int (*run)(const std::uint8_t*, std::size_t);
};

inline constexpr SssFuzzTarget kSssFuzzTargets[] = {
    {"gltf", sss_fuzz_gltf},
    {"sss_extras", sss_fuzz_sss_extras},
    {"medium_args", sss_fuzz_medium_args},
    {"image", sss_fuzz_image},
};
