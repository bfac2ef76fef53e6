"""The jog tool's terminal: curses draws jog.render's lines and turns key presses into jog keys."""

import curses
import os

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


# Keys at the prompt -> jog.prompt_key's names; any other code below 32 is dropped there.
PROMPT_KEYS = {10: "ENTER", 13: "ENTER", curses.KEY_ENTER: "ENTER", 27: "ESC", 3: "CTRL-C"}
PROMPT_KEYS.update({8: "BACKSPACE", 127: "BACKSPACE", curses.KEY_BACKSPACE: "BACKSPACE"})


def prompt_name(code):
    """A curses key code as jog.prompt_key takes it ('' for a key with no character)."""
    if code in PROMPT_KEYS:
        return PROMPT_KEYS[code]
    return chr(code) if 0 <= code < 256 else ""


def ask(screen, prompt):
    """A line typed at the bottom of the screen: Enter sends it, Esc or Ctrl-C drops it (raw mode,
    loop(): Ctrl-C comes here as a key, not a signal) and no control key reaches the board
    (jog.prompt_key)."""
    height, width = screen.getmaxyx()
    curses.curs_set(1)
    text, state = "", None
    try:
        while state is None:
            screen.move(height - 1, 0)
            screen.clrtoeol()
            screen.addnstr(height - 1, 0, prompt + text, width - 1)
            screen.refresh()
            text, state = jog.prompt_key(text, prompt_name(screen.getch()))
        return text if state == "done" else ""
    finally:
        curses.curs_set(0)


# Keys on the guided screen -> guided.Guide's names: Enter goes on, Esc (or Ctrl-C) quits it.
GUIDE_KEYS = {10: "ENTER", 13: "ENTER", curses.KEY_ENTER: "ENTER", 27: "ESC", 3: "ESC"}


def guide_key(tool, code):
    if code in GUIDE_KEYS:
        tool.key(GUIDE_KEYS[code])
    elif 0 <= code < 256:
        tool.key(chr(code))


def loop(screen, tool, port, guided_first=False):
    # Raw mode throughout: Ctrl-C (and Ctrl-Z, Ctrl-\\) arrive as keys, never as signals, so no
    # key press races the prompt's own handling; on the jog screen Ctrl-C quits as q does.
    curses.raw()
    curses.curs_set(0)
    screen.keypad(True)
    tool.start()
    if guided_first and tool.view.connected:
        tool.key("G")
    while not tool.view.quit:
        draw(screen, tool.screen(port))
        code = screen.getch()
        if tool.guide is not None:
            guide_key(tool, code)
        elif code == 3:
            tool.key("q")
        elif code == ord(":"):
            tool.line(ask(screen, ": "))
        elif code in SPECIAL:
            tool.key(SPECIAL[code])
        elif 0 <= code < 256:
            tool.key(chr(code))


def run(tool, port, guided_first=False):
    os.environ.setdefault("ESCDELAY", "25")  # Esc quits the guide at once, not after curses' 1 s
    curses.wrapper(loop, tool, port, guided_first)
