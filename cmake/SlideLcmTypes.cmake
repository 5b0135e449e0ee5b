# Generates C++ headers from lcmtypes/ at build time, their decoders hardened against hostile length
# fields (cmake/lcm_gen_checked.cmake), and, when javac exists, a jar for lcm-spy.
file(GLOB_RECURSE SLIDE_LCM_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/lcmtypes/*.lcm)
set(SLIDE_LCM_CPP_DIR ${PROJECT_BINARY_DIR}/lcmtypes/cpp)
set(SLIDE_LCM_JAVA_DIR ${PROJECT_BINARY_DIR}/lcmtypes/java)
set(SLIDE_LCM_STAMP ${PROJECT_BINARY_DIR}/lcmtypes/cpp.stamp)
add_custom_command(
  OUTPUT ${SLIDE_LCM_STAMP}
  COMMAND ${CMAKE_COMMAND} -E rm -rf ${SLIDE_LCM_CPP_DIR}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${SLIDE_LCM_CPP_DIR}
  COMMAND ${LCM_GEN} --cpp --cpp-std c++11 --cpp-hpath ${SLIDE_LCM_CPP_DIR} ${SLIDE_LCM_FILES}
  COMMAND ${CMAKE_COMMAND} -DDIR=${SLIDE_LCM_CPP_DIR} -P ${PROJECT_SOURCE_DIR}/cmake/lcm_gen_checked.cmake
  COMMAND ${CMAKE_COMMAND} -E touch ${SLIDE_LCM_STAMP}
  DEPENDS ${SLIDE_LCM_FILES} ${PROJECT_SOURCE_DIR}/cmake/lcm_gen_checked.cmake
  COMMENT "lcm-gen: C++ types from lcmtypes/, every length field bounded (cmake/lcm_gen_checked.cmake)")
add_custom_target(slide_lcmtypes_gen DEPENDS ${SLIDE_LCM_STAMP})
add_library(slide_lcmtypes INTERFACE)
add_dependencies(slide_lcmtypes slide_lcmtypes_gen)
target_include_directories(slide_lcmtypes INTERFACE ${SLIDE_LCM_CPP_DIR})
target_link_libraries(slide_lcmtypes INTERFACE PkgConfig::LCM)
# LCM 1.3.1's coretypes encode a double through an int64_t pointer: under GCC's strict aliasing
# (-O2 and up) a value stored just before encode() can be sent as the old one (a NaN or 12.5
# assigned to a zeroed message encodes as 0). Every target that includes the types turns it off.
target_compile_options(slide_lcmtypes INTERFACE -fno-strict-aliasing)

find_file(LCM_JAR lcm.jar PATHS /usr/share/java /usr/local/share/java)
if(Java_JAVAC_EXECUTABLE AND LCM_JAR)
  set(SLIDE_LCM_JAR ${PROJECT_BINARY_DIR}/slide_lcmtypes.jar)
  add_custom_command(
    OUTPUT ${SLIDE_LCM_JAR}
    COMMAND ${PROJECT_SOURCE_DIR}/cmake/build_types_jar.sh ${Java_JAVAC_EXECUTABLE} ${Java_JAR_EXECUTABLE}
            ${LCM_JAR} ${SLIDE_LCM_JAR} ${SLIDE_LCM_JAVA_DIR} ${SLIDE_LCM_FILES}
    DEPENDS ${SLIDE_LCM_FILES} ${PROJECT_SOURCE_DIR}/cmake/build_types_jar.sh
    COMMENT "lcm-gen: Java jar of the types for lcm-spy")
  add_custom_target(slide_lcmtypes_jar ALL DEPENDS ${SLIDE_LCM_JAR})
else()
  message(STATUS "javac or lcm.jar not found: skipping the lcm-spy types jar")
endif()
