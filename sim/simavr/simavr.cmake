# libsimavr for avrmotion: Debian's simavr 1.6 source, patched for timing
# fidelity (sim/simavr/patches, see docs/simulator.md), or Debian's stock
# system library for comparison.
#
#   -DAVRMOTION_SIMAVR=patched (default)  fetch + patch + build libsimavr.a
#   -DAVRMOTION_SIMAVR=stock              use the system libsimavr (pkg-config)
#
# Targets:
#   avrmotion::simavr        the selected libsimavr (headers usable both as
#                            <simavr/sim_avr.h> and "sim_avr.h")
#   avrmotion::simavrparts   hc595 / hd44780 / button / uart_pty parts
#   avrmotion::simavr-stock  Debian's system libsimavr, whatever the option
#                            says (only if installed; used by the calibration
#                            runner that documents the stock faults)
#
# The patched library is fetched, patched and built at configure time: it is
# small (a few seconds on 2 cores), and doing it then means every target that
# links avrmotion::simavr simply finds a finished libsimavr.a, with no
# cross-target ordering to get wrong. Each step is cached in the build tree:
# the fetch happens once, patching + rebuilding only when a patch changes.
#
# The source comes from "apt-get source simavr" through a private apt
# configuration in the build tree (/etc/apt is never touched). Offline, point
# AVRMOTION_SIMAVR_SOURCE_DIR at an unpacked simavr-1.6+dfsg tree instead.

set(AVRMOTION_SIMAVR patched CACHE STRING "libsimavr to use: patched | stock")
set_property(CACHE AVRMOTION_SIMAVR PROPERTY STRINGS patched stock)
set(AVRMOTION_SIMAVR_SOURCE_DIR "" CACHE PATH
    "Unpacked Debian simavr-1.6+dfsg source (skips apt-get source)")

find_package(Threads REQUIRED)
find_package(PkgConfig)

# --- Debian's system library: always offered as avrmotion::simavr-stock ----
if(PkgConfig_FOUND)
  pkg_check_modules(AVRMOTION_SYS_SIMAVR QUIET IMPORTED_TARGET simavr)
endif()
if(AVRMOTION_SYS_SIMAVR_FOUND AND NOT TARGET avrmotion::simavr-stock)
  add_library(avrmotion::simavr-stock INTERFACE IMPORTED)
  target_link_libraries(avrmotion::simavr-stock INTERFACE
    PkgConfig::AVRMOTION_SYS_SIMAVR elf Threads::Threads ${CMAKE_DL_LIBS} m)
endif()

if(AVRMOTION_SIMAVR STREQUAL "stock")
  if(NOT TARGET avrmotion::simavr-stock)
    message(FATAL_ERROR "AVRMOTION_SIMAVR=stock needs Debian's libsimavr-dev "
                        "(pkg-config simavr): apt-get install libsimavr-dev")
  endif()
  add_library(avrmotion::simavr ALIAS avrmotion::simavr-stock)
  find_library(AVRMOTION_SYS_SIMAVRPARTS simavrparts REQUIRED)
  add_library(avrmotion::simavrparts INTERFACE IMPORTED)
  target_include_directories(avrmotion::simavrparts INTERFACE /usr/include/simavr/parts)
  target_link_libraries(avrmotion::simavrparts INTERFACE
    ${AVRMOTION_SYS_SIMAVRPARTS} avrmotion::simavr util)
  message(STATUS "libsimavr: stock Debian system library (timing faults A-G present)")
  return()
elseif(NOT AVRMOTION_SIMAVR STREQUAL "patched")
  message(FATAL_ERROR "AVRMOTION_SIMAVR must be 'patched' or 'stock', not '${AVRMOTION_SIMAVR}'")
endif()

set(_sa_root ${CMAKE_BINARY_DIR}/_simavr)
set(_sa_pkg simavr-1.6+dfsg)

function(_sa_run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "libsimavr: ${what} failed (${rc}):\n${out}")
  endif()
endfunction()

# --- 1. pristine source (fetched once) --------------------------------------
if(AVRMOTION_SIMAVR_SOURCE_DIR)
  set(_sa_pristine ${AVRMOTION_SIMAVR_SOURCE_DIR})
else()
  set(_sa_pristine ${_sa_root}/fetch/${_sa_pkg})
  if(NOT EXISTS ${_sa_pristine}/simavr/sim/sim_avr.c)
    find_program(AVRMOTION_APT_GET apt-get)
    find_program(AVRMOTION_DPKG_SOURCE dpkg-source)
    if(NOT AVRMOTION_APT_GET OR NOT AVRMOTION_DPKG_SOURCE)
      message(FATAL_ERROR
        "libsimavr: fetching Debian's simavr source needs apt-get and dpkg-source "
        "(apt-get install dpkg-dev). Alternatively configure with "
        "-DAVRMOTION_SIMAVR_SOURCE_DIR=<unpacked ${_sa_pkg}> or -DAVRMOTION_SIMAVR=stock.")
    endif()
    set(_apt ${_sa_root}/apt)
    file(MAKE_DIRECTORY ${_apt}/lists/partial ${_apt}/cache/archives/partial ${_sa_root}/fetch)
    file(WRITE ${_apt}/sources.list "deb-src http://deb.debian.org/debian bookworm main\n")
    set(_apt_opts
      -o Dir::Etc::SourceList=${_apt}/sources.list
      -o Dir::Etc::SourceParts=/dev/null
      -o Dir::State::Lists=${_apt}/lists
      -o Dir::Cache=${_apt}/cache
      -o APT::Sandbox::User=root)
    message(STATUS "libsimavr: fetching Debian bookworm simavr source (private apt config in ${_apt})")
    foreach(step "update" "source simavr")
      separate_arguments(_args UNIX_COMMAND "${step}")
      execute_process(COMMAND ${AVRMOTION_APT_GET} -q ${_apt_opts} ${_args}
        WORKING_DIRECTORY ${_sa_root}/fetch
        RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
      if(NOT rc EQUAL 0 OR (step STREQUAL "update" AND out MATCHES "(^|\n)(W|E): Failed"))
        message(FATAL_ERROR
          "libsimavr: 'apt-get ${step}' failed, so Debian's simavr source could not be had:\n${out}\n"
          "Check network access to deb.debian.org, or configure with "
          "-DAVRMOTION_SIMAVR_SOURCE_DIR=<unpacked ${_sa_pkg}> (from 'apt-get source simavr' "
          "elsewhere), or with -DAVRMOTION_SIMAVR=stock to use the unpatched system library.")
      endif()
    endforeach()
    if(NOT EXISTS ${_sa_pristine}/simavr/sim/sim_avr.c)
      message(FATAL_ERROR "libsimavr: apt-get source did not produce ${_sa_pristine}")
    endif()
  endif()
endif()

# --- 2. patched copy (redone when the patch set changes) --------------------
file(GLOB _sa_patches CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/patches/*.patch)
list(SORT _sa_patches)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_sa_patches})
set(_sa_id "${_sa_pristine}")
foreach(p IN LISTS _sa_patches)
  file(SHA256 ${p} h)
  string(APPEND _sa_id ";${h}")
endforeach()
string(SHA256 _sa_id "${_sa_id}")

set(_sa_src ${_sa_root}/src)
set(_sa_prefix ${_sa_root}/install)
set(_sa_stamp ${_sa_root}/patched-build.stamp)
set(_sa_old "")
if(EXISTS ${_sa_stamp})
  file(READ ${_sa_stamp} _sa_old)
endif()

if(NOT _sa_old STREQUAL _sa_id OR NOT EXISTS ${_sa_prefix}/lib/libsimavr.a)
  find_program(AVRMOTION_PATCH patch REQUIRED)
  find_program(AVRMOTION_MAKE NAMES gmake make REQUIRED)
  file(REMOVE_RECURSE ${_sa_src} ${_sa_prefix} ${_sa_stamp})
  file(COPY ${_sa_pristine}/ DESTINATION ${_sa_src})
  foreach(p IN LISTS _sa_patches)
    get_filename_component(n ${p} NAME)
    message(STATUS "libsimavr: applying ${n}")
    _sa_run("patch ${n}" ${AVRMOTION_PATCH} -p1 --forward --batch -d ${_sa_src} -i ${p})
  endforeach()

  # --- 3. build only libsimavr.a (no run_avr, .so, examples or GL parts) ---
  execute_process(COMMAND ${CMAKE_C_COMPILER} -dumpmachine
                  OUTPUT_VARIABLE _sa_triple OUTPUT_STRIP_TRAILING_WHITESPACE)
  cmake_host_system_information(RESULT _sa_jobs QUERY NUMBER_OF_LOGICAL_CORES)
  message(STATUS "libsimavr: building patched libsimavr.a")
  _sa_run("make libsimavr.a"
    ${CMAKE_COMMAND} -E env CC=${CMAKE_C_COMPILER} "CFLAGS=-fPIC"
    ${AVRMOTION_MAKE} -C ${_sa_src}/simavr -j${_sa_jobs} RELEASE=1
      SIMAVR_VERSION=1.6+avrmotion obj-${_sa_triple}/libsimavr.a)

  # --- 4. install headers + lib in Debian's layout, inside the build tree --
  file(GLOB _h ${_sa_src}/simavr/sim/*.h ${_sa_src}/simavr/sim_core_*.h)
  file(COPY ${_h} DESTINATION ${_sa_prefix}/include/simavr)
  file(COPY ${_sa_src}/simavr/sim/avr DESTINATION ${_sa_prefix}/include/simavr)
  file(GLOB _h ${_sa_src}/examples/parts/*.h)
  file(COPY ${_h} DESTINATION ${_sa_prefix}/include/simavr/parts)
  file(COPY ${_sa_src}/simavr/obj-${_sa_triple}/libsimavr.a DESTINATION ${_sa_prefix}/lib)
  file(WRITE ${_sa_stamp} "${_sa_id}")
endif()

add_library(avrmotion_simavr STATIC IMPORTED GLOBAL)
set_target_properties(avrmotion_simavr PROPERTIES
  IMPORTED_LOCATION ${_sa_prefix}/lib/libsimavr.a
  INTERFACE_INCLUDE_DIRECTORIES "${_sa_prefix}/include;${_sa_prefix}/include/simavr"
  INTERFACE_LINK_LIBRARIES "elf;Threads::Threads;${CMAKE_DL_LIBS};m")
add_library(avrmotion::simavr ALIAS avrmotion_simavr)

# A few parts from simavr's examples/parts, built against the patched core
# (the GL/LCD-window parts are left out: they would pull in OpenGL).
add_library(avrmotion_simavrparts STATIC
  ${_sa_src}/examples/parts/hc595.c
  ${_sa_src}/examples/parts/hd44780.c
  ${_sa_src}/examples/parts/button.c
  ${_sa_src}/examples/parts/uart_pty.c)
set_target_properties(avrmotion_simavrparts PROPERTIES
  C_STANDARD 99 C_EXTENSIONS ON POSITION_INDEPENDENT_CODE ON)
target_include_directories(avrmotion_simavrparts PUBLIC ${_sa_prefix}/include/simavr/parts)
target_link_libraries(avrmotion_simavrparts PUBLIC avrmotion::simavr util)
add_library(avrmotion::simavrparts ALIAS avrmotion_simavrparts)

message(STATUS "libsimavr: patched (${_sa_prefix}/lib/libsimavr.a)")
