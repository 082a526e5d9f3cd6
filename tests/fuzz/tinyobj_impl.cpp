// tinyobjloader's implementation, compiled into the fuzz targets with the sanitizers and the
// fuzzer's coverage instrumentation (instead of linking Debian's uninstrumented
// libtinyobjloader_double.so), so that a bug inside tinyobjloader is found and its branches guide
// the fuzzer. TINYOBJLOADER_USE_DOUBLE comes from the command line (tests/fuzz/fuzz.mk), as the
// CMake target tinyobjloader::tinyobjloader_double defines it for tb/scene/obj_loader.cpp.
#ifndef TINYOBJLOADER_USE_DOUBLE
#error "build with -DTINYOBJLOADER_USE_DOUBLE (the scene library uses tinyobjloader_double)"
#endif
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
