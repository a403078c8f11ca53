// The implementations of tinyobjloader and stb_image, compiled into the fuzzer (with its
// instrumentation) instead of linking Debian's shared libraries.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
