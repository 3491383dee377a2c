# SPDX-License-Identifier: BSD-3-Clause
# Every third-party library lmk uses, all from Debian 12 packages (scripts/install-deps.sh).

find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(TBB REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Ceres 2 REQUIRED)
find_package(CGAL 5 REQUIRED)
find_package(urdfdom REQUIRED)
# Planning arm motions around obstacles (lmk::pr2, issue #60): RRT-Connect in joint space.
find_package(ompl 1.5 REQUIRED)
# The pairs of links an SRDF says may touch (<disable_collisions>, pr2/srdf.h): a small XML reader.
find_package(tinyxml2 REQUIRED)
# RGB-D depth and colour images (libpng-dev).
find_package(PNG REQUIRED)

# nanoflann is header-only; Debian ships its CMake config.
find_package(nanoflann REQUIRED)

# Debian's PCL config pulls in VTK, whose config needs MPI's C bindings (mpi-default-dev).
find_package(MPI COMPONENTS C REQUIRED)
find_package(PCL 1.12 REQUIRED COMPONENTS common io registration kdtree search sample_consensus)

# Debian ships FindOpenVDB.cmake under the multiarch library directory, not on CMake's path.
if(CMAKE_LIBRARY_ARCHITECTURE)
  list(APPEND CMAKE_MODULE_PATH "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB")
endif()
find_package(OpenVDB REQUIRED)

# urdfdom's CMake config carries no version; its pkg-config file does (for `lmk --version`).
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(LMK_URDFDOM_PC QUIET urdfdom)
endif()
if(LMK_URDFDOM_PC_VERSION)
  set(urdfdom_VERSION ${LMK_URDFDOM_PC_VERSION})
else()
  set(urdfdom_VERSION unknown)
endif()
