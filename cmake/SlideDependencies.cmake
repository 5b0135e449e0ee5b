# System dependencies, all from Debian packages (see tools/commands/setup.sh).
find_package(PkgConfig REQUIRED)
pkg_check_modules(LCM REQUIRED IMPORTED_TARGET lcm)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(Ceres REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs)
find_package(spdlog REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(nanoflann REQUIRED)
find_package(GTest REQUIRED)
find_package(Threads REQUIRED)
find_package(Java COMPONENTS Development QUIET)
find_program(LCM_GEN lcm-gen REQUIRED)
# PCL (libpcl-dev): PCD files and the reference clustering / RANSAC steps of the geometric
# front-end. Found by hand: PCL's own config searches VTK (with MPI) for pcl_io, which this
# project neither needs nor can configure without MPI's CMake package. Its headers are
# included by few .cpp files (build time).
find_path(PCL_INCLUDE_DIR pcl/point_types.h PATH_SUFFIXES pcl-1.13 pcl-1.12 pcl-1.11 pcl-1.10 REQUIRED)
set(_pcl_libs)
foreach(_c common io search kdtree segmentation sample_consensus)
  find_library(PCL_${_c}_LIBRARY pcl_${_c} REQUIRED)
  list(APPEND _pcl_libs ${PCL_${_c}_LIBRARY})
endforeach()
add_library(slide_pcl INTERFACE)
target_include_directories(slide_pcl SYSTEM INTERFACE ${PCL_INCLUDE_DIR})
target_link_libraries(slide_pcl INTERFACE ${_pcl_libs})


# Real data (KITTI, SemanticKITTI, robot maps, forest inventories, TLS) read in place by tests
# and benchmarks; override with -DSLIDE_DATA_DIR=... or the SLIDE_DATA environment variable.
if(DEFINED ENV{SLIDE_DATA})
  set(_data_default $ENV{SLIDE_DATA})
elseif(EXISTS ${PROJECT_SOURCE_DIR}/../shared/data)
  get_filename_component(_data_default ${PROJECT_SOURCE_DIR}/../shared/data ABSOLUTE)
else()
  set(_data_default /work/shared/data)
endif()
set(SLIDE_DATA_DIR ${_data_default} CACHE PATH "Folder holding the shared real data sets")
add_compile_definitions(SLIDE_DATA_DIR="${SLIDE_DATA_DIR}")

# ROS 1 bags (librosbag-storage-dev, libsensor-msgs-dev, libnav-msgs-dev, libtf2-msgs-dev,
# pluginlib-dev, librcpputils-dev, libament-index-cpp-dev). rosbag_storage.pc requires a
# pluginlib.pc that Debian does not ship, so the include folders and libraries are named here.
# Only lib/io/ros_bag.cpp includes these headers.
find_path(ROSBAG_INCLUDE_DIR rosbag/bag.h REQUIRED)
set(_rosbag_includes ${ROSBAG_INCLUDE_DIR})
foreach(_sub pluginlib class_loader rcpputils rcutils ament_index_cpp)
  if(EXISTS /usr/include/${_sub})
    list(APPEND _rosbag_includes /usr/include/${_sub})
  endif()
endforeach()
set(_rosbag_libs)
foreach(_lib rosbag_storage roscpp_serialization rostime cpp_common console_bridge boost_filesystem class_loader)
  find_library(_found_${_lib} ${_lib} REQUIRED)
  list(APPEND _rosbag_libs ${_found_${_lib}})
endforeach()
add_library(slide_rosbag INTERFACE)
target_include_directories(slide_rosbag SYSTEM INTERFACE ${_rosbag_includes})
target_link_libraries(slide_rosbag INTERFACE ${_rosbag_libs})

