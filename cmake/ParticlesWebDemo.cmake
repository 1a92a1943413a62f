# particle-demo as a web page (included by demos/CMakeLists.txt under
# Emscripten; scripts/build-web.sh): the desktop's sources with the page's
# platform layer (demos/gui/web/), Emscripten's GLUT on a WebGL 2 canvas, Dear
# ImGui compiled from its sources, and the page build-web/particle-demo.html
# with its .js and .wasm, the scene files and the panel's font embedded.
set(PARTICLES_IMGUI_SOURCE "" CACHE PATH "Dear ImGui's source folder (imgui.cpp; apt-get source imgui)")
if(NOT EXISTS ${PARTICLES_IMGUI_SOURCE}/imgui.cpp)
  message(FATAL_ERROR "Dear ImGui's sources not found: set PARTICLES_IMGUI_SOURCE (scripts/build-web.sh fetches them)")
endif()
set(imgui ${PARTICLES_IMGUI_SOURCE})
set(imgui_sources ${imgui}/imgui.cpp ${imgui}/imgui_draw.cpp ${imgui}/imgui_tables.cpp ${imgui}/imgui_widgets.cpp
    ${imgui}/backends/imgui_impl_glut.cpp ${imgui}/backends/imgui_impl_opengl3.cpp)
set(web ${PROJECT_SOURCE_DIR}/demos/gui/web)
target_sources(particle-demo PRIVATE ${web}/page.cpp ${web}/screenshot.cpp ${imgui_sources})
set_source_files_properties(${imgui_sources} PROPERTIES COMPILE_OPTIONS "-w")
# web/ first: its GL/freeglut.h stands in for freeglut's.
target_include_directories(particle-demo BEFORE PRIVATE ${web})
target_include_directories(particle-demo PRIVATE ${imgui})
target_compile_definitions(particle-demo PRIVATE IMGUI_IMPL_OPENGL_ES3)

# The scene files where the desktop's working folder has them (scenes/…, as
# `--scene-file scenes/rod.json`), and the font where Debian puts it.
set(font /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf)
if(NOT EXISTS ${font})
  message(FATAL_ERROR "${font} not found (Debian's fonts-dejavu-core; scripts/build-web.sh installs it)")
endif()
file(GLOB scene_files CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/demos/scenes/*.json)
# (SHELL: keeps each --embed-file with its file: CMake merges repeated options.)
set(embedded "SHELL:--embed-file ${font}@${font}")
foreach(file IN LISTS scene_files)
  get_filename_component(name ${file} NAME)
  list(APPEND embedded "SHELL:--embed-file ${file}@/scenes/${name}")
endforeach()
set(page ${web}/particle-demo.html)
target_link_options(particle-demo PRIVATE
  -fexceptions -sMIN_WEBGL_VERSION=2 -sMAX_WEBGL_VERSION=2 -sALLOW_MEMORY_GROWTH=1
  -sEXPORTED_RUNTIME_METHODS=FS -sMINIFY_HTML=0 --shell-file ${page} ${embedded})
set_target_properties(particle-demo PROPERTIES SUFFIX ".html" RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}
                      LINK_DEPENDS "${page};${scene_files}")
# The folder's index opens the page with the same query.
file(WRITE ${CMAKE_BINARY_DIR}/index.html
  "<!doctype html><meta charset=\"utf-8\"><title>particle-lab demo</title>\n"
  "<script>location.replace('particle-demo.html' + location.search)</script>\n"
  "<a href=\"particle-demo.html\">particle-demo.html</a>\n")
