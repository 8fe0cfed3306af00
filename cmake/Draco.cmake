# Google's Draco (Debian libdraco-dev) for glTF's KHR_draco_mesh_compression, as the target
# gpurt_draco: only its decoder. Debian builds Draco with its glTF transcoder, which brings a
# tinygltf and an stb_image of its own (other versions than Debian's libtinygltf): libdraco.so
# exports them, and from libdraco.a the linker would take them in place of libtinygltf's. So gpurt
# links a copy of libdraco.a without that member (tiny_gltf_utils.cc.o), made at configure time.
find_package(draco CONFIG REQUIRED)
get_target_property(_draco_configs draco::draco_static IMPORTED_CONFIGURATIONS)
list(GET _draco_configs 0 _draco_config)
get_target_property(_draco_archive draco::draco_static IMPORTED_LOCATION_${_draco_config})
get_target_property(_draco_includes draco::draco_static INTERFACE_INCLUDE_DIRECTORIES)
set(GPURT_DRACO_ARCHIVE ${CMAKE_BINARY_DIR}/draco/libdraco-decoder.a)
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/draco)
# Made afresh each configure, replacing the one there only if it differs (ar writes deterministic
# archives), so that a configure does not relink everything.
file(COPY_FILE ${_draco_archive} ${GPURT_DRACO_ARCHIVE}.new)
execute_process(COMMAND ${CMAKE_AR} d ${GPURT_DRACO_ARCHIVE}.new tiny_gltf_utils.cc.o RESULT_VARIABLE _draco_ar)
if(NOT _draco_ar EQUAL 0)
  message(FATAL_ERROR "could not take tinygltf out of a copy of ${_draco_archive}")
endif()
file(COPY_FILE ${GPURT_DRACO_ARCHIVE}.new ${GPURT_DRACO_ARCHIVE} ONLY_IF_DIFFERENT)
file(REMOVE ${GPURT_DRACO_ARCHIVE}.new)
add_library(gpurt_draco STATIC IMPORTED)
set_target_properties(gpurt_draco PROPERTIES IMPORTED_LOCATION ${GPURT_DRACO_ARCHIVE}
                                             INTERFACE_INCLUDE_DIRECTORIES "${_draco_includes}")
