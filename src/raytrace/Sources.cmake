# The sources of gpurt_raytrace, listed once: src/raytrace/CMakeLists.txt builds the library from
# both lists and tests/fuzz instruments the GL-free one for libFuzzer. A source that includes
# nothing of src/stream goes in the first.
set(GPURT_RAYTRACE_CPU_SOURCES
  accel/Acceleration.cpp
  accel/Registry.cpp
  accel/BenchRays.cpp
  accel/SceneBox.cpp
  accel/bvh/Bvh.cpp
  accel/bvh/BvhAccelerator.cpp
  accel/bvh/BvhCpu.cpp
  accel/bvh/BvhTexels.cpp
  accel/grid/GridAccelerator.cpp
  accel/grid/GridCpu.cpp
  accel/grid/GridTexels.cpp
  accel/grid/UniformGrid.cpp
  camera/Camera.cpp
  common/PackedBytes.cpp
  common/RenderTypes.cpp
  denoise/DenoiseCpu.cpp
  denoise/DenoiseFiles.cpp
  integrators/CpuScene.cpp
  integrators/Registry.cpp
  integrators/ao/AoIntegrator.cpp
  integrators/path/PathCpu.cpp
  integrators/path/PathIntegrator.cpp
  integrators/whitted/WhittedCpu.cpp
  integrators/whitted/WhittedIntegrator.cpp
  lights/EmitterTable.cpp
  lights/EnvironmentTable.cpp
  materials/AlphaCoverage.cpp
  materials/MaterialRecord.cpp
  materials/SheenTable.cpp
  materials/SurfaceTexture.cpp
  render/CpuTracer.cpp
  scene/PackedScene.cpp
  scene/packed/Geometry.cpp
  scene/packed/Lights.cpp
  scene/packed/Materials.cpp
  scene/packed/Sections.cpp
  scene/packed/View.cpp
  scene/SceneLoader.cpp
  scene/SceneScale.cpp
  textures/SceneTextureLayout.cpp)
set(GPURT_RAYTRACE_GL_SOURCES
  accel/GlRegistry.cpp
  accel/bvh/BvhGl.cpp
  accel/grid/GridGl.cpp
  denoise/DenoiseGl.cpp
  integrators/GlRegistry.cpp
  integrators/GpuPipeline.cpp
  integrators/Megakernel.cpp
  integrators/SharedPasses.cpp
  integrators/ao/AoGl.cpp
  integrators/path/PathGl.cpp
  integrators/path/PathMegakernelGl.cpp
  integrators/whitted/WhittedGl.cpp
  render/GpuTracer.cpp
  render/Renderer.cpp
  textures/SceneTextures.cpp)
# Full paths, so that tests/fuzz/CMakeLists.txt can use them from its own folder.
list(TRANSFORM GPURT_RAYTRACE_CPU_SOURCES PREPEND ${CMAKE_CURRENT_LIST_DIR}/)
list(TRANSFORM GPURT_RAYTRACE_GL_SOURCES PREPEND ${CMAKE_CURRENT_LIST_DIR}/)
