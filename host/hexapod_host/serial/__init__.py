"""A board over its serial port: the console client (link), the jog tool (jog, jog_tui), flashing (flash)."""
