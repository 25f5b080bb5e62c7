# The electronic leadscrew (docs/lathe.md): the leadscrew's own interrupts
# and pace on Timer1, the spindle encoder (firmware/devices/), the time base
# (firmware/engine/clock.cpp alone: the step engine's Timer1 vector would
# collide with the pace's, so the engine part is not linked).
set(APP_PARTS devices)
list(APPEND app_sources ${CMAKE_CURRENT_SOURCE_DIR}/engine/clock.cpp)
