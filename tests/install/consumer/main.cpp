// Loads a character through the installed library and prints what it holds,
// and the library's version line (which reaches the SIMD dispatch, Highway).
#include <iostream>

#include "asset/gltf_loader.h"
#include "measuring/environment.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: consumer CHARACTER.glb\n";
    return 2;
  }
  const crowdprof::Character character = crowdprof::load_character(argv[1]);
  std::cout << character.skeleton.names.size() << " joints, " << character.mesh.vertex_count() << " vertices, "
            << character.actions.size() << " actions\n"
            << crowdprof::version_line() << "\n";
  return 0;
}
