# The sources of gpurt_raytrace, listed once: src/raytrace/CMakeLists.txt builds the library from
# both lists and tests/fuzz instruments the GL-free one for libFuzzer. A source that includes
# nothing of src/stream goes in the first.
set(GPURT_RAYTRACE_CPU_SOURCES
  AlphaCoverage.cpp
  BenchRays.cpp
  Camera.cpp
  RenderTypes.cpp
  CpuTracer.cpp
  SurfaceTexture.cpp
  EmitterTable.cpp
  EnvironmentTable.cpp
  MaterialRecord.cpp
  PackedScene.cpp
  SceneLoader.cpp
  SceneScale.cpp
  SceneTextureLayout.cpp
  accel/Acceleration.cpp
  accel/SceneBox.cpp
  accel/bvh/Bvh.cpp
  accel/bvh/BvhCpu.cpp
  accel/grid/GridCpu.cpp
  accel/grid/UniformGrid.cpp
  denoise/DenoiseCpu.cpp
  denoise/DenoiseFiles.cpp
  integrators/Registry.cpp
  integrators/ao/AoIntegrator.cpp
  integrators/path/PathCpu.cpp
  integrators/path/PathIntegrator.cpp
  integrators/whitted/WhittedCpu.cpp
  integrators/whitted/WhittedIntegrator.cpp)
set(GPURT_RAYTRACE_GL_SOURCES
  GpuPipeline.cpp
  GpuTracer.cpp
  Renderer.cpp
  SceneTextures.cpp
  accel/bvh/BvhGl.cpp
  accel/grid/GridGl.cpp
  denoise/DenoiseGl.cpp
  integrators/SharedPasses.cpp
  integrators/path/PathGl.cpp
  integrators/path/PathMegakernelGl.cpp
  integrators/Megakernel.cpp
  integrators/GlRegistry.cpp
  integrators/ao/AoGl.cpp
  integrators/whitted/WhittedGl.cpp)
# Full paths, so that tests/fuzz/CMakeLists.txt can use them from its own folder.
list(TRANSFORM GPURT_RAYTRACE_CPU_SOURCES PREPEND ${CMAKE_CURRENT_LIST_DIR}/)
list(TRANSFORM GPURT_RAYTRACE_GL_SOURCES PREPEND ${CMAKE_CURRENT_LIST_DIR}/)
