# The interactive viewer's window (`tessera view` without --headless): a module,
# libtessera_view_window.so beside the tessera executable, built from
# host/view/window/view_window.cpp with GLFW, OpenGL and Dear ImGui (Debian's
# libglfw3-dev, libgl-dev, libimgui-dev), and Xlib (libx11-dev) for its X error handlers. `tessera view` loads it with dlopen, so no other
# command needs these libraries at run time. TESSERA_VIEWER: AUTO builds it when all are
# found (else a message says why not, and `tessera view` without --headless explains it
# at run time), ON requires them, OFF never builds it.
set(TESSERA_VIEWER AUTO CACHE STRING "Build the viewer window module: AUTO, ON or OFF")
set_property(CACHE TESSERA_VIEWER PROPERTY STRINGS AUTO ON OFF)

set(tessera_viewer_missing "")
if(NOT TESSERA_VIEWER STREQUAL "OFF")
  find_package(PkgConfig QUIET)
  if(PkgConfig_FOUND)
    pkg_check_modules(GLFW3 QUIET IMPORTED_TARGET glfw3)
    pkg_check_modules(TESSERA_X11 QUIET IMPORTED_TARGET x11)
  endif()
  set(OpenGL_GL_PREFERENCE GLVND)
  find_package(OpenGL QUIET)
  find_path(IMGUI_INCLUDE_DIR imgui.h PATH_SUFFIXES imgui)
  find_library(IMGUI_LIBRARY imgui)
  # Debian's libimgui.a may lack the GLFW and OpenGL 3 backends; their sources ship as
  # examples, and are compiled into the module when present.
  find_path(IMGUI_BACKEND_SOURCES imgui_impl_glfw.cpp
            PATHS /usr/share/doc/libimgui-dev/examples/backends NO_DEFAULT_PATH)
  if(NOT GLFW3_FOUND)
    list(APPEND tessera_viewer_missing "GLFW (libglfw3-dev)")
  endif()
  if(NOT TESSERA_X11_FOUND)
    list(APPEND tessera_viewer_missing "Xlib (libx11-dev)")
  endif()
  if(NOT OpenGL_FOUND)
    list(APPEND tessera_viewer_missing "OpenGL (libgl-dev)")
  endif()
  if(NOT IMGUI_INCLUDE_DIR OR NOT IMGUI_LIBRARY)
    list(APPEND tessera_viewer_missing "Dear ImGui (libimgui-dev)")
  endif()
endif()

if(TESSERA_VIEWER STREQUAL "OFF")
  message(STATUS "Viewer window: off (TESSERA_VIEWER=OFF); `tessera view --headless` still works")
elseif(tessera_viewer_missing)
  list(JOIN tessera_viewer_missing ", " tessera_viewer_missing_text)
  if(TESSERA_VIEWER STREQUAL "ON")
    message(FATAL_ERROR "TESSERA_VIEWER=ON but not found: ${tessera_viewer_missing_text}")
  endif()
  message(STATUS "Viewer window: not built (not found: ${tessera_viewer_missing_text}); "
                 "`tessera view --headless` still works")
else()
  set(tessera_viewer_sources ${CMAKE_SOURCE_DIR}/host/view/window/view_window.cpp
                             ${CMAKE_SOURCE_DIR}/host/view/window/x11_errors.cpp)
  if(IMGUI_BACKEND_SOURCES)
    list(APPEND tessera_viewer_sources ${IMGUI_BACKEND_SOURCES}/imgui_impl_glfw.cpp
                                       ${IMGUI_BACKEND_SOURCES}/imgui_impl_opengl3.cpp)
  endif()
  add_library(tessera_view_window MODULE ${tessera_viewer_sources})
  set_target_properties(tessera_view_window PROPERTIES
    PREFIX "lib" OUTPUT_NAME tessera_view_window LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR})
  target_include_directories(tessera_view_window PRIVATE ${CMAKE_SOURCE_DIR}/host ${IMGUI_INCLUDE_DIR}
                           ${IMGUI_INCLUDE_DIR}/backends)
  target_compile_definitions(tessera_view_window PRIVATE GL_GLEXT_PROTOTYPES)
  # The vendored-by-Debian backend sources are not ours to fix: no warnings from them.
  if(IMGUI_BACKEND_SOURCES)
    set_source_files_properties(${IMGUI_BACKEND_SOURCES}/imgui_impl_glfw.cpp
                                ${IMGUI_BACKEND_SOURCES}/imgui_impl_opengl3.cpp PROPERTIES COMPILE_OPTIONS "-w")
  endif()
  # Debian's libimgui.a takes its font rasteriser (stb_truetype) from libstb: the module
  # links it itself rather than leaning on the executable's symbols (dlopen found them
  # there only while the executable used stb).
  target_link_libraries(tessera_view_window PRIVATE PkgConfig::GLFW3 PkgConfig::TESSERA_X11 OpenGL::GL ${IMGUI_LIBRARY}
                        PkgConfig::STB)
  add_dependencies(tessera tessera_view_window)
  target_compile_definitions(tessera_core PRIVATE TESSERA_VIEW_WINDOW=1)
  set(TESSERA_VIEWER_BUILT ON)
  message(STATUS "Viewer window: libtessera_view_window.so (GLFW, OpenGL, Dear ImGui)")
endif()
