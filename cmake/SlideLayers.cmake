# The robot's core and its tooling (README, "Library areas"). Tooling areas serve development
# only (the simulator and its scenarios, evaluation, plots, benchmarks and their reports); a core
# area or a daemon that links one, directly or through other targets, fails the configure step.
set(SLIDE_TOOLING_AREAS simulator graph_scenario mapped_robot eval plot bench report)

# The targets a target links, directly or through others (imported targets are not followed).
function(slide_link_closure target out)
  set(seen)
  set(queue ${target})
  while(queue)
    list(POP_FRONT queue t)
    if(NOT TARGET ${t} OR t IN_LIST seen)
      continue()
    endif()
    list(APPEND seen ${t})
    get_target_property(imported ${t} IMPORTED)
    if(imported)
      continue()
    endif()
    get_target_property(direct ${t} LINK_LIBRARIES)
    get_target_property(iface ${t} INTERFACE_LINK_LIBRARIES)
    foreach(dep IN LISTS direct iface)
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" dep "${dep}")  # a static library's private deps
      if(dep AND NOT dep MATCHES "-NOTFOUND$" AND NOT dep MATCHES "^\\$<")
        list(APPEND queue ${dep})
      endif()
    endforeach()
  endwhile()
  list(REMOVE_ITEM seen ${target})
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

# slide_check_layers(CORE targets... TOOLING targets...): fails naming the first CORE target
# that links a TOOLING target and the chain's end.
function(slide_check_layers)
  cmake_parse_arguments(A "" "" "CORE;TOOLING" ${ARGN})
  foreach(t IN LISTS A_CORE)
    slide_link_closure(${t} deps)
    foreach(d IN LISTS deps)
      if(d IN_LIST A_TOOLING)
        message(FATAL_ERROR "${t} is robot core (a core lib area or a daemon) but links ${d}, which is tooling "
                            "(SLIDE_TOOLING_AREAS in cmake/SlideLayers.cmake; README, Library areas)")
      endif()
    endforeach()
  endforeach()
endfunction()

# The project's check: every target of lib/<area> is core unless the area is tooling; every
# target of daemons/ is core.
function(slide_check_project_layers)
  foreach(area IN LISTS SLIDE_TOOLING_AREAS)
    if(NOT IS_DIRECTORY ${PROJECT_SOURCE_DIR}/lib/${area})
      message(FATAL_ERROR "tooling area lib/${area} does not exist: update SLIDE_TOOLING_AREAS (cmake/SlideLayers.cmake)")
    endif()
  endforeach()
  set(core)
  set(tooling)
  file(GLOB folders RELATIVE ${PROJECT_SOURCE_DIR} ${PROJECT_SOURCE_DIR}/lib/*/CMakeLists.txt
       ${PROJECT_SOURCE_DIR}/daemons/*/CMakeLists.txt)
  foreach(f IN LISTS folders)
    get_filename_component(folder ${f} DIRECTORY)
    get_filename_component(area ${folder} NAME)
    get_property(targets DIRECTORY ${PROJECT_SOURCE_DIR}/${folder} PROPERTY BUILDSYSTEM_TARGETS)
    if(folder MATCHES "^lib/" AND area IN_LIST SLIDE_TOOLING_AREAS)
      list(APPEND tooling ${targets})
    else()
      list(APPEND core ${targets})
    endif()
  endforeach()
  slide_check_layers(CORE ${core} TOOLING ${tooling})
endfunction()
