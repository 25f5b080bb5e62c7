# Simulator calibration suite (issue 3, docs/simulator.md).
#
# Small assembly programs (programs/*.S) with cycle counts derived from the
# datasheet are built for the AVR, then run by calib_runner inside libsimavr;
# each program's EXPECT lines must match exactly.
#
#   ctest -L calibration          against avrmotion::simavr (patched by default)
#   ctest -L calibration-stock    the same programs against Debian's stock
#                                 libsimavr; cases that hit a known fault are
#                                 marked WILL_FAIL (so they pass by failing,
#                                 and start to fail if stock ever gets fixed)
#   tests/calibration/run-stock.sh  prints the stock measurements themselves
set(_calib_dir ${CMAKE_CURRENT_LIST_DIR})
set(_calib_mcus atmega328p atmega32 atmega1284p)   # all at 16 MHz
set(_calib_bin ${CMAKE_BINARY_DIR}/calibration-avr)
if(NOT AVRMOTION_TOOLCHAIN)
  set(AVRMOTION_TOOLCHAIN ${CMAKE_SOURCE_DIR}/toolchain/avr-gcc.cmake)
endif()

# Cases that fail on Debian's libsimavr 1.6 (measured; see docs/simulator.md).
set(_calib_stock_faults
  irq_response irq_reentry sei_one ctc_top0 tcnt_preload tcnt_write foc oc_no_phantom
  ctc_missed_compare ctc_tov oc_event_stamp oc_port_override uart_byte_time
  extint_level_disabled extint_level_reenable tifr_shared_clear skip_adiw)

string(REPLACE ";" "|" _calib_mcus_arg "${_calib_mcus}")
ExternalProject_Add(calibration_programs
  SOURCE_DIR ${_calib_dir}/programs
  BINARY_DIR ${_calib_bin}
  LIST_SEPARATOR |
  CMAKE_ARGS -DCMAKE_TOOLCHAIN_FILE=${AVRMOTION_TOOLCHAIN}
             -DCMAKE_BUILD_TYPE=Release
             -DCALIB_MCUS=${_calib_mcus_arg}
  INSTALL_COMMAND ""
  BUILD_ALWAYS ON)

function(_calib_runner target simavr_target)
  add_executable(${target} ${_calib_dir}/calib_runner.cpp)
  target_compile_features(${target} PRIVATE cxx_std_17)
  target_link_libraries(${target} PRIVATE ${simavr_target})
  add_dependencies(${target} calibration_programs)
endfunction()

# label: ctest label and test-name prefix; stock: runner linked to stock lib
function(_calib_tests runner label stock)
  file(GLOB programs ${_calib_dir}/programs/*.S)
  foreach(mcu IN LISTS _calib_mcus)
    foreach(src IN LISTS programs)
      get_filename_component(name ${src} NAME_WE)
      file(STRINGS ${src} only REGEX "MCUS:")   # same rule as programs/
      if(only AND NOT only MATCHES "MCUS:.*[ \t]${mcu}([ \t]|$)")
        continue()
      endif()
      set(t ${label}.${name}.${mcu})
      add_test(NAME ${t}
        COMMAND ${runner} --mcu ${mcu} --freq 16000000 ${_calib_bin}/${name}-${mcu}.elf ${src})
      set_tests_properties(${t} PROPERTIES LABELS ${label} TIMEOUT 60)
      if(stock AND name IN_LIST _calib_stock_faults)
        set_tests_properties(${t} PROPERTIES WILL_FAIL ON)
      endif()
    endforeach()
  endforeach()
endfunction()

_calib_runner(calib_runner avrmotion::simavr)
if(AVRMOTION_SIMAVR STREQUAL "stock")
  _calib_tests(calib_runner calibration ON)
else()
  _calib_tests(calib_runner calibration OFF)
  if(TARGET avrmotion::simavr-stock)
    _calib_runner(calib_runner_stock avrmotion::simavr-stock)
    _calib_tests(calib_runner_stock calibration-stock ON)
  endif()
endif()
