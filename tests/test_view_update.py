"""How the view's redraws follow the player (issue 23's update rate): every tab redraws right
after each snapshot the player publishes (player.listeners), a tab whose redraw fails is dropped
without stopping the source, and scene numbers go out rounded to 0.1 mm, so a link whose length
does not change is not rescaled."""

import math

from hexapod_host.view import page
from hexapod_host.view.player import Player
from tests.test_view import Counter


def test_listeners_hear_every_snapshot_and_a_failing_one_is_dropped(capsys):
    p = Player(Counter())
    heard, calls = [], []

    def broken():
        calls.append(p.snap["frame"])
        raise RuntimeError("a tab's redraw failed")

    p.listeners += [lambda: heard.append(p.snap["frame"]), broken]
    p.advance(0.04)  # two 20 ms frames, one snapshot
    p.advance(0.04)
    p.pause()
    p.step()
    assert heard == [2, 4, 5] and calls == [2]  # the broken one once, then dropped
    assert p.source.n == 5  # the source went on
    assert "a page stopped following the player" in capsys.readouterr().err


class Obj:
    """A scene object that keeps the last values it was given."""

    def move(self, *v):
        self.centre = list(v)
        return self

    def rotate_R(self, r):
        self.rot = r
        return self

    def scale(self, *v):
        self.size = list(v)
        return self


def test_scene_numbers_are_rounded_to_a_tenth_of_a_millimetre():
    a, b = Obj(), Obj()
    # An 85 mm femur at 30 degrees, in two places 0.00001 mm apart (float noise in the last digits).
    c, s = 85 * math.cos(math.pi / 6), 85 * math.sin(math.pi / 6)
    page._place(a, [100.0, 20.0, 50.0], [100.0 + c, 20.0, 50.0 + s])
    page._place(b, [100.00001, 20.0, 50.0], [100.00001 + c, 20.0, 50.0 + s])
    assert a.size == b.size == [1.0, 0.085, 1.0]
    assert a.centre == b.centre == [round(0.1 + c / 2000, 4), 0.02, round(0.05 + s / 2000, 4)] == [0.1368, 0.02, 0.0713]
    assert a.rot == b.rot
    assert all(v == round(v, 4) for row in a.rot for v in row)
    assert page._m([1234.56789, -0.04, 80.0]) == [1.2346, -0.0, 0.08]


class Cloud:
    """A point cloud that keeps what it was sent."""

    def __init__(self):
        self.sent = []

    def set_points(self, points):
        self.sent.append(points)

    def material(self, *_):
        return self


class Scene:
    def __init__(self):
        self.clouds = []

    def __enter__(self):
        return self

    def __exit__(self, *_):
        pass

    def point_cloud(self, points, point_size):
        self.clouds.append(Cloud())
        return self.clouds[-1]


def test_a_growing_trail_resends_only_its_newest_cloud():
    view = type("V", (), {"trails": [], "trail_n": 0, "scene": Scene()})()
    trail = [(float(k), 0.0) for k in range(120)]  # 120 points, 1 mm apart
    page.View._draw_trail(view, trail)
    clouds = view.scene.clouds
    assert [len(c.sent[-1]) for c in clouds] == [50, 50, 20]  # TRAIL_CHUNK points each
    assert clouds[2].sent[-1][0] == [0.1, 0.0, 0.002] and clouds[2].sent[-1][-1] == [0.119, 0.0, 0.002]
    page.View._draw_trail(view, trail + [(120.0, 0.0)])
    assert [len(c.sent) for c in clouds] == [1, 1, 2] and len(clouds[2].sent[-1]) == 21  # only the third again
    page.View._draw_trail(view, trail[:10])  # a new trial: the trail starts over
    assert [c.sent[-1] for c in clouds[1:]] == [[], []] and len(clouds[0].sent[-1]) == 10
