// libFuzzer build only: tinyexr 1.0.1's implementation from Debian's header
// (libtinyexr-dev; zlib for ZIP, TINYEXR_USE_MINIZ 0 as the header defaults), instrumented,
// interposing on libtinyexr.so (see ThirdPartyStb.cpp).
#define TINYEXR_IMPLEMENTATION
#include <tinyexr.h>
