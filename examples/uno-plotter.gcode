; A pen plotter on the Uno: the Motor Shield's steppers on X and Y (25 steps
; per mm), the pen on the hardware-timed Z (400 steps per mm, 2 mm lift).
; Draws a 10 mm square, then a diamond through its edge midpoints, and
; returns to the origin. Each G1 of X and Y together is one coordinated
; block: both motors end on the corner together.
G21 G90
G1 Z2 F600        ; pen up
G0 X10 Y10        ; to the square's first corner
G1 Z0 F600        ; pen down
G1 X20 F300
G1 Y20
G1 X10
G1 Y10
G1 X15 Y10 F300   ; along the edge to its middle
G1 X20 Y15        ; the diamond: both axes together
G1 X15 Y20
G1 X10 Y15
G1 X15 Y10
G1 Z2 F600        ; pen up
G0 X0 Y0
M84               ; motors off, once the motion has ended
M114              ; where they are (M114 does not wait for the motion)
