# The sources of gpurt_raytrace, listed once: src/raytrace/CMakeLists.txt builds the library from
# both lists and tests/fuzz instruments the GL-free one for libFuzzer. A source that includes
# nothing of src/stream goes in the first.
set(GPURT_RAYTRACE_CPU_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/BenchRays.cpp
  ${CMAKE_CURRENT_LIST_DIR}/Camera.cpp
  ${CMAKE_CURRENT_LIST_DIR}/CpuTracer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/SurfaceTexture.cpp
  ${CMAKE_CURRENT_LIST_DIR}/EmitterTable.cpp
  ${CMAKE_CURRENT_LIST_DIR}/MaterialRecord.cpp
  ${CMAKE_CURRENT_LIST_DIR}/PackedScene.cpp
  ${CMAKE_CURRENT_LIST_DIR}/SceneLoader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/SceneScale.cpp
  ${CMAKE_CURRENT_LIST_DIR}/SceneTextureLayout.cpp
  ${CMAKE_CURRENT_LIST_DIR}/accel/grid/GridCpu.cpp
  ${CMAKE_CURRENT_LIST_DIR}/accel/grid/UniformGrid.cpp)
set(GPURT_RAYTRACE_GL_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/GpuTracer.cpp
  ${CMAKE_CURRENT_LIST_DIR}/SceneTextures.cpp
  ${CMAKE_CURRENT_LIST_DIR}/accel/grid/GridGl.cpp)
