"""Flow control for one tab: the server draws only while the page keeps up.

Each draw ends with a mark the page sends back once it has applied everything before it (NiceGUI
applies a tab's messages in order). A page that falls behind (a busy machine, SwiftShader
drawing the scene on the CPU) gets fewer draws instead of a backlog: unbounded, that backlog
queued the websocket's keepalive ping behind it until uvicorn closed the socket, and the page,
too far behind for NiceGUI's history to replay, reloaded (a click in flight was lost with it).
"""

IN_FLIGHT = 4  # draws sent that the page has not yet shown: the next one waits
PATIENCE = 125  # beats skipped waiting for a mark (5 s at the player's 25): then draw anyway,
# in case a mark was lost with a socket; a page still behind gets one draw per PATIENCE beats


class Pace:
    """Counts of draws sent, seen back from the page and skipped; ready() says whether to draw."""

    def __init__(self, in_flight=IN_FLIGHT, patience=PATIENCE):
        if in_flight < 1 or patience < 1:
            raise ValueError("in_flight %r, patience %r: allowed 1 or more each" % (in_flight, patience))
        self.in_flight = in_flight
        self.patience = patience
        self.sent = 0  # the last mark sent
        self.seen = 0  # the last mark the page sent back
        self.skipped = 0  # beats not drawn, in all
        self._waited = 0  # beats not drawn since the last draw

    def ready(self):
        """True to draw this beat (then call sending()), False to skip it (counted)."""
        if self.sent - self.seen < self.in_flight or self._waited >= self.patience:
            self._waited = 0
            return True
        self._waited += 1
        self.skipped += 1
        return False

    def sending(self):
        """The mark for the draw just made: the page sends it back when shown."""
        self.sent += 1
        return self.sent

    def shown(self, mark):
        """The page has shown every draw up to mark; anything but a mark already sent is ignored
        (a page's event is input from outside)."""
        if isinstance(mark, int) and not isinstance(mark, bool) and self.seen < mark <= self.sent:
            self.seen = mark
