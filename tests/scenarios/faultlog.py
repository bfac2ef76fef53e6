"""The fault log (hexapod.faultlog) and its keepers (drivers.faultkeep) on both runtimes, with
stand-ins for machine.mem32 and machine.RTC that hold what was written where."""

from scenarios.heap import heap_bytes

from drivers import faultkeep
from hexapod import faultlog


class Mem32:
    """machine.mem32 stand-in: a dict of address -> word; unwritten addresses read `fill`."""

    def __init__(self, fill=0):
        self.cells = {}
        self.fill = fill

    def __getitem__(self, addr):
        return self.cells.get(addr, self.fill)

    def __setitem__(self, addr, value):
        self.cells[addr] = value


class Rtc:
    """machine.RTC stand-in: memory() reads, memory(buf) keeps a copy."""

    def __init__(self, data=b""):
        self.data = bytearray(data)

    def memory(self, buf=None):
        if buf is None:
            return bytes(self.data)
        if len(self.data) != len(buf):
            self.data = bytearray(len(buf))
        for i in range(len(buf)):  # a copy, as the port's memcpy into RTC RAM, without a heap object
            self.data[i] = buf[i]


def entries(log):
    return [list(log.entry(i)) for i in range(log.count())]


def pushes(records):
    """[(words, entries) after each record] in a log without a keeper."""
    log = faultlog.FaultLog()
    out = []
    for kind, what, frame in records:
        log.record(kind, what, frame)
        out.append([list(log.words), entries(log)])
    return out


def scratch(records, fill=0, preset=()):
    """Record into a log kept in Mem32 (preset: (address, word) written first, as a reset leaves
    them): [the cells written, a second log's (kept, entries) loaded from the same cells]."""
    mem = Mem32(fill)
    for a, w in preset:
        mem[a] = w
    log = faultlog.FaultLog(faultkeep.Rp2Scratch(mem))
    first = [log.kept, entries(log)]
    for kind, what, frame in records:
        log.record(kind, what, frame)
    again = faultlog.FaultLog(faultkeep.Rp2Scratch(mem))
    return [first, [list(c) for c in sorted(mem.cells.items())], again.kept, entries(again)]


def rtc(records, data=b""):
    """Record into a log kept in an Rtc: [its memory bytes, a second log's entries]."""
    r = Rtc(data)
    log = faultlog.FaultLog(faultkeep.RtcMemory(r))
    for kind, what, frame in records:
        log.record(kind, what, frame)
    again = faultlog.FaultLog(faultkeep.RtcMemory(r))
    return [list(r.data), again.kept, entries(again)]


def kept_then_new(n_new):
    """4 faults kept from before a reset, then n_new new ones: (kept, entries)."""
    mem = Mem32()
    log = faultlog.FaultLog(faultkeep.Rp2Scratch(mem))
    for k in range(4):
        log.record(faultlog.SONAR, k, 100 + k)
    log = faultlog.FaultLog(faultkeep.Rp2Scratch(mem))
    for k in range(n_new):
        log.record(faultlog.I2C, 1, 7 + k)
    return [log.kept, entries(log)]


def record_heap(keeper):
    """Heap bytes left by 10 records (and a clear) with a keeper ('rp2', 'rtc', None)."""
    k = {"rp2": faultkeep.Rp2Scratch(Mem32()), "rtc": faultkeep.RtcMemory(Rtc()), None: None}[keeper]
    log = faultlog.FaultLog(k)
    log.record(faultlog.I2C, 0, 1)  # the stand-ins' first store makes their dict entry / bytes

    def ten(lg):
        for i in range(10):
            lg.record(faultlog.SONAR, i & 7, 1000 + i)

    return heap_bytes(ten, log)


def on_the_board(plan):
    """The stub board's loop (scenarios.selftest.Board, console attached) run frame by frame with
    faults put into the models at given frames. plan: [(frame, action)], actions "unplug_0x41",
    "replug_0x41", "reset_0x41", "mute_2", "unmute_2", "wdt", "clear". Runs 60 frames; returns
    [the `faults` reply, each action's frame as the runner counted it, the log's words]."""
    from scenarios.selftest import Board

    b = Board()
    todo = dict(plan)
    for n in range(60):
        a = todo.get(n)
        if a == "unplug_0x41":
            b.bus.detach(0x41)
        elif a == "replug_0x41":
            b.bus.attach(b.chips[0x41])
        elif a == "reset_0x41":
            b.chips[0x41].reset()
        elif a == "mute_2":
            b.sonars[2].missing_echo = True
        elif a == "unmute_2":
            b.sonars[2].missing_echo = False
        elif a == "wdt":
            b.r.note_reset(True)
        elif a == "clear":
            b.say("faults clear", end="ok faults")
            continue
        b.frame()
    lines, _ = b.say("faults", end="ok faults")
    return [lines, list(b.r.faultlog.words)]


def refused(lines):
    """Each bad `faults` line's reply, and whether the log's words stayed the same."""
    from scenarios.selftest import Board

    b = Board()
    b.bus.detach(0x41)
    for _ in range(3):
        b.frame()
    before = list(b.r.faultlog.words)
    out = []
    for line in lines:
        got, _ = b.say(line, end="ok faults")
        out.append(got)
    return [out, before == list(b.r.faultlog.words), before != [0, 0, 0, 0]]
