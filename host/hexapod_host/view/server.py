"""Serve the view: the page registered, the player's task started with the server, NiceGUI run
on the address asked for (never NiceGUI's own default of every interface)."""

import ipaddress
import socket

# A tab that loses its connection (a busy machine, a laptop's sleep) gets its page back on
# reconnecting within this long, instead of a reload (NiceGUI's default is 3 s).
RECONNECT_S = 60.0


def is_loopback(host):
    """True for an address that only this machine can reach (127.x, ::1, localhost)."""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def check_free(host, port):
    """None when host:port can be listened on, else why not (the OS's words)."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            s.bind((host, port))
        except OSError as err:
            return err.strerror or str(err)
    return None


def serve(player, host, port, show, fps):
    """Run the page until Ctrl-C; the player steps its source in NiceGUI's event loop; the 3-D
    scene redraws fps times a second."""
    from nicegui import app, ui

    from hexapod_host.view import page

    page.build(player, fps)
    app.on_startup(player.run)
    app.on_shutdown(player.stop)
    ui.run(
        host=host,
        port=port,
        show=show,
        reload=False,
        title="hexapod view",
        show_welcome_message=False,
        uvicorn_logging_level="warning",
        reconnect_timeout=RECONNECT_S,
    )
    interrupted()


def interrupted():
    """Raise KeyboardInterrupt if the server stopped for a Ctrl-C. Uvicorn takes SIGINT, shuts down
    and raises it again on its way out, but that raise lands in asyncio's runner, and once in a CI
    run (tests/test_view_record.py) the command then returned as if never interrupted (exit 0, not
    the CLI's 130)."""
    import signal

    from nicegui.server import Server

    server = getattr(Server, "instance", None)
    if signal.SIGINT in getattr(server, "_captured_signals", ()):
        raise KeyboardInterrupt
