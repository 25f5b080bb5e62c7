# The CNC / printer controller: the serial protocol on the step engine and
# planner.
set(APP_PARTS engine)
