# The CNC / printer controller: the serial protocol on the step engine and
# planner, and the services (firmware/services/) on a board whose header
# declares a heater (`constexpr bool kHeater = true;`, the m32's); a board
# with homing and no heater (`constexpr bool kHoming = true;`) links the
# homing service alone.
set(APP_PARTS engine)
file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/boards/${board_name}.h heater_line REGEX "^constexpr bool kHeater = true;")
file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/boards/${board_name}.h homing_line REGEX "^constexpr bool kHoming = true;")
if(heater_line)
  list(APPEND APP_PARTS services)
elseif(homing_line)
  list(APPEND APP_FILES services/homing.cpp)
endif()
# A board with settings in the EEPROM (`constexpr bool kSettings = true;`)
# links their service (a board with a heater has all of firmware/services/).
file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/boards/${board_name}.h settings_line REGEX "^constexpr bool kSettings = true;")
if(settings_line AND NOT heater_line)
  list(APPEND APP_FILES services/settings.cpp)
endif()
# A board with grbl's realtime bytes (`constexpr bool kRealtime = true;`)
# gets the 128-byte receive ring grbl's senders count characters against,
# and the receive interrupt hands every byte to its realtime filter first.
file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/boards/${board_name}.h realtime_line REGEX "^constexpr bool kRealtime = true;")
if(realtime_line)
  list(APPEND APP_DEFINITIONS HAL_UART_RX_SIZE=128 HAL_UART_REALTIME)
endif()
