"""A console reader for the stub board (tests, host benches): bytes handed in, read back one at a
time. Here, not in console.py: a board's resident heap keeps no test code."""


class BufferReader:
    """Bytes handed in (feed()), read back one at a time: a console's read_byte()."""

    def __init__(self, data=b""):
        self.data = bytearray(data)
        self.pos = 0

    def feed(self, data):
        self.data.extend(data)

    def read_byte(self):
        if self.pos >= len(self.data):
            return -1
        self.pos += 1
        return self.data[self.pos - 1]
