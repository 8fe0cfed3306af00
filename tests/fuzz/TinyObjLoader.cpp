// tinyobjloader's implementation, compiled into the fuzz build so that it is instrumented too (the
// product links Debian's prebuilt library, which is the same version of this header).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
