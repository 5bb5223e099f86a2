// libFuzzer build only (fuzz/CMakeLists.txt): stb_image's implementation compiled from
// Debian's own header (libstb-dev) with the fuzz preset's instrumentation. The
// executable's definitions interpose on those of libstb.so, so libFuzzer sees the
// decoder's branches and ASan its memory accesses. No code is vendored.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
