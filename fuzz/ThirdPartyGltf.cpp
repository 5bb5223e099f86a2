// libFuzzer build only: tinygltf 2.7.0's implementation from Debian's header
// (libtinygltf-dev), with the same defaults as the loader's includes (GltfContext.h),
// instrumented, interposing on libtinygltf.so (see ThirdPartyStb.cpp). stb_image and
// stb_image_write are declared here and defined by ThirdPartyStb.cpp / libstb.so.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
