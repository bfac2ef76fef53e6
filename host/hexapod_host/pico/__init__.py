"""The firmware on an emulated Raspberry Pi Pico (host/pico/run.mjs under Node.js): emulator, loop."""
