# rosbag_storage (ROS 1 bags: Debian's librosbag-storage-dev) through pkg-config, as the target
# PkgConfig::ROSBAG. Used by the plugin foglab_rosbag (src/io/rosbag_plugin.h) only.
#
# Debian 12's rosbag_storage.pc requires "pluginlib" (rosbag/bag.h includes
# <pluginlib/class_loader.hpp> for its encryption plugins), but Debian's pluginlib-dev is the
# ROS 2 package: it installs no pluginlib.pc, and its headers, and those of the packages they
# include, lie one folder down (/usr/include/pluginlib/pluginlib/class_loader.hpp). So when
# pkg-config knows no pluginlib, a pluginlib.pc naming those folders is written into the build
# tree for this configuration. It names no library: the plugin loader's code that rosbag uses is
# inside librosbag_storage.
macro(foglab_find_rosbag)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(FOGLAB_PLUGINLIB QUIET pluginlib)
  set(_foglab_saved_pkg_config_path "$ENV{PKG_CONFIG_PATH}")
  if(NOT FOGLAB_PLUGINLIB_FOUND)
    set(_foglab_cflags "")
    foreach(_foglab_header pluginlib/class_loader.hpp class_loader/multi_library_class_loader.hpp
                           ament_index_cpp/get_resource.hpp rcpputils/shared_library.hpp
                           rcutils/logging_macros.h)
      string(REGEX REPLACE "/.*" "" _foglab_package "${_foglab_header}")
      find_path(FOGLAB_${_foglab_package}_INCLUDE_DIR ${_foglab_header}
                PATH_SUFFIXES ${_foglab_package})
      if(NOT FOGLAB_${_foglab_package}_INCLUDE_DIR)
        message(FATAL_ERROR "foglab: rosbag/bag.h needs <${_foglab_header}>, which is not "
                            "installed (Debian: pluginlib-dev; scripts/install-deps.sh)")
      endif()
      string(APPEND _foglab_cflags " -I${FOGLAB_${_foglab_package}_INCLUDE_DIR}")
    endforeach()
    set(_foglab_pc_dir "${CMAKE_CURRENT_BINARY_DIR}/foglab-pkgconfig")
    file(WRITE "${_foglab_pc_dir}/pluginlib.pc"
         "Name: pluginlib\n"
         "Description: the include folders of Debian's pluginlib-dev (written by foglab)\n"
         "Version: 0\n"
         "Cflags:${_foglab_cflags}\n")
    set(ENV{PKG_CONFIG_PATH} "${_foglab_pc_dir}:$ENV{PKG_CONFIG_PATH}")
  endif()
  pkg_check_modules(ROSBAG REQUIRED IMPORTED_TARGET rosbag_storage roscpp_serialization rostime)
  set(ENV{PKG_CONFIG_PATH} "${_foglab_saved_pkg_config_path}")
endmacro()
