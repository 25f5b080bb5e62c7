# The electronic leadscrew (docs/lathe.md): the leadscrew's own interrupts
# and pace on Timer1, the spindle encoder (firmware/devices/), the time base
# (firmware/engine/clock.cpp alone: the step engine's Timer1 vector would
# collide with the pace's, so the engine part is not linked).
list(APPEND app_sources ${CMAKE_CURRENT_SOURCE_DIR}/engine/clock.cpp ${CMAKE_CURRENT_SOURCE_DIR}/engine/clock_vector.S)
# A board with kServoLeadscrew (firmware/boards/m16-servo.h) drives the
# leadscrew with a DC servo: servo/leadscrew_servo.cpp in place of the
# stepper's leadscrew.cpp, its own single-channel spindle count (INT0 is the
# motor encoder's); the stepper's leadscrew takes the spindle encoder's
# decoder from firmware/devices/.
# A board header that includes another board's (m16-servo-panel.h:
# m16-servo.h) has that board's flags too: both are read.
file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/boards/${board_name}.h board_lines)
foreach(line ${board_lines})
  if(line MATCHES "^#include \"([a-z0-9-]+\\.h)\"")
    file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/boards/${CMAKE_MATCH_1} base_lines)
    list(APPEND board_lines ${base_lines})
  endif()
endforeach()
list(FILTER board_lines INCLUDE REGEX "^constexpr bool k(ServoLeadscrew|OperatorPanel) = true")
string(FIND "${board_lines}" "kServoLeadscrew" servo_line)
string(FIND "${board_lines}" "kOperatorPanel" panel_line)
if(servo_line GREATER -1)
  list(REMOVE_ITEM app_sources ${app_dir}/leadscrew.cpp)
  list(APPEND app_sources ${app_dir}/servo/leadscrew_servo.cpp)
else()
  set(APP_PARTS devices)
  # The spindle vectors in assembly (outside the link-time optimisation:
  # the data they use have assembler names, spindle_vectors.h).
  list(APPEND app_sources ${app_dir}/spindle_vectors.S)
endif()
# The operator panel's images (a board with kOperatorPanel, firmware/apps/
# lathe/operator.h: m16-panel, m32-servo-panel) have the panel's devices (a
# servo's without the spindle decoder) and no UART front end: neither the
# protocol nor the UART driver (whose vectors would stay linked) goes into
# them. The others have no panel.
if(panel_line GREATER -1)
  if(servo_line GREATER -1)
    set(APP_FILES devices/hd44780.cpp devices/keypad.cpp)
  endif()
  # The panel's image is at the flash limit: its workflow inlined less
  # (about 50 bytes).
  set_source_files_properties(${app_dir}/operator.cpp PROPERTIES COMPILE_OPTIONS "-finline-limit=1;-fno-gcse")
  list(REMOVE_ITEM app_sources ${app_dir}/protocol.cpp)
  list(REMOVE_ITEM SHARED_SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/../hal/avr/uart.cpp)
else()
  list(REMOVE_ITEM app_sources ${app_dir}/operator.cpp)
endif()
