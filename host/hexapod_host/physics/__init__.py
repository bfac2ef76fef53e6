"""MuJoCo: the robot file as an MJCF model (mjcf), the core's frames walking it and what is measured (sim)."""
