"""Pins on wires that chip models drive: Pin, time_pulse_us, WDT, freq, reset_cause, unique_id.

Every Pin built with the same id shares one wire, so a model connected to pin 7 sees the
driver's Pin(7) writes and answers its reads. A model is any object with three methods:
  pin_written(pin_id, level)       the board drove an output pin (level 0/1) at now_us()
  level(pin_id, t_us)              the level the model drives at t_us, or -1 if it does not
  next_change(pin_id, t_us)        first instant > t_us (unwrapped us) its level changes, or -1
Time comes from the virtual clock (_stub_clock); time_pulse_us advances it to the edge it
waits for, so a 5 ms echo costs no real time. Pin.irq handlers run at their edges: whenever the
clock is about to move, the edges the models drive up to the new instant are visited in time
order, the clock is set to each and the handler called there (ticks_us() in it reads the edge's
instant, as a board's IRQ would, minus the latency). Nothing on a read, write or IRQ path allocates.
"""

import _stub_clock as clock

PWRON_RESET = 1
HARD_RESET = 2
WDT_RESET = 3
DEEPSLEEP_RESET = 4
SOFT_RESET = 5

_UNIQUE_ID = b"\xe6\x61\x41\x04\x03\x2c\x8b\x2f"  # what a Pico's flash id looks like: 8 bytes

_wires = {}
_state = {"freq": 125000000, "reset_cause": PWRON_RESET}


class _Wire:
    """What every Pin object with one id shares."""

    def __init__(self, pin_id):
        self.pin_id = pin_id
        self.mode = -1
        self.pull = -1
        self.out = 0  # last level written by the board
        self.forced = -1  # a level a test holds the line at, -1 when released
        self.model = None
        self.handler = None  # Pin.irq's handler, called with irq_pin at each edge in irq_trigger
        self.irq_pin = None
        self.irq_trigger = 0
        self.irq_t = 0  # unwrapped us up to which this wire's edges were handled


def _wire(pin_id):
    w = _wires.get(pin_id)
    if w is None:
        w = _Wire(pin_id)
        _wires[pin_id] = w
    return w


def connect(pin_id, model):
    """Attach a chip model to pin_id; one model per pin."""
    w = _wire(pin_id)
    if w.model is not None and w.model is not model:
        raise ValueError("pin %r is already connected to %r" % (pin_id, w.model))
    before = _read(w, clock.now_us())
    w.model = model
    _step(w, before)


def disconnect(pin_id):
    """Unplug whatever model drives pin_id (the line floats to its pull)."""
    w = _wire(pin_id)
    before = _read(w, clock.now_us())
    w.model = None
    _step(w, before)


def force(pin_id, level):
    """Hold an input line at level 0/1 by hand; -1 releases it."""
    w = _wire(pin_id)
    before = _read(w, clock.now_us())
    w.forced = level
    _step(w, before)


def _step(w, before):
    # A line that a hand or a plug moved at once: an edge now, for its IRQ handler as any other.
    lv = _read(w, clock.now_us())
    if lv != before and w.handler is not None and w.irq_trigger & (Pin.IRQ_RISING if lv else Pin.IRQ_FALLING):
        w.handler(w.irq_pin)


_irq_wires = []  # wires with an IRQ handler, in the order they got one


def _dispatch(t_end):
    """Run the IRQ handlers of every edge up to t_end (unwrapped us) at its instant, in order."""
    start = clock._now  # edges up to here were handled when time got here (or skipped by a clock reset)
    while True:
        first = None
        t = -1
        for w in _irq_wires:
            e = _next_change(w, w.irq_t if w.irq_t > start else start)
            if 0 <= e <= t_end and (first is None or e < t):
                first = w
                t = e
        if first is None:
            return
        first.irq_t = t
        clock._now = t
        lv = _read(first, t)
        if first.irq_trigger & (Pin.IRQ_RISING if lv else Pin.IRQ_FALLING):
            first.handler(first.irq_pin)


def reset():
    """Forget every wire, model and IRQ handler, restore freq and reset cause (between tests)."""
    _wires.clear()
    _irq_wires.clear()
    clock._edge_hook = None
    _state["freq"] = 125000000
    _state["reset_cause"] = PWRON_RESET


def _read(w, t_us):
    if w.mode == Pin.OUT:
        return w.out
    if w.forced >= 0:
        return w.forced
    if w.model is not None:
        lv = w.model.level(w.pin_id, t_us)
        if lv >= 0:
            return lv
    return 1 if w.pull == Pin.PULL_UP else 0


def _next_change(w, t_us):
    if w.mode == Pin.OUT or w.forced >= 0 or w.model is None:
        return -1
    return w.model.next_change(w.pin_id, t_us)


def next_edge(pin_id, t_us):
    """Unwrapped us of the line's next level change after t_us, -1 if none (for fake peripherals)."""
    return _next_change(_wire(pin_id), t_us)


def level(pin_id):
    """The level on pin_id now, as the board would read it (for tests)."""
    return _read(_wire(pin_id), clock.now_us())


class Pin:
    """machine.Pin on a shared wire; id is any hashable (GPIO number or a name)."""

    IN = 0
    OUT = 1
    OPEN_DRAIN = 2
    ALT = 3
    PULL_UP = 1
    PULL_DOWN = 2
    IRQ_RISING = 1
    IRQ_FALLING = 2

    def __init__(self, id, mode=-1, pull=-1, value=None):
        self.id = id
        self._w = _wire(id)
        self.init(mode, pull, value)

    def init(self, mode=-1, pull=-1, value=None):
        """Change mode/pull/output level; -1 keeps the current setting."""
        if mode not in (-1, Pin.IN, Pin.OUT, Pin.OPEN_DRAIN, Pin.ALT):
            raise ValueError("Pin %r: mode %r, allowed IN, OUT, OPEN_DRAIN, ALT" % (self.id, mode))
        if pull not in (-1, None, Pin.PULL_UP, Pin.PULL_DOWN):
            raise ValueError("Pin %r: pull %r, allowed None, PULL_UP, PULL_DOWN" % (self.id, pull))
        if value is not None:
            self._w.out = 1 if value else 0
        if mode != -1:
            self._w.mode = mode
        if pull != -1:
            self._w.pull = -1 if pull is None else pull
        if value is not None and self._w.mode == Pin.OUT and self._w.model is not None:
            self._w.model.pin_written(self.id, self._w.out)

    def value(self, v=None):
        """Read the line (no argument) or drive it to 0/1."""
        w = self._w
        if v is None:
            return _read(w, clock.now_us())
        w.out = 1 if v else 0
        if w.mode == Pin.OUT and w.model is not None:
            w.model.pin_written(self.id, w.out)
        return None

    def __call__(self, v=None):
        return self.value(v)

    def on(self):
        self.value(1)

    def off(self):
        self.value(0)

    def high(self):
        self.value(1)

    def low(self):
        self.value(0)

    def toggle(self):
        self.value(1 - self._w.out)

    def irq(self, handler=None, trigger=3, hard=False):
        """Call handler(pin) at each edge in trigger (IRQ_RISING | IRQ_FALLING) of this input from
        now on, at the edge's instant on the virtual clock; handler None removes it. hard is
        accepted and ignored (a stub handler runs like a hard one: it must not sleep)."""
        if handler is not None and not callable(handler):
            raise ValueError("Pin %r: irq handler %r, allowed a callable or None" % (self.id, handler))
        if not isinstance(trigger, int) or isinstance(trigger, bool) or trigger < 1 or trigger > 3:
            raise ValueError(
                "Pin %r: irq trigger %r, allowed IRQ_RISING, IRQ_FALLING or both (1..3)" % (self.id, trigger)
            )
        w = self._w
        w.handler = handler
        w.irq_pin = self
        w.irq_trigger = trigger
        w.irq_t = clock.now_us()
        if handler is None:
            if w in _irq_wires:
                _irq_wires.remove(w)
        elif w not in _irq_wires:
            _irq_wires.append(w)
        clock._edge_hook = _dispatch if _irq_wires else None
        return self

    def __repr__(self):
        return "Pin(%r)" % (self.id,)


def time_pulse_us(pin, pulse_level, timeout_us=1000000):
    """Width in us of the next pulse at pulse_level; -2 if it never starts, -1 if too long.

    As MicroPython's: if the line already sits at pulse_level the timing starts at once;
    each phase (waiting for the start, timing the pulse) gives up after timeout_us, and the
    virtual clock advances by exactly what a board would have spent.
    """
    w = pin._w
    t0 = clock.now_us()
    if _read(w, t0) != pulse_level:
        e = _next_change(w, t0)
        if e < 0 or e - t0 >= timeout_us:
            clock.advance_to(t0 + timeout_us)
            return -2
        clock.advance_to(e)
    start = clock.now_us()
    e = _next_change(w, start)
    if e < 0 or e - start >= timeout_us:
        clock.advance_to(start + timeout_us)
        return -1
    clock.advance_to(e)
    return e - start


class WDT:
    """Watchdog on the virtual clock; `expired()` says whether a board would have reset."""

    def __init__(self, id=0, timeout=5000):
        if not isinstance(timeout, int) or timeout < 1 or timeout > 8388:
            # 8388 ms is the rp2's longest; esp32 allows more, the smaller limit keeps boards portable
            raise ValueError("WDT timeout: %r ms, allowed 1..8388" % (timeout,))
        self.timeout_ms = timeout
        self._fed = clock.now_us()

    def feed(self):
        self._fed = clock.now_us()

    def expired(self):
        """True once more than timeout_ms passed since the last feed."""
        return clock.now_us() - self._fed > self.timeout_ms * 1000


def freq(hz=None):
    """CPU frequency in Hz: read, or set (stored only)."""
    if hz is None:
        return _state["freq"]
    if not isinstance(hz, int) or hz < 1000000 or hz > 300000000:
        raise ValueError("freq: %r Hz, allowed 1000000..300000000" % (hz,))
    _state["freq"] = hz
    return None


def reset_cause():
    return _state["reset_cause"]


def set_reset_cause(cause):
    """Test hook: what reset_cause() reports after the next 'boot'."""
    _state["reset_cause"] = cause


def unique_id():
    return _UNIQUE_ID


def idle():
    """Nothing to wait for: the virtual clock moves only when told."""


def disable_irq():
    return 0


def enable_irq(state=0):
    return None


def lightsleep(ms=0):
    clock.sleep_ms(ms)
