# Frozen into our RPI_PICO image (host/pico/firmware.py): the rp2 port's own modules and asyncio.
# micropython-lib is not packaged in Debian, so the port's onewire, ds18x20, dht and neopixel are left out.
freeze("$(PORT_DIR)/modules")  # noqa: F821 (makemanifest.py provides freeze and include)
include("$(MPY_DIR)/extmod/asyncio")  # noqa: F821
