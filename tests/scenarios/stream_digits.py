"""drivers.stream's integer writer and its viper twin on the same rows (tests/test_console_stream.py)."""

from drivers import stream


def digits_same(rows):
    """Each row (44 ints) through stream.digits and its viper twin: [rows written the same, the
    last row's first three fields as written]."""
    from array import array

    same = 0
    a = n = None
    for row in rows:
        v = array("i", row)
        a = bytearray(531)
        c = bytearray(531)
        n = stream.digits(a, 2, v, 44)
        m = stream._digits_fast(c, 2, v, 44)
        same += n == m and a == c
    return [same, bytes(a[:n]).decode().split(" ")[1:4]]
