# The sources of gpurt_image, listed once: src/image/CMakeLists.txt builds the library from them
# and tests/fuzz instruments them for libFuzzer (none needs GL).
set(GPURT_IMAGE_SOURCES
  AtomicFile.cpp
  Colour.cpp
  EnvironmentImage.cpp
  ExrIO.cpp
  ImageIO.cpp
  InputError.cpp
  TextureImage.cpp
  Tiles.cpp)
# Full paths, so that tests/fuzz/CMakeLists.txt can use them from its own folder.
list(TRANSFORM GPURT_IMAGE_SOURCES PREPEND ${CMAKE_CURRENT_LIST_DIR}/)
