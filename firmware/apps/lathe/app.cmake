# The electronic leadscrew (docs/lathe.md): the leadscrew's own interrupts
# and pace on Timer1, the spindle encoder (firmware/devices/), the time base
# (firmware/engine/clock.cpp alone: the step engine's Timer1 vector would
# collide with the pace's, so the engine part is not linked).
list(APPEND app_sources ${CMAKE_CURRENT_SOURCE_DIR}/engine/clock.cpp ${CMAKE_CURRENT_SOURCE_DIR}/engine/clock_vector.S)
# A board with kServoLeadscrew (firmware/boards/m16-servo.h) drives the
# leadscrew with a DC servo: servo/leadscrew_servo.cpp in place of the
# stepper's leadscrew.cpp, its own single-channel spindle count (INT0 is the
# motor encoder's), no operator panel (nor its devices).
file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/boards/${board_name}.h servo_line REGEX "^constexpr bool kServoLeadscrew = true;")
if(servo_line)
  list(REMOVE_ITEM app_sources ${app_dir}/leadscrew.cpp ${app_dir}/operator.cpp)
  list(APPEND app_sources ${app_dir}/servo/leadscrew_servo.cpp)
else()
  set(APP_PARTS devices)
  # The spindle vectors in assembly (outside the link-time optimisation:
  # the data they use have assembler names, spindle_vectors.h).
  list(APPEND app_sources ${app_dir}/spindle_vectors.S)
endif()
# The operator panel's image (a board with kOperatorPanel, firmware/apps/
# lathe/operator.h) has no UART front end: neither the protocol nor the
# UART driver (whose vectors would stay linked) goes into it.
file(STRINGS ${CMAKE_CURRENT_SOURCE_DIR}/boards/${board_name}.h panel_line REGEX "^constexpr bool kOperatorPanel = true;")
if(panel_line)
  # The panel's image is at the flash limit: its workflow inlined less
  # (about 50 bytes).
  set_source_files_properties(${app_dir}/operator.cpp PROPERTIES COMPILE_OPTIONS "-finline-limit=1;-fno-gcse")
  list(REMOVE_ITEM app_sources ${app_dir}/protocol.cpp)
  list(REMOVE_ITEM SHARED_SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/../hal/avr/uart.cpp)
endif()
