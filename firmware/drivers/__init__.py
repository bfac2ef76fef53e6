"""Chip and runtime edges: each driver takes its bus, pins and clock as arguments."""
