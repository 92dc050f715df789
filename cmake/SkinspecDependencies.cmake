# Finds every third-party dependency from Debian 12 packages and repairs the two known packaging faults,
# so nobody has to patch system files:
#  1. OpenImageIO's exported target lists /usr/include/opencv4 (absent unless OpenCV is installed), and
#     CMake refuses imported targets with non-existent include directories.
#  2. OpenColorIO's config is installed under /usr/share/cmake, from where it computes its prefix four
#     levels up and exports "/include". We build the imported target from the real header and library.

find_package(Threads REQUIRED)
find_package(fmt REQUIRED)
find_package(glm REQUIRED)
find_package(TBB REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(tomlplusplus REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(OpenImageIO REQUIRED CONFIG)
find_package(PkgConfig REQUIRED)
# PLplot's own CMake config references every optional binding; its pkg-config file is the reliable entry.
pkg_check_modules(PLPLOT REQUIRED IMPORTED_TARGET plplot-c++)
# SIMD packets of the Monte Carlo walks, dispatched at run time (Google Highway, libhwy-dev)
pkg_check_modules(HWY REQUIRED IMPORTED_TARGET libhwy)
pkg_check_modules(NLOPT REQUIRED IMPORTED_TARGET nlopt)
pkg_check_modules(FFTW REQUIRED IMPORTED_TARGET fftw3)

function(skinspec_drop_missing_include_dirs target)
  foreach(property INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    get_target_property(dirs ${target} ${property})
    if(dirs)
      set(kept "")
      foreach(dir IN LISTS dirs)
        if(dir MATCHES "^\\$<" OR EXISTS "${dir}")
          list(APPEND kept "${dir}")
        endif()
      endforeach()
      set_target_properties(${target} PROPERTIES ${property} "${kept}")
    endif()
  endforeach()
endfunction()

foreach(target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  if(TARGET ${target})
    skinspec_drop_missing_include_dirs(${target})
  endif()
endforeach()

if(NOT TARGET OpenColorIO::OpenColorIO)
  find_path(OpenColorIO_INCLUDE_DIR OpenColorIO/OpenColorIO.h REQUIRED)
  find_library(OpenColorIO_LIBRARY NAMES OpenColorIO REQUIRED)
  add_library(OpenColorIO::OpenColorIO UNKNOWN IMPORTED)
  set_target_properties(OpenColorIO::OpenColorIO PROPERTIES
    IMPORTED_LOCATION "${OpenColorIO_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OpenColorIO_INCLUDE_DIR}")
endif()

if(SKINSPEC_BUILD_TESTS)
  find_package(Catch2 2 REQUIRED)
endif()

# The Python module is built for the interpreter Debian's python3-numpy and python3-pytest belong to
# (/usr/bin/python3), not whichever python3 is first on PATH; -DPython3_EXECUTABLE=... chooses another.
if(SKINSPEC_PYTHON)
  if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Interpreter of the Python module")
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module)
  find_package(pybind11 2.6 CONFIG)
  if(NOT Python3_FOUND OR NOT pybind11_FOUND)
    message(FATAL_ERROR "The Python module needs python3-dev and pybind11-dev (scripts/setup.sh installs them), "
                        "or configure with -DSKINSPEC_PYTHON=OFF")
  endif()
endif()

# Mitsuba 3 scene files (formats/mitsuba_scene.hpp) are XML: pugixml (libpugixml-dev).
find_package(pugixml REQUIRED)

# MPI (OpenMPI from Debian: libopenmpi-dev, openmpi-bin) shares `spectrum --vary` and `export lut` among
# processes started by mpirun (cli/process_group.hpp). Optional: without it the program is one process.
if(SKINSPEC_MPI)
  enable_language(C)
  find_package(MPI COMPONENTS C)
  if(NOT MPI_C_FOUND)
    message(STATUS "MPI not found: skinspec is built without it (install libopenmpi-dev for mpirun runs)")
  endif()
endif()
