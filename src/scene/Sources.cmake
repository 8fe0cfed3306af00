# The sources of gpurt_scene, listed once: src/scene/CMakeLists.txt builds the library from them
# and tests/fuzz instruments them for libFuzzer (none needs GL).
set(GPURT_SCENE_SOURCES
  GltfBytes.cpp
  GltfDraco.cpp
  GltfLoader.cpp
  GltfMeshopt.cpp
  JsonScene.cpp
  MaterialModels.cpp
  ObjLoader.cpp
  PlyLoader.cpp
  Scene.cpp
  SceneFile.cpp
  SmoothNormals.cpp)
# Full paths, so that tests/fuzz/CMakeLists.txt can use them from its own folder.
list(TRANSFORM GPURT_SCENE_SOURCES PREPEND ${CMAKE_CURRENT_LIST_DIR}/)
