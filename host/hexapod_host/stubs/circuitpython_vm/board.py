"""Fake CircuitPython `board` for the VM: the Feather RP2040's pin names (see _cp_vm)."""

from _stub_cp import FEATHER_RP2040_PINS, BoardPin

board_id = "adafruit_feather_rp2040"
for _name in FEATHER_RP2040_PINS:
    globals()[_name] = BoardPin(_name)
