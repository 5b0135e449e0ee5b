# Adds every direct subfolder of DIR that has a CMakeLists.txt, in name order.
function(slide_add_subdirs dir)
  file(GLOB children RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/${dir} CONFIGURE_DEPENDS
       ${CMAKE_CURRENT_SOURCE_DIR}/${dir}/*/CMakeLists.txt)
  list(SORT children)
  foreach(child ${children})
    get_filename_component(sub ${child} DIRECTORY)
    add_subdirectory(${dir}/${sub})
  endforeach()
endfunction()

# slide_library(NAME area SOURCES ... DEPS ...): one library target per lib area,
# named slide_<area>, with lib/ as its include root (#include "objects/object.h").
function(slide_library area)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  add_library(slide_${area} ${A_SOURCES})
  target_include_directories(slide_${area} PUBLIC ${PROJECT_SOURCE_DIR}/lib)
  target_link_libraries(slide_${area} PUBLIC ${A_DEPS})
endfunction()

# slide_executable(name SOURCES ... DEPS ...): a daemon or tool binary, placed in build/bin.
function(slide_executable name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_DEPS})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/bin)
endfunction()

# slide_test(name SOURCES ... DEPS ... [LABELS ...]): a GoogleTest binary registered with ctest.
# Tests labelled "scenario" are long and excluded from the default suite.
function(slide_test name)
  cmake_parse_arguments(A "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${A_SOURCES})
  target_link_libraries(${name} PRIVATE ${A_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    SLIDE_SOURCE_DIR="${PROJECT_SOURCE_DIR}" SLIDE_BINARY_DIR="${PROJECT_BINARY_DIR}")
  set(props)
  if(A_LABELS)
    set(props PROPERTIES LABELS "${A_LABELS}")
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 ${props})
endfunction()
