// tinygltf's implementation, compiled into the fuzz build so that it is instrumented too (the
// product links Debian's prebuilt library, built from this header). Without stb_image
// (TINYGLTF_NO_STB_IMAGE and _WRITE, set for the whole fuzz library in CMakeLists.txt): gpurt
// installs its own image callback (it decodes no textures yet), and never writes glTF.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
