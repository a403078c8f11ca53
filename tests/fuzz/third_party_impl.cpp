// The implementation of tinyobjloader, compiled into the fuzzer (with its instrumentation)
// instead of linking Debian's shared library.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
