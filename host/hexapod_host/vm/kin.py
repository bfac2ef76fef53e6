# The `hexapod ik` / `hexapod fk` engine. Runs unchanged on CPython (imported by the CLI) and
# inside the MicroPython VM (run as a script), so both print byte-identical text.
#
#   kin.py MODE JSON COXA FEMUR TIBIA OFFSET L1 .. L6      (values on stdin)
# MODE is ik or fk (stdin: the user's words as given, each ended by a NUL byte) or ik-batch /
# fk-batch (stdin: lines of three numbers); JSON is 0 or 1; lengths in 0.1 mm, limits in cdeg.
# Input is read as bytes in chunks and cut at LINE_MAX, and only ASCII numbers are read
# (units.parse_fixed), so no input can make the two runtimes differ, raise or run out of heap.
#
# Exit status (README "Command line"): 0 all solved, 1 some refused, 2 bad input (a batch: 2
# if any line was bad, else 1 if any was refused), 3 internal error. As a script it exits with
# STATUS_BASE + status, so the host can tell an answer from the VM itself failing (exit 1).
import sys

from hexapod.leg import ANGLE_MAX, COORD_MAX, OK, Leg, describe
from hexapod.units import SHOWN_MAX, format_fixed, parse_fixed, shown

SOLVED = 0
REFUSED = 1
BAD_INPUT = 2
INTERNAL = 3
STATUS_BASE = 10
LINE_MAX = 1000  # longest batch line or value accepted, bytes
_CHUNK = 4096
_BOM = b"\xef\xbb\xbf"

NAMES = {"ik": ("x", "y", "z"), "fk": ("theta1", "theta2", "theta3")}
PLACES = {"ik": 1, "fk": 2}  # the user's mm -> 0.1 mm, degrees -> cdeg
# The input domain: |x|, |y|, |z| <= 3000 mm (the core's COORD_MAX); angles within +-360 deg.
LIMIT = {"ik": COORD_MAX, "fk": 2 * ANGLE_MAX}
UNIT = {"ik": "mm", "fk": "deg"}


def records(stream, sep, limit=LINE_MAX):
    """Yield (data, size) per sep-ended record of a byte stream; data is cut to limit bytes.

    Reads _CHUNK bytes at a time and keeps at most limit + _CHUNK, so a 100,000-digit line
    costs no more heap than a short one. A last record without sep is yielded when not empty.
    """
    pending = b""
    size = 0  # bytes of the current record so far, kept or not
    while True:
        chunk = stream.read(_CHUNK)
        if not chunk:
            break
        start = 0
        while True:
            k = chunk.find(sep, start)
            if k < 0:
                break
            if size <= limit:
                pending += chunk[start:k]
            size += k - start
            yield pending[:limit], size
            pending = b""
            size = 0
            start = k + 1
        if size <= limit:
            pending += chunk[start:]
        size += len(chunk) - start
    if size:
        yield pending[:limit], size


def _lead(c):
    """(continuation bytes, range of the first one) after a UTF-8 lead byte c, else None (RFC 3629 sec. 4)."""
    if 0xC2 <= c <= 0xDF:
        return 1, 0x80, 0xBF
    if c == 0xE0:
        return 2, 0xA0, 0xBF  # no overlong 3-byte form
    if c == 0xED:
        return 2, 0x80, 0x9F  # no surrogate
    if 0xE1 <= c <= 0xEF:
        return 2, 0x80, 0xBF
    if c == 0xF0:
        return 3, 0x90, 0xBF  # no overlong 4-byte form
    if c == 0xF4:
        return 3, 0x80, 0x8F  # nothing past U+10FFFF
    if 0xF1 <= c <= 0xF3:
        return 3, 0x80, 0xBF
    return None


def utf8_ok(b):
    """True when the bytes are well-formed UTF-8 (RFC 3629: no overlong form, surrogate or
    code point past U+10FFFF). MicroPython's decode() accepts some of those; CPython's not."""
    i = 0
    n = len(b)
    while i < n:
        if b[i] < 0x80:
            i += 1
            continue
        lead = _lead(b[i])
        if lead is None or i + lead[0] >= n or not lead[1] <= b[i + 1] <= lead[2]:
            return False
        for k in range(i + 2, i + lead[0] + 1):
            if not 0x80 <= b[k] <= 0xBF:
                return False
        i += lead[0] + 1
    return True


def raw(data):
    """Bytes quoted for a message, each byte >= 128 as \\xNN (shown() cuts it)."""
    return shown("".join([chr(c) for c in data[: SHOWN_MAX + 1]]))


def number(kind, k, word):
    """The k-th value of an ik or fk line (bytes) as a scaled integer; ValueError names it."""
    try:
        return parse_fixed(word.decode(), PLACES[kind], LIMIT[kind], UNIT[kind])
    except ValueError as err:
        raise ValueError("%s: %s" % (NAMES[kind][k], err)) from None


def three(kind, words):
    if len(words) != 3:
        raise ValueError("need 3 numbers (%s), got %d" % (" ".join(NAMES[kind]), len(words)))
    return [number(kind, 0, words[0]), number(kind, 1, words[1]), number(kind, 2, words[2])]


def _fixed3(out, i, places):
    return format_fixed(out[i], places), format_fixed(out[i + 1], places), format_fixed(out[i + 2], places)


def json_text(s):
    """A JSON string of ASCII text (what every message here is)."""
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


# Per kind: the JSON flag, the text before a refusal's reason, the answer's keys, its slot in out, decimals.
ANSWER = {
    "ik": ("reachable", "unreachable: ", ("theta1_deg", "theta2_deg", "theta3_deg"), 0, 2),
    "fk": ("within_limits", "beyond limit: ", ("x_mm", "y_mm", "z_mm"), 3, 1),
}


def solve(leg, kind, words, as_json, out, head=""):
    """(SOLVED or REFUSED, the answer line); ValueError on bad input. head starts a JSON object."""
    v = three(kind, words)
    if kind == "fk":
        code = leg.accept(v[0], v[1], v[2], out, 0)
        if code == OK:
            leg.fk(v[0], v[1], v[2], out, 3)
    else:
        code = leg.ik(v[0], v[1], v[2], out, 0)
    flag, refusal, keys, i, places = ANSWER[kind]
    if code == OK:
        a, b, c = _fixed3(out, i, places)
        if as_json:
            return SOLVED, '{%s"%s": true, "%s": %s, "%s": %s, "%s": %s}' % (
                head,
                flag,
                keys[0],
                a,
                keys[1],
                b,
                keys[2],
                c,
            )
        return SOLVED, "%s %s %s" % (a, b, c)
    reason = describe(code, leg.excess)
    if as_json:
        return REFUSED, '{%s"%s": false, "reason": %s}' % (head, flag, json_text(reason))
    return REFUSED, refusal + reason


def run_words(leg, kind, stdin, as_json, out, stdout, stderr):
    """One solve of the user's words (NUL-ended records on stdin); bad input under --json is also a
    {"error": ...} object on stdout, so a script reading JSON always gets one."""
    words = []
    try:
        for data, size in records(stdin, b"\0"):
            k = len(words)
            name = NAMES[kind][k] if k < 3 else "value %d" % (k + 1)
            if size > LINE_MAX:
                raise ValueError("%s: %s is longer than %d bytes" % (name, raw(data), LINE_MAX))
            if not utf8_ok(data):
                raise ValueError("%s: %s is not UTF-8 text" % (name, raw(data)))
            words.append(data)
        status, text = solve(leg, kind, words, as_json, out)
    except ValueError as err:
        stderr.write("hexapod: error: %s\n" % err)
        if as_json:
            stdout.write('{"error": %s}\n' % json_text(str(err)))
        return BAD_INPUT
    stdout.write(text + "\n")
    return status


def run_batch(leg, kind, stdin, as_json, out, stdout, stderr):
    """One answer line per input line; blank lines are skipped, a leading BOM dropped."""
    refused = False
    bad = False
    n = 0
    for data, size in records(stdin, b"\n"):
        n += 1
        if n == 1 and data[:3] == _BOM:
            data = data[3:]
        try:
            if size > LINE_MAX:
                raise ValueError("%s is longer than %d bytes" % (raw(data), LINE_MAX))
            if data and max(data) > 127 and not utf8_ok(data):
                raise ValueError("%s is not UTF-8 text" % raw(data))
            words = data.split()
            if not words:
                continue
            status, text = solve(leg, kind, words, as_json, out, '"line": %d, ' % n)
            refused = refused or status == REFUSED
        except ValueError as err:
            bad = True
            stderr.write("hexapod: line %d: %s\n" % (n, err))
            text = (
                '{"line": %d, "error": %s}' % (n, json_text(str(err))) if as_json else "error: line %d: %s" % (n, err)
            )
        stdout.write(text + "\n")
    return BAD_INPUT if bad else REFUSED if refused else SOLVED


def run(argv, stdin, stdout, stderr):
    """The engine on argv words (see the top of this file); stdin is a byte stream."""
    mode = argv[0]
    g = [int(w) for w in argv[2:12]]
    leg = Leg(coxa=g[0], femur=g[1], tibia=g[2], femur_offset=g[3], limits=g[4:10])
    kind = mode[:2]
    job = run_batch if mode.endswith("-batch") else run_words
    return job(leg, kind, stdin, argv[1] == "1", [0] * 6, stdout, stderr)


def main():
    try:
        status = run(sys.argv[1:], sys.stdin.buffer, sys.stdout, sys.stderr)
    except Exception as err:  # a bug: say so in one line, with its own status
        sys.stderr.write("hexapod: internal error: %s: %s\n" % (type(err).__name__, err))
        status = INTERNAL
    sys.exit(STATUS_BASE + status)


if __name__ == "__main__":
    main()
