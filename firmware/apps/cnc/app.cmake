# The CNC / printer controller: the serial protocol on the step engine and
# planner, and the heater service (firmware/services/) on a board whose
# header declares a heater (`constexpr bool kHeater = true;`, the m32's). The
# homing service (kHoming) is in the same part: only a board with a heater
# can have it today.
set(APP_PARTS engine)
file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/boards/${board_name}.h heater_line REGEX "^constexpr bool kHeater = true;")
if(heater_line)
  list(APPEND APP_PARTS services)
endif()
