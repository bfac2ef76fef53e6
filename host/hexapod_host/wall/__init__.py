"""The wall-following simulator: worlds, the room, the trials, the MuJoCo mover, the firmware rig."""
