"""The jog tool's terminal: curses draws jog.render's lines and turns key presses into jog keys."""

import curses

from hexapod_host.serial import jog

# curses key codes -> the command layer's key names
SPECIAL = {
    curses.KEY_UP: "UP",
    curses.KEY_DOWN: "DOWN",
    curses.KEY_LEFT: "LEFT",
    curses.KEY_RIGHT: "RIGHT",
    curses.KEY_PPAGE: "PGUP",
    curses.KEY_NPAGE: "PGDN",
}


def draw(screen, lines):
    screen.erase()
    height, width = screen.getmaxyx()
    for row, text in enumerate(lines[: height - 1]):
        screen.addnstr(row, 0, text, width - 1)
    screen.refresh()


def ask(screen, prompt):
    """A line typed at the bottom of the screen (Enter ends it)."""
    height, width = screen.getmaxyx()
    screen.move(height - 1, 0)
    screen.clrtoeol()
    screen.addnstr(height - 1, 0, prompt, width - 1)
    curses.echo()
    curses.curs_set(1)
    try:
        return screen.getstr(height - 1, len(prompt), 95).decode(errors="replace")
    finally:
        curses.noecho()
        curses.curs_set(0)


def loop(screen, tool, port):
    curses.curs_set(0)
    screen.keypad(True)
    tool.start()
    while not tool.view.quit:
        draw(screen, jog.render(tool.view, port))
        code = screen.getch()
        if code == ord(":"):
            tool.line(ask(screen, ": "))
        elif code in SPECIAL:
            tool.key(SPECIAL[code])
        elif 0 <= code < 256:
            tool.key(chr(code))


def run(tool, port):
    curses.wrapper(loop, tool, port)
