# The step/dir driver board: its own interrupt-driven coil drive, no engine.
set(APP_PARTS "")
