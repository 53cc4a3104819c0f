# Finds ROS 1's bag storage library and the message headers of the io module's bag reader
# (Debian: librosbag-dev, libsensor-msgs-dev, libnav-msgs-dev, libtf2-msgs-dev) and defines the
# imported target slamkit::rosbag. Used by the build and, installed next to slamkitConfig.cmake,
# by projects that use slamkit::io. Debian's pkg-config files for these libraries require
# pluginlib's, which no Debian package ships, so the libraries are located directly.
find_path(SLAMKIT_ROSBAG_INCLUDE_DIR rosbag/view.h)
find_path(SLAMKIT_ROS_MSGS_INCLUDE_DIR sensor_msgs/LaserScan.h)
# rosbag/bag.h includes pluginlib's header, which includes class_loader's, rcpputils', rcutils'
# and ament_index_cpp's: Debian keeps each of them one folder down (/usr/include/NAME/NAME/).
set(_slamkit_ros_nested_vars)
foreach(_pair pluginlib:class_loader.hpp class_loader:multi_library_class_loader.hpp
              rcpputils:shared_library.hpp rcutils:shared_library.h
              ament_index_cpp:get_package_prefix.hpp)
  string(REPLACE ":" ";" _pair "${_pair}")
  list(GET _pair 0 _name)
  list(GET _pair 1 _header)
  find_path(SLAMKIT_ROS_${_name}_INCLUDE_DIR ${_name}/${_header} PATH_SUFFIXES ${_name})
  list(APPEND _slamkit_ros_nested_vars SLAMKIT_ROS_${_name}_INCLUDE_DIR)
  mark_as_advanced(SLAMKIT_ROS_${_name}_INCLUDE_DIR)
endforeach()
set(_slamkit_rosbag_libraries)
set(_slamkit_rosbag_vars)
foreach(_lib rosbag_storage roscpp_serialization rostime cpp_common console_bridge)
  find_library(SLAMKIT_ROS_${_lib}_LIBRARY ${_lib})
  list(APPEND _slamkit_rosbag_libraries ${SLAMKIT_ROS_${_lib}_LIBRARY})
  list(APPEND _slamkit_rosbag_vars SLAMKIT_ROS_${_lib}_LIBRARY)
  mark_as_advanced(SLAMKIT_ROS_${_lib}_LIBRARY)
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SlamkitRosbag REQUIRED_VARS ${_slamkit_rosbag_vars}
                                  SLAMKIT_ROSBAG_INCLUDE_DIR SLAMKIT_ROS_MSGS_INCLUDE_DIR
                                  ${_slamkit_ros_nested_vars})
if(SlamkitRosbag_FOUND AND NOT TARGET slamkit::rosbag)
  add_library(slamkit::rosbag INTERFACE IMPORTED)
  target_include_directories(slamkit::rosbag SYSTEM INTERFACE ${SLAMKIT_ROSBAG_INCLUDE_DIR}
                                                               ${SLAMKIT_ROS_MSGS_INCLUDE_DIR})
  foreach(_var IN LISTS _slamkit_ros_nested_vars)
    target_include_directories(slamkit::rosbag SYSTEM INTERFACE ${${_var}})
  endforeach()
  target_link_libraries(slamkit::rosbag INTERFACE ${_slamkit_rosbag_libraries})
endif()
unset(_slamkit_rosbag_libraries)
unset(_slamkit_rosbag_vars)
unset(_slamkit_ros_nested_vars)
mark_as_advanced(SLAMKIT_ROSBAG_INCLUDE_DIR SLAMKIT_ROS_MSGS_INCLUDE_DIR)
