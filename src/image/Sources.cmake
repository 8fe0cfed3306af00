# The sources of gpurt_image, listed once: src/image/CMakeLists.txt builds the library from them
# and tests/fuzz instruments them for libFuzzer (none needs GL).
set(GPURT_IMAGE_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/AtomicFile.cpp
  ${CMAKE_CURRENT_LIST_DIR}/Colour.cpp
  ${CMAKE_CURRENT_LIST_DIR}/ExrIO.cpp
  ${CMAKE_CURRENT_LIST_DIR}/ImageIO.cpp
  ${CMAKE_CURRENT_LIST_DIR}/TextureImage.cpp
  ${CMAKE_CURRENT_LIST_DIR}/Tiles.cpp)
