// The one translation unit that holds tiny_gltf's implementation, built with Draco.
// Images are never decoded (TINYGLTF_NO_STB_IMAGE and friends, set for every file
// in lib/CMakeLists.txt): crowdprof needs geometry and animation only, and
// skipping stb_image keeps a whole class of hostile-input bugs out of the process.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
