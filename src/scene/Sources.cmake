# The sources of gpurt_scene, listed once: src/scene/CMakeLists.txt builds the library from them
# and tests/fuzz instruments them for libFuzzer (none needs GL).
set(GPURT_SCENE_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/GltfLoader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/JsonScene.cpp
  ${CMAKE_CURRENT_LIST_DIR}/ObjLoader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/PlyLoader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/Scene.cpp
  ${CMAKE_CURRENT_LIST_DIR}/SceneFile.cpp
  ${CMAKE_CURRENT_LIST_DIR}/SmoothNormals.cpp)
