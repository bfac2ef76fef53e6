"""`hexapod view`: one live page for the robot, whatever drives it (docs/view.md).

source.py says what a source is (step() and snapshot(), a plain dict); sim.py is the wall
simulator's source; player.py steps a source in real time in the background; scene.py turns a
snapshot into world-frame geometry (pure, no UI); page.py draws it with NiceGUI; bench.py
measures the update rate.
"""
