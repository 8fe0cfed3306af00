# Embeds every file under glsl/ into the binary (a table of path -> contents), so that gpurt runs
# from any folder; --glsl-dir loads the same paths from disk instead.
file(GLOB_RECURSE GPURT_GLSL_FILES CONFIGURE_DEPENDS
     RELATIVE ${CMAKE_SOURCE_DIR}/glsl
     ${CMAKE_SOURCE_DIR}/glsl/*.glsl ${CMAKE_SOURCE_DIR}/glsl/*.frag ${CMAKE_SOURCE_DIR}/glsl/*.vert
     ${CMAKE_SOURCE_DIR}/glsl/*.h)
list(SORT GPURT_GLSL_FILES)
set(GPURT_GLSL_ABSOLUTE "")
foreach(f ${GPURT_GLSL_FILES})
  list(APPEND GPURT_GLSL_ABSOLUTE ${CMAKE_SOURCE_DIR}/glsl/${f})
endforeach()
set(GPURT_EMBEDDED_GLSL ${CMAKE_BINARY_DIR}/generated/EmbeddedGlsl.cpp)
add_custom_command(
  OUTPUT ${GPURT_EMBEDDED_GLSL}
  COMMAND ${CMAKE_COMMAND} -DGLSL_ROOT=${CMAKE_SOURCE_DIR}/glsl "-DGLSL_FILES=${GPURT_GLSL_FILES}"
          -DOUTPUT=${GPURT_EMBEDDED_GLSL} -P ${CMAKE_SOURCE_DIR}/cmake/EmbedGlslScript.cmake
  DEPENDS ${GPURT_GLSL_ABSOLUTE} ${CMAKE_SOURCE_DIR}/cmake/EmbedGlslScript.cmake
  COMMENT "Embedding GLSL sources"
  VERBATIM)
