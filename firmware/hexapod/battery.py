"""Battery awareness: the pack voltage from one raw ADC reading at a time -> OK, LOW or CUTOFF.

Pure and integer-only, like the rest of the core: the loop (runner.Runner) reads the ADC
(machine.ADC(pin).read_u16()) every SAMPLE_FRAMES frames and hands the reading to
Monitor.update(); the monitor never touches a pin or a clock.

The reading: read_u16() is 0..65535; on the RP2040 it is the 12-bit conversion scaled up as
MicroPython's rp2 port does (raw << 4 | raw >> 8, ports/rp2/machine_adc.c), so raw >> 4 gives
the 12-bit code back. The ADC's reference is the Pico's 3.3 V (ADC_VREF = ADC_AVDD), so the
pin's voltage is code * 3300 / 4096 mV, and the pack's is that divided by the divider's ratio
(divider_permille: the pin's voltage per pack volt, in permille; docs/wiring.md).

The filter: a window of the last WINDOW samples (SAMPLE_FRAMES frames apart: 200 ms at 50 Hz,
so the window spans 5 x 200 = 1000 ms). A threshold is crossed downward only when the window's
MAXIMUM is below it (every sample of the last second below: a sustained sag), and upward only
when its MINIMUM is above it (every sample above). A servo's inrush pulls the pack down for a
few tens to a few hundreds of ms (a stand's soft start switches on a leg group every 160 ms;
a tripod's swing lasts 500 ms): a dip shorter than 1000 ms covers at most 5 of 6 samples and
never trips anything, whatever its depth (a low-pass filter would trip on a deep enough short
dip); a dip of 1200 ms or longer covers 6 samples and always does; 1000..1200 ms depends on
where the samples fall. The same goes for a short rise (a recharge must hold for a second).
The reaction time to a real sag is 1.0..1.2 s, which a LiPo survives easily (its cells are
hurt by hours below 3.0 V, not by a second below 3.3 V).

States (transitions only, in this order of precedence):
    any     -> CUTOFF  when the window's maximum is below cutoff_mv
    OK      -> LOW     when the window's maximum is below warn_mv
    LOW/CUTOFF -> OK   when the window's minimum is at or above resume_mv (resume > warn > cutoff)
The first reading fills the window: the state at power-up is known from the first sample.
"""

from micropython import const

OK = const(0)
LOW = const(1)
CUTOFF = const(2)
STATE_NAMES = ("ok", "low", "cutoff")
NO_CHANGE = const(-1)

SAMPLE_FRAMES = const(10)  # a reading every 10 frames: 200 ms at 50 Hz (one ADC read, ~2 us of 20 ms)
WINDOW = const(6)  # samples in the filter's window: 6 x 200 ms, spanning 1000 ms
REF_MV = const(3300)  # the RP2040 ADC's reference (the Pico's 3.3 V rail)

# Defaults for a LiPo pack, per cell (mV). LiPo cells are 4.2 V full and 3.7 V nominal; the
# usual advice (hobby chargers' and RC battery makers' storage and discharge notes) is never to
# go below 3.0 V a cell at rest and to land at 3.3 V a cell under load, which leaves about 10 %
# of the charge. Warn at 3.5 V (roughly 20 % left at rest, time to head home), cut at 3.3 V,
# and allow the robot up again only at 3.6 V: above where a rested but flat pack recovers to
# (a LiPo unloaded after a cut at 3.3 V rises by 0.1-0.2 V), so only a charged pack resumes.
CELL_FULL_MV = const(4200)  # a LiPo cell fully charged: what the divider must stay under REF_MV at
CELL_WARN_MV = const(3500)
CELL_CUTOFF_MV = const(3300)
CELL_RESUME_MV = const(3600)
CELL_MIN_MV = const(2500)  # thresholds allowed per cell: 2.5 V (Li-ion's floor) .. 4.2 V (full)
CELL_MAX_MV = const(4200)
CELLS = const(2)  # a 2S pack (7.4 V nominal, 8.4 V full) unless the board file says otherwise
CELLS_MAX = const(6)
DIVIDER_MIN = const(100)  # permille: 1:10 is the steepest divider allowed (keeps sums below 2**30)
DIVIDER_MAX = const(1000)

# In LOW, Robot.cap_speed(LOW_SPEED, LOW_YAW): walking at most 60 mm/s and 15 deg/s, half the
# tripod's 120 mm/s and 30 deg/s (docs/motion.md): slower swings draw less peak current, so the
# sag that would trip the cutoff under load comes later.
LOW_SPEED = const(600)  # 0.1 mm/s
LOW_YAW = const(1500)  # cdeg/s


class Monitor:
    """The battery state machine: update(read_u16 value) every SAMPLE_FRAMES frames."""

    def __init__(
        self,
        cells=CELLS,
        divider_permille=333,
        cell_warn_mv=CELL_WARN_MV,
        cell_cutoff_mv=CELL_CUTOFF_MV,
        cell_resume_mv=CELL_RESUME_MV,
    ):
        """Thresholds per cell (mV) as a board file gives them (hexapod.board checked them:
        cutoff < warn < resume); the pack's are cells times them."""
        check(cells, divider_permille, cell_warn_mv, cell_cutoff_mv, cell_resume_mv)
        self.cells = cells
        self.divider_permille = divider_permille
        self.warn_mv = cells * cell_warn_mv
        self.cutoff_mv = cells * cell_cutoff_mv
        self.resume_mv = cells * cell_resume_mv
        # pack mV = code12 * REF_MV * 1000 / (4096 * divider): folded into one factor, x4 for
        # precision; code12 * _k stays below 4096 * 132000 < 2**30 for divider >= 100.
        self._k = REF_MV * 4000 // divider_permille
        self._window = [0] * WINDOW
        self._at = 0
        self.samples = 0
        self.mv = 0  # the last sample, pack mV
        self.level_mv = 0  # the window's maximum: the pack without its inrush dips (status)
        self.low_mv = 0  # the window's minimum
        self.state = OK

    def to_mv(self, raw):
        """A read_u16 value (0..65535) -> pack mV."""
        return ((raw >> 4) * self._k + 8192) >> 14

    def update(self, raw):
        """One reading (read_u16, 0..65535); returns the new state when it changed, else NO_CHANGE."""
        mv = self.to_mv(raw)
        self.mv = mv
        w = self._window
        if self.samples == 0:
            for k in range(WINDOW):
                w[k] = mv
        else:
            w[self._at] = mv
        self._at += 1
        if self._at >= WINDOW:
            self._at = 0
        if self.samples < 1000000:
            self.samples += 1
        hi = lo = w[0]
        for k in range(1, WINDOW):
            v = w[k]
            if v > hi:
                hi = v
            if v < lo:
                lo = v
        self.level_mv = hi
        self.low_mv = lo
        s = self.state
        if hi < self.cutoff_mv:
            new = CUTOFF
        elif s == OK and hi < self.warn_mv:
            new = LOW
        elif s != OK and lo >= self.resume_mv:
            new = OK
        else:
            new = s
        if new == s:
            return NO_CHANGE
        self.state = new
        return new


def check(cells, divider_permille, cell_warn_mv, cell_cutoff_mv, cell_resume_mv):
    """ValueError naming the first bad value and what is allowed (the board file's "battery" keys)."""
    _int_in("cells", cells, 1, CELLS_MAX, " (LiPo cells in series)")
    _int_in("divider_permille", divider_permille, DIVIDER_MIN, DIVIDER_MAX, " (the ADC pin's voltage per pack volt)")
    for name, v in (
        ("cell_cutoff_mv", cell_cutoff_mv),
        ("cell_warn_mv", cell_warn_mv),
        ("cell_resume_mv", cell_resume_mv),
    ):
        _int_in(name, v, CELL_MIN_MV, CELL_MAX_MV, " mV a cell")
    if cell_warn_mv <= cell_cutoff_mv:
        raise ValueError(
            "cell_warn_mv: %d must be above cell_cutoff_mv %d (warn before cutting)" % (cell_warn_mv, cell_cutoff_mv)
        )
    if cell_resume_mv <= cell_cutoff_mv:
        raise ValueError(
            "cell_resume_mv: %d must be above cell_cutoff_mv %d (a recharged pack, not the one that was cut)"
            % (cell_resume_mv, cell_cutoff_mv)
        )
    if cell_resume_mv <= cell_warn_mv:
        raise ValueError(
            "cell_resume_mv: %d must be above cell_warn_mv %d (a resumed pack must not warn at once)"
            % (cell_resume_mv, cell_warn_mv)
        )
    full = cells * CELL_FULL_MV * divider_permille // 1000
    if full > REF_MV:
        raise ValueError(
            "divider_permille: %d puts %d mV on the ADC pin for a full %d-cell pack (%d mV), above the"
            " ADC's %d mV reference; allowed at most %d (e.g. 1:3, 333, for 2 cells)"
            % (divider_permille, full, cells, cells * CELL_FULL_MV, REF_MV, REF_MV * 1000 // (cells * CELL_FULL_MV))
        )


def _int_in(name, v, lo, hi, unit):
    if not isinstance(v, int) or isinstance(v, bool) or v < lo or v > hi:
        raise ValueError("%s: %r, allowed %d..%d%s" % (name, v, lo, hi, unit))


def volts(mv):
    """mV -> text in V with 2 decimals (rounded down: 6599 mV is 6.59 V, below a 6.60 V cutoff)."""
    return "%d.%02d" % (mv // 1000, mv % 1000 // 10)
