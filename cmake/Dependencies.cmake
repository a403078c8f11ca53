# Every dependency is a Debian 12 package; scripts/install-deps lists them.
find_package(embree 3 REQUIRED)
find_package(OpenCL REQUIRED)
find_package(TBB REQUIRED)
find_package(OpenEXR REQUIRED)
find_package(tinyobjloader REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(glm REQUIRED)
find_package(PkgConfig REQUIRED)
# libstb: the tests' independent PNG reader (stb_image, what the previews and textures are
# checked against), and the viewer module's font rasteriser (Debian's imgui uses its
# stb_truetype; cmake/Viewer.cmake).
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)
# JPEG textures (host/scene/jpeg_decode.cpp): libjpeg62-turbo through libjpeg-dev.
find_package(JPEG REQUIRED)
# PNG textures (host/scene/png_decode.cpp) and the PNG previews (host/image/png_io.cpp):
# libpng16 through libpng-dev.
find_package(PNG REQUIRED)
if(NOT TARGET glm::glm)
  add_library(glm::glm INTERFACE IMPORTED)
  target_include_directories(glm::glm INTERFACE ${GLM_INCLUDE_DIRS})
endif()
