"""docs/wiring.md carries, for every board file, the wiring tables rendered from that
file's data, and for the robot's calibration file its servo and sonar tables."""

import importlib
import os

from hexapod import board as hb
from hexapod import robotcal

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TITLES = {
    "pico": ("Raspberry Pi Pico (MicroPython)", "GP%d"),
    "esp32_devkit": ("ESP32 DevKit (MicroPython)", "GPIO%d"),
    "feather_rp2040": ("Adafruit Feather RP2040 (CircuitPython)", "%s"),
    "feather_rp2040_micropython": ("Adafruit Feather RP2040 (MicroPython)", "GPIO%d"),
}
LEG_NAMES = {1: "1 RF", 2: "2 RM", 3: "3 RR", 4: "4 LR", 5: "5 LM", 6: "6 LF"}


def mm(v):
    """0.1 mm -> text in mm."""
    return "%d.%d" % (v // 10, v % 10) if v >= 0 else "-%d.%d" % (-v // 10, -v % 10)


def render(name):
    """The markdown tables for one board, from its BOARD dict."""
    b = hb.load(name)
    title, pin_fmt = TITLES[name]
    i2c, pca = b["i2c"], b["pca9685"]
    lines = ["### %s: `boards/%s.py`" % (title, name), ""]
    lines += ["| signal | board pin | goes to |", "|---|---|---|"]
    bus = "I2C%d" % i2c["id"] if i2c["id"] is not None else "I2C"
    lines.append("| %s SDA | %s | SDA of both PCA9685 boards |" % (bus, pin_fmt % i2c["sda"]))
    lines.append(
        "| %s SCL (%d kHz) | %s | SCL of both PCA9685 boards |" % (bus, i2c["freq"] // 1000, pin_fmt % i2c["scl"])
    )
    for s in b["sonars"]:
        lines.append("| %s trigger | %s | HC-SR04 Trig |" % (s[0], pin_fmt % s[1]))
        lines.append("| %s echo | %s | HC-SR04 Echo through the 1k/2k divider |" % (s[0], pin_fmt % s[2]))
    lines += ["", "| PCA9685 | address | oscillator trim | frame rate |", "|---|---|---|---|"]
    for k, chip in enumerate(pca["chips"]):
        lines.append("| chip %d | 0x%02x | %d Hz | %d Hz |" % (k, chip["address"], chip["osc_hz"], pca["pwm_hz"]))
    lines += ["", "| leg | coxa | femur | tibia |", "|---|---|---|---|"]
    table = hb.servo_table(b, [None] * 18)
    for leg in range(1, 7):
        cells = ["0x%02x ch %d" % table[(leg - 1) * 3 + j][:2] for j in range(3)]
        lines.append("| %s | %s |" % (LEG_NAMES[leg], " | ".join(cells)))
    return "\n".join(lines) + "\n"


def render_robot(name):
    """The markdown tables for one robot's calibration file (robots/<name>_cal.py)."""
    c = robotcal.load(name)
    ref = c["REFERENCE"]
    lines = ["### Robot `%s`: `robots/%s_cal.py`" % (name, name), ""]
    lines += ["| leg | coxa | femur | tibia |", "|---|---|---|---|"]
    lines.append("| reference angle | %s |" % " | ".join("%d deg" % (a // 100) for a in ref))
    rows = {}
    for s in c["SERVOS"]:
        rows[(s[0], s[1])] = "%d us, %+d, %d..%d" % (s[2], s[3], s[4], s[5])
    for leg in range(1, 7):
        cells = [rows[(leg, j)] for j in ("coxa", "femur", "tibia")]
        lines.append("| %s | %s |" % (LEG_NAMES[leg], " | ".join(cells)))
    lines += ["", "| sonar | x (mm) | y (mm) | heading (deg) |", "|---|---|---|---|"]
    for s in c["SONARS"]:
        lines.append("| %s | %s | %s | %d |" % (s[0], mm(s[1]), mm(s[2]), s[3] // 100))
    return "\n".join(lines) + "\n"


def test_every_board_file_has_a_title():
    names = sorted(f[:-3] for f in os.listdir(os.path.join(ROOT, "boards")) if f.endswith(".py") and f != "__init__.py")
    assert names == sorted(TITLES)
    for name in names:
        importlib.import_module("boards." + name)


def test_wiring_doc_matches_the_board_files():
    for doc_name in ("docs/wiring.md",):
        with open(os.path.join(ROOT, doc_name)) as f:
            doc = f.read()
        for name in TITLES:
            assert render(name) in doc, "%s is stale for %s; regenerate with render(%r):\n%s" % (
                doc_name,
                name,
                name,
                render(name),
            )
        assert render_robot("default") in doc, "%s is stale for robots/default_cal.py:\n%s" % (
            doc_name,
            render_robot("default"),
        )
